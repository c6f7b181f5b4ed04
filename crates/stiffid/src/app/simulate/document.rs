//! The document of the simulate job ([`crate::app::simulate`]): `stiffid simulate --json` (and
//! `--out DIR/simulation.json`), its `deviation_rates.csv`, Python's `simulate`; each group's part
//! ([`Group`]) is also a group of the study's summary.

use crate::app::document::csv_text;
use crate::app::simulate::Report;
use crate::model::Parameter;
use crate::study::simulate::GroupSimulation;
use crate::Setup;
use serde::Serialize;

/// One group's simulation: deviation rates in percent, per level then parameter (the drives,
/// then the model's virtual springs, in the order of `parameters`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Group {
    /// Name of the group.
    pub name: String,
    /// Mean deviation rate, percent, `[levels][parameters]`.
    pub mean_deviation_pct: Vec<Vec<f64>>,
    /// Standard deviation of the deviation rate, percent, `[levels][parameters]`.
    pub std_deviation_pct: Vec<Vec<f64>>,
    /// First-order predicted mean deviation rate, percent, `[levels][parameters]`.
    pub predicted_deviation_pct: Vec<Vec<f64>>,
    /// Mean identified stiffness of the drives, Nm/rad, `[levels][6]`.
    pub mean_stiffness_nm_per_rad: Vec<[f64; 6]>,
    /// Mean identified stiffness of each virtual spring, in its parameter's unit (Nm/rad for a
    /// rotation, N/mm for a translation), `[levels][springs]`; left out for the drives alone.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    #[cfg_attr(feature = "schema", schemars(default))]
    pub mean_spring_stiffness: Vec<Vec<f64>>,
}

impl Group {
    /// The document of group `name`'s simulation of a model with `parameters` (drives first).
    pub fn new(name: &str, sim: &GroupSimulation, parameters: &[Parameter]) -> Self {
        let join = |drives: &[[f64; 6]], springs: &[Vec<f64>]| -> Vec<Vec<f64>> {
            drives
                .iter()
                .enumerate()
                .map(|(l, d)| {
                    let rest = springs.get(l).map_or(&[][..], Vec::as_slice);
                    d.iter().chain(rest).copied().collect()
                })
                .collect()
        };
        let springs = parameters.get(6..).unwrap_or_default();
        Self {
            name: name.into(),
            mean_deviation_pct: join(&sim.mean_deviation_pct, &sim.spring_mean_deviation_pct),
            std_deviation_pct: join(&sim.std_deviation_pct, &sim.spring_std_deviation_pct),
            predicted_deviation_pct: join(
                &sim.predicted_deviation_pct,
                &sim.spring_predicted_deviation_pct,
            ),
            mean_stiffness_nm_per_rad: sim.mean_stiffness.iter().map(|k| (*k).into()).collect(),
            mean_spring_stiffness: sim
                .spring_mean_stiffness
                .iter()
                .map(|k| {
                    k.iter()
                        .zip(springs)
                        .map(|(k, p)| k * p.unit.per_si())
                        .collect()
                })
                .collect(),
        }
    }
}

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
