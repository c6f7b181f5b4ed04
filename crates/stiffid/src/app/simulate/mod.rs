//! The simulate job: Monte Carlo identification with groups of postures at every noise level of
//! the setup, beside the first-order prediction (Zhang et al. 2021, Section IV-A;
//! [`stiffid_design::study::simulate`]), over every parameter of the setup's model (the drives and its virtual
//! springs, each with its nominal stiffness as the truth).

pub mod document;

use crate::app::Warning;
use nalgebra::Vector6;
use stiffid_core::common::progress::Progress;
use stiffid_core::model::Parameter;
use stiffid_core::{common::limits, Result, Setup};
use stiffid_design::study::simulate::{monte_carlo_reporting, GroupSimulation, Options};

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
    /// Told of one stage, `Monte Carlo identification`, one unit per run (groups x levels x
    /// runs); `&()` for none.
    pub progress: &'a dyn Progress,
}

/// What the simulation found.
#[derive(Debug, Clone)]
pub struct Report {
    /// The groups' names, in order.
    pub names: Vec<String>,
    /// Each group's simulation, in order.
    pub simulations: Vec<GroupSimulation>,
    /// The parameters simulated (the six drives, then the model's virtual springs), in the order
    /// of the rates' columns.
    pub parameters: Vec<Parameter>,
    /// Runs per group and level.
    pub runs: usize,
    /// The seed of the noise.
    pub seed: u64,
    /// None today: the job's warnings, for the pattern ([`crate::app`]).
    pub warnings: Vec<Warning>,
}

/// The simulate job's report and its document.
pub type Outcome = crate::app::Outcome<Report, document::Document>;

/// Simulates every group.
///
/// # Errors
/// [`stiffid_core::Error::InvalidField`] (`groups`) for no group or more than [`limits::MAX_GROUPS`]; the
/// errors of [`monte_carlo`](stiffid_design::study::simulate::monte_carlo) (among them a virtual spring without a nominal stiffness, the
/// truth of the simulation, and a group that cannot identify every parameter of the model).
pub fn run(request: &Request) -> Result<Outcome> {
    let report = find(request)?;
    let document = document::Document::new(&report, request.setup);
    Ok(Outcome { report, document })
}

/// What [`run`] finds, before its document.
fn find(request: &Request) -> Result<Report> {
    let progress = request.progress;
    let setup = request.setup;
    setup.require_loading("simulate (the rope load of every posture)")?;
    limits::check_count("groups", request.groups.len(), 1, limits::MAX_GROUPS)?;
    let groups: Vec<Vec<Vector6<f64>>> =
        request.groups.iter().map(|g| g.postures.clone()).collect();
    Ok(Report {
        names: request.groups.iter().map(|g| g.name.clone()).collect(),
        simulations: monte_carlo_reporting(setup, &groups, &request.options, progress)?,
        parameters: setup.model().parameters(),
        runs: request.options.runs,
        seed: request.options.seed,
        warnings: Vec::new(),
    })
}
