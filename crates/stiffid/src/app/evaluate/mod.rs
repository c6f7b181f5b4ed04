//! The evaluate job: every design criterion of a group of postures (Zhang et al. 2021, Eq.
//! 19-21, and the criteria beyond the paper, [`stiffid_design::criteria`]), its predicted
//! deviation rates, each posture's feasibility in the cell, which parameters of the setup's
//! model the group identifies, and which candidates of the model comparison it identifies
//! together with the model ([`stiffid_design::candidates`]).

pub mod document;

use super::purpose::{self, CalibrationOptions, Purpose};
use crate::app::Warning;
use nalgebra::Vector6;
use stiffid_core::cell::{Checker, Feasibility};
use stiffid_core::common::error::JobOption;
use stiffid_core::math::lsq::Factor;
use stiffid_core::observation::rope_observation_matrix;
use stiffid_core::{Error, Result, Setup};
use stiffid_design::candidates::{pool, verdicts, Verdicts};
use stiffid_design::observability::CalibrationCriteria;
use stiffid_design::{evaluate, unidentifiable, Evaluation};

/// The group to evaluate.
pub struct Request<'a> {
    /// The setup: robot, tool, load, noise, nominal stiffness, cell, model.
    pub setup: &'a Setup,
    /// The group: axis angles (rad), within the setup's bounds.
    pub postures: &'a [Vector6<f64>],
    /// What the group is for: with [`Purpose::Calibration`] or [`Purpose::Both`], the
    /// calibration criteria too (and for the calibration alone, no check that the group
    /// identifies the stiffness).
    pub purpose: Purpose,
    /// The calibration the group is for ([`purpose::design`]).
    pub calibration: CalibrationOptions,
    /// The candidates to judge the group for, as `identify --compare-models --candidates` names
    /// them ([`pool`]); `None` for the default pool.
    pub candidates: Option<Vec<String>>,
}

/// What the evaluation found.
#[derive(Debug, Clone)]
pub struct Report {
    /// Every criterion, the relative standard deviations and the predicted deviation rates.
    pub evaluation: Evaluation,
    /// Each posture's checks in the cell, in order.
    pub feasibility: Vec<Feasibility>,
    /// The combinations of the model's parameters the group cannot separate (empty when it
    /// identifies every parameter), e.g. `0.71 k6 - 0.71 flange_rz`.
    pub unidentifiable: Vec<String>,
    /// With [`Purpose::Calibration`] or [`Purpose::Both`]: the calibration options and the
    /// group's calibration criteria.
    pub calibration: Option<(CalibrationOptions, CalibrationCriteria)>,
    /// With a purpose with the stiffness: how the group identifies each candidate of the model
    /// comparison together with the setup's model.
    pub candidates: Option<Verdicts>,
    /// None today: the job's warnings, for the pattern ([`crate::app`]).
    pub warnings: Vec<Warning>,
}

/// The evaluate job's report and its document.
pub type Outcome = crate::app::Outcome<Report, document::Document>;

/// Evaluates the group.
///
/// # Errors
/// For the drives alone and a purpose with the stiffness, [`Error::Unidentifiable`] naming the
/// joints when the group's observation matrix cannot identify every joint (a model with virtual
/// springs reports what it cannot separate in [`Report::unidentifiable`] instead); those of
/// [`purpose::check`] (options that mean nothing for the purpose), [`Error::InvalidOption`]
/// ([`JobOption::Candidates`]) for candidates with for = calibration or check, [`purpose::design`] and
/// [`stiffid_design::observability::CalibrationDesign::evaluate`]; [`pool`]'s for the candidates; [`verdicts`]'.
pub fn run(request: &Request) -> Result<Outcome> {
    let report = find(request)?;
    let document = document::Document::new(&report, request.setup);
    Ok(Outcome { report, document })
}

/// What [`run`] finds, before its document.
fn find(request: &Request) -> Result<Report> {
    let (setup, postures) = (request.setup, request.postures);
    purpose::check(request.purpose, &request.calibration)?;
    if !request.purpose.calibration_only() {
        setup.require_loading("evaluate (the rope load of every posture)")?;
    }
    if request.candidates.is_some() && request.purpose.calibration_only() {
        return Err(Error::InvalidOption {
            option: JobOption::Candidates,
            message: "springs of the stiffness model, judged with for = stiffness or both: a group for the calibration alone identifies no spring".into(),
        });
    }
    setup.check_bodies()?;
    if setup.model().is_drives_only() && !request.purpose.calibration_only() {
        Factor::try_new(rope_observation_matrix(setup, postures))?;
    }
    let calibration = match request.purpose {
        Purpose::Stiffness => None,
        _ => {
            let options = request.calibration.of(request.purpose);
            let design = purpose::design(setup, &options)?;
            Some((options, design.evaluate(postures)?))
        }
    };
    let candidates = match request.purpose {
        Purpose::Calibration | Purpose::Check => None,
        _ => Some(verdicts(
            setup,
            postures,
            &pool(setup, request.candidates.as_deref())?,
        )?),
    };
    let evaluation = evaluate(setup, postures);
    let checker = Checker::new(setup);
    Ok(Report {
        candidates,
        feasibility: postures.iter().map(|q| checker.feasibility(q)).collect(),
        unidentifiable: unidentifiable(&evaluation, setup),
        evaluation,
        calibration,
        warnings: Vec::new(),
    })
}
