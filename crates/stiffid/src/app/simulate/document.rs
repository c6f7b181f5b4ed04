//! The document of the simulate job ([`crate::app::simulate`]): `stiffid simulate --json` (and
//! `--out DIR/simulation.json`), its `deviation_rates.csv`, Python's `simulate`; the report is the document
//! ([`super::Report`]); here its parts: each group's
//! ([`Group`](crate::app::document::group::Group), as the study's summary has it too) and the parameters' names.

use crate::app::document::csv_text;
use serde::{Serialize, Serializer};
use stiffid_core::model::Parameter;
use stiffid_design::study::simulate::GroupSimulation;

/// A parameter of the simulated model: its name and the unit of its stiffness.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub(crate) struct Named {
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

/// The parameters of a model written as their names and units ([`Named`]). Schema:
/// `Vec<Named>`.
///
/// # Errors
/// The serialiser's.
pub(crate) fn named<S: Serializer>(parameters: &[Parameter], s: S) -> Result<S::Ok, S::Error> {
    s.collect_seq(parameters.iter().map(Named::from))
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
