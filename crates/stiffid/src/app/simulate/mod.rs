//! The simulate job: Monte Carlo identification with groups of postures at every noise level of
//! the setup, beside the first-order prediction (Zhang et al. 2021, Section IV-A;
//! [`stiffid_design::study::simulate`]), over every parameter of the setup's model (the drives and its virtual
//! springs, each with its nominal stiffness as the truth).

pub mod document;

use crate::app::document::group::Group as Rates;
use crate::app::Warning;
use nalgebra::Vector6;
use serde::Serialize;
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

/// What the simulation found. It is its own document (`stiffid simulate --json`, `--out
/// DIR/simulation.json`, Python's `simulate`): every field it writes is a count or a rate, with
/// no unit to convert; each group's part
/// ([`Group`](crate::app::document::group::Group)) as the study's summary has it too.
#[derive(Debug, Clone, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "simulate")]
#[cfg_attr(feature = "schema", schemars(description = "The simulate document."))]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("simulate")))]
pub struct Report {
    /// The setup's name.
    pub setup: String,
    /// The seed of the measurement noise.
    pub seed: u64,
    /// Monte Carlo runs per group and noise level.
    pub runs: usize,
    /// The noise level multiples of the setup's variance.
    pub levels: Vec<f64>,
    /// The parameters simulated, in the order of the rates' columns.
    #[serde(serialize_with = "document::named")]
    #[cfg_attr(feature = "schema", schemars(with = "Vec<document::Named>"))]
    pub parameters: Vec<Parameter>,
    /// One per group, in the order given.
    pub groups: Vec<Rates>,
    /// Each group's simulation, in the order given (for `deviation_rates.csv`,
    /// [`document::deviation_csv`]).
    #[serde(skip)]
    pub simulations: Vec<GroupSimulation>,
    /// None today: the job's warnings, for the pattern ([`crate::app`]).
    #[serde(skip)]
    pub warnings: Vec<Warning>,
}

/// The simulate job's report, which is its document.
pub(crate) type Outcome = crate::app::Outcome<Report>;

/// Simulates every group.
///
/// # Errors
/// [`stiffid_core::Error::InvalidField`] (`groups`) for no group or more than [`limits::MAX_GROUPS`]; the
/// errors of [`monte_carlo`](stiffid_design::study::simulate::monte_carlo) (among them a virtual spring without a nominal stiffness, the
/// truth of the simulation, and a group that cannot identify every parameter of the model).
pub fn run(request: &Request) -> Result<Outcome> {
    Ok(Outcome {
        report: find(request)?,
        document: crate::app::Itself,
    })
}

/// What [`run`] finds, before its document.
fn find(request: &Request) -> Result<Report> {
    let progress = request.progress;
    let setup = request.setup;
    setup.require_loading("simulate (the rope load of every posture)")?;
    limits::check_count("groups", request.groups.len(), 1, limits::MAX_GROUPS)?;
    let groups: Vec<Vec<Vector6<f64>>> =
        request.groups.iter().map(|g| g.postures.clone()).collect();
    let simulations = monte_carlo_reporting(setup, &groups, &request.options, progress)?;
    let parameters = setup.model().parameters();
    Ok(Report {
        setup: setup.name().into(),
        seed: request.options.seed,
        runs: request.options.runs,
        levels: setup.noise().levels.clone(),
        groups: (request.groups.iter().zip(&simulations))
            .map(|(g, s)| Rates::new(&g.name, s, &parameters))
            .collect(),
        parameters,
        simulations,
        warnings: Vec::new(),
    })
}
