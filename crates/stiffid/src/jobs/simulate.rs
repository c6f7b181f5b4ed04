//! The simulate job: Monte Carlo identification with groups of postures at every noise level of
//! the setup, beside the first-order prediction (Zhang et al. 2021, Section IV-A;
//! [`crate::simulate`]).

use super::Warning;
use crate::model::Parameter;
use crate::simulate::{monte_carlo, GroupSimulation, Options};
use crate::{limits, Error, Result, Setup};
use nalgebra::Vector6;

/// A group of postures to simulate.
#[derive(Debug, Clone)]
pub struct Group {
    /// Its name in the report.
    pub name: String,
    /// Axis angles (rad), within the setup's bounds.
    pub postures: Vec<Vector6<f64>>,
}

/// What to simulate.
pub struct Request<'a> {
    /// The setup: its nominal stiffness is the true stiffness, its noise and levels the noise.
    pub setup: &'a Setup,
    /// The groups (1 to [`limits::MAX_GROUPS`]).
    pub groups: Vec<Group>,
    /// Runs per group and level, and the seed.
    pub options: Options,
}

/// What the simulation found.
#[derive(Debug, Clone)]
pub struct Report {
    /// The groups' names, in order.
    pub names: Vec<String>,
    /// Each group's simulation, in order.
    pub simulations: Vec<GroupSimulation>,
    /// The parameters simulated (the six drives), in the order of the rates' columns.
    pub parameters: Vec<Parameter>,
    /// Runs per group and level.
    pub runs: usize,
    /// The seed of the noise.
    pub seed: u64,
    /// None today: the job's warnings, for the pattern ([`crate::jobs`]).
    pub warnings: Vec<Warning>,
}

/// Simulates every group.
///
/// # Errors
/// [`Error::InvalidField`] (`groups`) for no group or more than [`limits::MAX_GROUPS`], and
/// (`model`) for a setup whose model has virtual springs (the simulation covers the six drive
/// springs); the errors of [`monte_carlo`].
pub fn run(request: &Request) -> Result<Report> {
    let setup = request.setup;
    limits::check_count("groups", request.groups.len(), 1, limits::MAX_GROUPS)?;
    if !setup.model().is_drives_only() {
        return Err(Error::InvalidField {
            field: "model".into(),
            message: format!(
                "the simulation identifies the six drive springs; the model of setup {} has virtual springs",
                limits::short(setup.name())
            ),
        });
    }
    let groups: Vec<Vec<Vector6<f64>>> =
        request.groups.iter().map(|g| g.postures.clone()).collect();
    Ok(Report {
        names: request.groups.iter().map(|g| g.name.clone()).collect(),
        simulations: monte_carlo(setup, &groups, &request.options)?,
        parameters: setup.model().parameters(),
        runs: request.options.runs,
        seed: request.options.seed,
        warnings: Vec::new(),
    })
}
