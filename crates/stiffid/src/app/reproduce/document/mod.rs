//! The document of the reproduce job ([`crate::app::reproduce`]): `summary.json` of
//! `stiffid reproduce`, Python's `Study.to_dict()`: the resolved setup, the options, every
//! group's postures, criteria and deviation rates, and the findings (in numbers and in words,
//! [`sentences`]).

mod sentences;
mod setup;

pub use sentences::{search_words, sentences};
pub use setup::SetupJson;

use crate::app::document::group::{CriteriaValues, Group};
use crate::app::reproduce::Report;
use nalgebra::{Vector3, Vector6};
use serde::Serialize;
use stiffid_design::study::Study;

/// The value of the `generator` key that marks a directory as a report of ours.
pub const GENERATOR: &str = "stiffid reproduce";

/// A position (m) in mm.
fn mm(v: &Vector3<f64>) -> [f64; 3] {
    [v.x * 1e3, v.y * 1e3, v.z * 1e3]
}

/// Axis angles (rad) in deg.
fn deg(q: &Vector6<f64>) -> [f64; 6] {
    std::array::from_fn(|i| q[i].to_degrees())
}

/// `summary.json` of `stiffid reproduce`: the resolved setup, the options, and every group's
/// postures, criteria and deviation rates (`kind` first, then the keys in the order below).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "reproduce")]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("reproduce")))]
pub struct Summary<'a> {
    /// `stiffid reproduce`: marks the directory as a report of ours.
    pub generator: &'static str,
    /// The version of stiffid that wrote it.
    pub version: &'static str,
    /// The setup, resolved.
    pub setup: SetupJson<'a>,
    /// The seed of the study.
    pub seed: u64,
    /// Monte Carlo runs per group and noise level.
    pub runs: usize,
    /// The noise level multiples of the setup's variance.
    pub levels: &'a [f64],
    /// The noise level (1-based) of the validation at the test postures.
    pub validation_level: usize,
    /// Wall-clock time of the study, s.
    pub elapsed_s: f64,
    /// The true displacement of every measuring point at every test posture, base frame, mm:
    /// `[test posture][point]`.
    pub test_deflection_mm: Vec<Vec<[f64; 3]>>,
    /// Every group of postures, in the order of the report.
    pub groups: Vec<GroupSummary<'a>>,
    /// The seeded start groups of the check of the paper's claim.
    pub start_trials: Vec<TrialJson>,
    /// What the study found.
    pub findings: FindingsJson,
}

/// One group of postures: its simulation, how it was found, its criteria.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct GroupSummary<'a> {
    /// Its simulation (its name and deviation rates).
    #[serde(flatten)]
    pub simulation: Group,
    /// Short label, e.g. `Group 3 (zhang2021, local)`.
    pub title: &'a str,
    /// The criterion searched; `null` for the start group.
    pub criterion: Option<&'static str>,
    /// How the group was obtained, in words.
    pub search: String,
    /// Criterion evaluations the search spent (0 for the start group).
    pub search_evaluations: usize,
    /// Axis angles q1..q6, deg, one row per posture.
    pub postures_deg: Vec<[f64; 6]>,
    /// Its design criteria.
    #[serde(flatten)]
    pub criteria: CriteriaValues,
    /// Mean over noise levels and joints of `mean_deviation_pct`, percent.
    pub average_deviation_pct: f64,
    /// `|delta(k_mean) - delta(k_true)|` of every measuring point at every test posture at the
    /// validation level, mm: `[test posture][point]`.
    pub validation_error_mm: Vec<Vec<f64>>,
}

impl<'a> GroupSummary<'a> {
    fn new(study: &'a Study, g: usize) -> Self {
        let group = &study.groups[g];
        Self {
            simulation: Group::new(
                &group.name,
                &group.simulation,
                &study.setup.model().parameters(),
            ),
            title: &group.title,
            criterion: group.origin.criterion().map(|c| c.name()),
            search: search_words(&group.origin, study.seed),
            search_evaluations: group.evaluations,
            postures_deg: group.postures.iter().map(deg).collect(),
            criteria: CriteriaValues::from(&group.evaluation),
            average_deviation_pct: group.average_deviation_pct(),
            validation_error_mm: group
                .validation_error
                .iter()
                .map(|t| t.iter().map(|e| e * 1e3).collect())
                .collect(),
        }
    }
}

/// One seeded start group of the check of the paper's claim: the predicted average deviation
/// rate (percent) of the start group and of SQP from it on `classical` and on `zhang2021`.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct TrialJson {
    /// The seed of the start group.
    pub seed: u64,
    /// The start group's, percent.
    pub start_predicted_average_pct: f64,
    /// After SQP on `classical`, percent.
    pub classical_predicted_average_pct: f64,
    /// After SQP on `zhang2021`, percent.
    pub zhang2021_predicted_average_pct: f64,
}

/// What the study found (the report's findings).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct FindingsJson {
    /// Whether Group 3 (zhang2021) has a lower average deviation rate than Groups 1 and 2.
    pub group3_beats_groups_1_and_2: bool,
    /// Group 1's average deviation rate over Group 3's (> 1: Group 3 better).
    pub group3_factor_vs_group1: Option<f64>,
    /// Group 2's over Group 3's.
    pub group3_factor_vs_group2: Option<f64>,
    /// Group 3's over the globally searched relative-a group's; `null` without that group.
    pub relative_a_factor_vs_group3: Option<f64>,
    /// Start groups from which SQP on zhang2021 beats both the start group and SQP on classical
    /// (predicted).
    pub start_groups_where_zhang2021_beats_both: usize,
    /// Start groups tried.
    pub start_groups: usize,
    /// Mean of |simulated / predicted - 1| over groups, levels and joints (finite ratios only).
    pub prediction_mean_abs_relative_error: f64,
    /// The findings in words.
    pub sentences: Vec<String>,
}

impl<'a> Summary<'a> {
    /// The summary of a reproduce report (the study's `elapsed_s` as it stands).
    pub(crate) fn new(report: &'a Report) -> Self {
        let (study, f) = (&report.study, &report.findings);
        Summary {
            generator: GENERATOR,
            version: env!("CARGO_PKG_VERSION"),
            setup: SetupJson::new(&study.setup),
            seed: study.seed,
            runs: study.runs,
            levels: &study.setup.noise().levels,
            validation_level: study.validation_level + 1,
            elapsed_s: study.elapsed_s,
            test_deflection_mm: study
                .test_deflection
                .iter()
                .map(|t| t.iter().map(mm).collect())
                .collect(),
            groups: (0..study.groups.len())
                .map(|g| GroupSummary::new(study, g))
                .collect(),
            start_trials: study
                .trials
                .iter()
                .map(|t| TrialJson {
                    seed: t.seed,
                    start_predicted_average_pct: t.predicted_average_pct[0],
                    classical_predicted_average_pct: t.predicted_average_pct[1],
                    zhang2021_predicted_average_pct: t.predicted_average_pct[2],
                })
                .collect(),
            findings: FindingsJson {
                group3_beats_groups_1_and_2: f.paper_claim_holds,
                group3_factor_vs_group1: f.group3.first().map(|v| v.factor),
                group3_factor_vs_group2: f.group3.get(1).map(|v| v.factor),
                relative_a_factor_vs_group3: f.relative_a.as_ref().map(|v| v.factor),
                start_groups_where_zhang2021_beats_both: f.start_check.wins,
                start_groups: f.start_check.trials,
                prediction_mean_abs_relative_error: f.prediction_error,
                sentences: sentences(f, study),
            },
        }
    }
}
