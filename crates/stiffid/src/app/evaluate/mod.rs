//! The evaluate job: every design criterion of a group of postures (Zhang et al. 2021, Eq.
//! 19-21, and the criteria beyond the paper, [`crate::design::criteria`]), its predicted
//! deviation rates, each posture's feasibility in the cell, and which parameters of the setup's
//! model the group identifies.

pub mod document;

use super::Warning;
use crate::cell::{Checker, Feasibility};
use crate::design::{evaluate, unidentifiable, Evaluation};
use crate::math::lsq::Factor;
use crate::observation::rope_observation_matrix;
use crate::{Result, Setup};
use nalgebra::Vector6;

/// The group to evaluate.
pub struct Request<'a> {
    /// The setup: robot, tool, load, noise, nominal stiffness, cell, model.
    pub setup: &'a Setup,
    /// The group: axis angles (rad), within the setup's bounds.
    pub postures: &'a [Vector6<f64>],
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
    /// None today: the job's warnings, for the pattern ([`crate::app`]).
    pub warnings: Vec<Warning>,
}

/// Evaluates the group.
///
/// # Errors
/// For the drives alone, [`Error::Unidentifiable`] naming the joints when the group's observation
/// matrix cannot identify every joint (a model with virtual springs reports what it cannot
/// separate in [`Report::unidentifiable`] instead).
pub fn run(request: &Request) -> Result<Report> {
    let (setup, postures) = (request.setup, request.postures);
    setup.check_bodies()?;
    if setup.model().is_drives_only() {
        Factor::try_new(rope_observation_matrix(setup, postures))?;
    }
    let evaluation = evaluate(setup, postures);
    let checker = Checker::new(setup);
    Ok(Report {
        feasibility: postures.iter().map(|q| checker.feasibility(q)).collect(),
        unidentifiable: unidentifiable(&evaluation, setup),
        evaluation,
        warnings: Vec::new(),
    })
}
