//! The document of the simulate job ([`crate::app::simulate`]): `stiffid simulate --json` (and
//! `--out DIR/simulation.json`), its `deviation_rates.csv`, Python's `simulate`; each group's part
//! ([`Group`]) as the study's summary has it too.

use crate::app::document::csv_text;
use crate::app::document::group::Group;
use crate::app::simulate::Report;
use serde::Serialize;
use stiffid_core::model::Parameter;
use stiffid_core::Setup;
use stiffid_design::study::simulate::GroupSimulation;

/// A parameter of the simulated model: its name and the unit of its stiffness.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Named {
    /// `k1` .. `k6`, then the virtual springs' names.
    pub name: String,
    /// `Nm/rad` (drives, rotations) or `N/mm` (translations).
    pub unit: &'static str,
}

impl From<&Parameter> for Named {
    fn from(p: &Parameter) -> Self {
        Self {
            name: p.name.clone(),
            unit: p.unit.symbol(),
        }
    }
}

/// The simulate document.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "simulate")]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("simulate")))]
pub struct Document {
    /// The setup's name.
    pub setup: String,
    /// The seed of the measurement noise.
    pub seed: u64,
    /// Monte Carlo runs per group and noise level.
    pub runs: usize,
    /// The noise level multiples of the setup's variance.
    pub levels: Vec<f64>,
    /// The parameters simulated, in the order of the rates' columns.
    pub parameters: Vec<Named>,
    /// One per group, in the order given.
    pub groups: Vec<Group>,
}

impl Document {
    /// The document of a simulate report on `setup`.
    pub fn new(r: &Report, setup: &Setup) -> Self {
        Self {
            setup: setup.name().into(),
            seed: r.seed,
            runs: r.runs,
            levels: setup.noise().levels.clone(),
            parameters: r.parameters.iter().map(Named::from).collect(),
            groups: (r.names.iter().zip(&r.simulations))
                .map(|(n, s)| Group::new(n, s, &r.parameters))
                .collect(),
        }
    }
}

/// `deviation_rates.csv`: one row per group, noise level and joint.
pub fn deviation_csv(names: &[String], sims: &[GroupSimulation], levels: &[f64]) -> String {
    let header = [
        "group",
        "level",
        "variance_multiple",
        "joint",
        "mean_deviation_pct",
        "std_deviation_pct",
        "predicted_deviation_pct",
        "mean_stiffness_nm_per_rad",
    ]
    .map(String::from);
    let mut rows = Vec::new();
    for (name, sim) in names.iter().zip(sims) {
        for (l, m) in levels.iter().enumerate() {
            for j in 0..6 {
                rows.push(vec![
                    name.clone(),
                    (l + 1).to_string(),
                    m.to_string(),
                    (j + 1).to_string(),
                    format!("{:.6}", sim.mean_deviation_pct[l][j]),
                    format!("{:.6}", sim.std_deviation_pct[l][j]),
                    format!("{:.6}", sim.predicted_deviation_pct[l][j]),
                    format!("{:.1}", sim.mean_stiffness[l][j]),
                ]);
            }
        }
    }
    csv_text(&header, rows)
}
