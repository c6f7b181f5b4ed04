//! The evaluate job: every design criterion of a group of postures (Zhang et al. 2021, Eq.
//! 19-21, and the criteria beyond the paper, [`stiffid_design::criteria`]), its predicted
//! deviation rates, each posture's feasibility in the cell, which parameters of the setup's
//! model the group identifies, and which candidates of the model comparison it identifies
//! together with the model ([`stiffid_design::candidates`]).

use super::purpose::{self, CalibrationOptions, Purpose};
use crate::app::document::{candidates, feasibility, group};
use crate::app::Warning;
use nalgebra::Vector6;
use serde::Serialize;
use stiffid_core::cell::{Checker, Feasibility};
use stiffid_core::common::error::JobOption;
use stiffid_core::math::lsq::Factor;
use stiffid_core::observation::rope_observation_matrix;
use stiffid_core::{Error, Result, Setup};
use stiffid_design::candidates::{pool, verdicts, Verdicts};
use stiffid_design::criteria::ParameterQuality;
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

/// What the evaluation found. It is its own document (`stiffid evaluate --json`, Python's
/// `Setup.evaluate`): the criteria, every posture's feasibility in the cell, and how well the
/// group identifies each parameter, its SI values written in the document's units by the parts
/// of [`crate::app::document::group`], [`crate::app::document::feasibility`] and
/// [`crate::app::document::candidates`].
#[derive(Debug, Clone, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "evaluate")]
#[cfg_attr(
    feature = "schema",
    schemars(
        description = "The evaluate document: the criteria, every posture's feasibility in the cell, and how well the\ngroup identifies each parameter."
    )
)]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("evaluate")))]
pub struct Report {
    /// Every criterion, the relative standard deviations and the predicted deviation rates.
    #[serde(flatten, serialize_with = "group::criteria")]
    #[cfg_attr(feature = "schema", schemars(with = "group::Criteria"))]
    pub evaluation: Evaluation,
    /// Every posture's checks in the cell, in the order of the group.
    #[serde(serialize_with = "feasibility::each")]
    #[cfg_attr(feature = "schema", schemars(with = "Vec<feasibility::Posture>"))]
    pub feasibility: Vec<Feasibility>,
    /// Every parameter of the setup's model, drives first: whether the group identifies it and
    /// how well.
    #[serde(serialize_with = "group::parameters")]
    #[cfg_attr(feature = "schema", schemars(with = "Vec<group::Parameter>"))]
    pub parameters: Vec<ParameterQuality>,
    /// The combinations of parameters the group cannot separate (e.g. `0.71 k6 - 0.71 twin6`);
    /// empty when it identifies every parameter.
    pub unidentifiable: Vec<String>,
    /// With `--for calibration` or `both`: the group's calibration criteria.
    #[serde(
        skip_serializing_if = "Option::is_none",
        serialize_with = "group::calibration"
    )]
    #[cfg_attr(feature = "schema", schemars(with = "Option<group::CalibrationDoc>"))]
    pub calibration: Option<(CalibrationOptions, CalibrationCriteria)>,
    /// Unless `--for calibration`: how the group identifies each candidate of the model
    /// comparison together with the setup's model.
    #[serde(
        skip_serializing_if = "Option::is_none",
        serialize_with = "candidates::verdicts"
    )]
    #[cfg_attr(
        feature = "schema",
        schemars(with = "Option<candidates::CandidatesDoc>")
    )]
    pub candidates: Option<Verdicts>,
    /// None today: the job's warnings, for the pattern ([`crate::app`]).
    #[serde(skip)]
    pub warnings: Vec<Warning>,
}

impl Report {
    /// The criteria as the document writes them (its `classical`, ..., `cond_psi`, the relative
    /// standard deviations, the predicted deviation rates and why a criterion is infinite).
    pub fn criteria(&self) -> group::Criteria {
        group::Criteria::of(&self.evaluation)
    }

    /// Every posture's checks in the cell as the document writes them (its `feasibility`), in
    /// the order of the group.
    pub fn postures(&self) -> Vec<feasibility::Posture> {
        feasibility::postures(&self.feasibility)
    }

    /// With the calibration: its criteria as the document writes them (its `calibration`).
    pub fn calibration_criteria(&self) -> Option<group::CalibrationDoc> {
        (self.calibration.as_ref()).map(|(o, c)| group::CalibrationDoc::new(o, c))
    }

    /// Unless for the calibration alone: how the group identifies each candidate, as the
    /// document writes it (its `candidates`).
    pub fn candidate_verdicts(&self) -> Option<candidates::CandidatesDoc> {
        self.candidates.as_ref().map(candidates::CandidatesDoc::of)
    }
}

/// Each posture's checks in the cell (the setup's bounds, floor, obstacles, self-collision,
/// rope, line of sight, incidence, `[constraints]`), as the document's `feasibility` has them:
/// what the evaluate job writes of `postures` (axis angles, rad) without its criteria.
/// Python's `Setup.feasibility`.
pub fn feasibility(setup: &Setup, postures: &[Vector6<f64>]) -> Vec<feasibility::Posture> {
    feasibility::postures(&checks(setup, postures))
}

/// Each posture's checks in the cell, in the order of `postures` (axis angles, rad).
fn checks(setup: &Setup, postures: &[Vector6<f64>]) -> Vec<Feasibility> {
    let checker = Checker::new(setup);
    postures.iter().map(|q| checker.feasibility(q)).collect()
}

/// The evaluate job's report, which is its document.
pub(crate) type Outcome = crate::app::Outcome<Report>;

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
    Ok(Outcome {
        report: find(request)?,
        document: crate::app::Itself,
    })
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
    Ok(Report {
        candidates,
        feasibility: checks(setup, postures),
        unidentifiable: unidentifiable(&evaluation, setup),
        parameters: evaluation.parameters(setup),
        evaluation,
        calibration,
        warnings: Vec::new(),
    })
}
