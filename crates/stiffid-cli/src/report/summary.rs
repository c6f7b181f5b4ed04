//! `summary.json`: the resolved setup, the options, and every group's postures, criteria and
//! deviation rates. mm, deg, N and Nm/rad at the edges, units in the key names.

use super::findings::sentences;
use super::search_words;
use crate::commands::evaluate::CriteriaValuesJson;
use crate::commands::simulate::GroupJson;
use anyhow::Result;
use nalgebra::{Isometry3, Vector3, Vector6};
use schemars::JsonSchema;
use serde::Serialize;
use serde_json::Value;
use std::path::Path;
use stiffid::study::{findings, Study};
use stiffid::{Coordinates, Setup};

/// The value of the `generator` key that marks a directory as a report of ours.
pub const GENERATOR: &str = "stiffid reproduce";

/// Whether `path` is a `summary.json` whose `generator` is `generator` (e.g. [`GENERATOR`]).
pub fn is_ours(path: &Path, generator: &str) -> bool {
    std::fs::read_to_string(path)
        .ok()
        .and_then(|t| serde_json::from_str::<Value>(&t).ok())
        .is_some_and(|v| v["generator"] == generator)
}

fn mm(v: &Vector3<f64>) -> [f64; 3] {
    [v.x * 1e3, v.y * 1e3, v.z * 1e3]
}

fn deg(q: &Vector6<f64>) -> [f64; 6] {
    std::array::from_fn(|i| q[i].to_degrees())
}

/// `summary.json` of `stiffid reproduce`: the resolved setup, the options, and every group's
/// postures, criteria and deviation rates (keys in alphabetical order in the file).
#[derive(Serialize, JsonSchema)]
pub struct Summary<'a> {
    /// `stiffid reproduce`: marks the directory as a report of ours.
    generator: &'static str,
    /// The version of stiffid that wrote it.
    version: &'static str,
    /// The setup, resolved.
    setup: SetupJson<'a>,
    /// The seed of the study.
    seed: u64,
    /// Monte Carlo runs per group and noise level.
    runs: usize,
    /// The noise level multiples of the setup's variance.
    levels: &'a [f64],
    /// The noise level (1-based) of the validation at the test postures.
    validation_level: usize,
    /// Wall-clock time of the study, s.
    elapsed_s: f64,
    /// The true displacement of every measuring point at every test posture, base frame, mm:
    /// [test posture][point].
    test_deflection_mm: Vec<Vec<[f64; 3]>>,
    /// Every group of postures, in the order of the report.
    groups: Vec<GroupSummary<'a>>,
    /// The seeded start groups of the check of the paper's claim.
    start_trials: Vec<TrialJson>,
    /// What the study found.
    findings: FindingsJson,
}

/// A rigid transform.
#[derive(Serialize, JsonSchema)]
struct FrameJson {
    /// Translation, mm.
    translation_mm: [f64; 3],
    /// Rotation as a unit quaternion, w, x, y, z.
    rotation_quaternion_wxyz: [f64; 4],
}

impl From<&Isometry3<f64>> for FrameJson {
    fn from(t: &Isometry3<f64>) -> Self {
        let q = t.rotation.quaternion();
        Self {
            translation_mm: mm(&t.translation.vector),
            rotation_quaternion_wxyz: [q.w, q.i, q.j, q.k],
        }
    }
}

/// The resolved setup (SI inside stiffid, mm, deg and N here).
#[derive(Serialize, JsonSchema)]
struct SetupJson<'a> {
    /// The setup's name.
    name: &'a str,
    /// Its description.
    description: &'a str,
    /// The robot, resolved.
    robot: RobotJson<'a>,
    /// The map from axis angles to kinematic angles: `theta = M q + offset`.
    axis_map: AxisMapJson,
    /// Where the springs sit.
    springs: Coordinates,
    /// The tool's points, flange frame.
    tool: ToolJson,
    /// The rope load.
    loading: LoadingJson,
    /// The tracker noise.
    noise: NoiseJson,
    /// The posture bounds of the search.
    bounds: BoundsJson,
    /// The nominal joint stiffness, Nm/rad (the study's true stiffness; a study needs it).
    stiffness_nm_per_rad: Option<[f64; 6]>,
    /// The characteristic length of the dexterity index, mm (a study needs it).
    characteristic_length_mm: Option<f64>,
    /// The test postures, axis angles q1..q6, deg.
    test_postures_deg: Vec<[f64; 6]>,
}

/// The robot, resolved.
#[derive(Serialize, JsonSchema)]
struct RobotJson<'a> {
    /// The robot as the setup names it (a preset or a file).
    reference: &'a str,
    /// The robot's name.
    name: &'a str,
    /// Where it comes from.
    source: &'a str,
    /// Every joint, base to flange.
    joints: Vec<JointJson>,
    /// Lower axis limits, deg.
    lower_limit_deg: [f64; 6],
    /// Upper axis limits, deg.
    upper_limit_deg: [f64; 6],
    /// The base frame in the world.
    base: FrameJson,
    /// The flange frame after the last joint.
    flange: FrameJson,
}

/// One joint: `pre`, the rotation about `axis` by the angle plus `offset_deg`, `post`.
#[derive(Serialize, JsonSchema)]
struct JointJson {
    /// The fixed transform before the rotation.
    pre: FrameJson,
    /// The unit rotation axis.
    axis: [f64; 3],
    /// The fixed transform after the rotation.
    post: FrameJson,
    /// The kinematic angle offset, deg.
    offset_deg: f64,
}

/// `theta = M q + offset`.
#[derive(Serialize, JsonSchema)]
struct AxisMapJson {
    /// `M`, row-major.
    matrix: [[f64; 6]; 6],
    /// The offset, deg.
    offset_deg: [f64; 6],
}

/// The tool's points, flange frame, mm.
#[derive(Serialize, JsonSchema)]
struct ToolJson {
    /// Where the rope pulls.
    loading_point_mm: [f64; 3],
    /// The points the tracker measures.
    measuring_points_mm: Vec<[f64; 3]>,
    /// The tool centre point.
    tcp_mm: [f64; 3],
}

/// The rope load.
#[derive(Serialize, JsonSchema)]
struct LoadingJson {
    /// The rope's tension, N.
    load_n: f64,
    /// The rope's fixed end, base frame, mm.
    anchor_mm: [f64; 3],
}

/// The tracker noise.
#[derive(Serialize, JsonSchema)]
struct NoiseJson {
    /// The variance of one coordinate at level multiple 1, mm^2.
    variance_mm2: f64,
    /// The noise level multiples of the variance.
    level_multiples: Vec<f64>,
}

/// Posture bounds, axis angles q1..q6, deg.
#[derive(Serialize, JsonSchema)]
struct BoundsJson {
    /// Lower bounds.
    lower_deg: [f64; 6],
    /// Upper bounds.
    upper_deg: [f64; 6],
}

impl<'a> SetupJson<'a> {
    fn new(s: &'a Setup) -> Self {
        let r = &s.robot();
        let m = &r.axis_map.matrix;
        Self {
            name: s.name(),
            description: s.description(),
            robot: RobotJson {
                reference: s.robot_ref(),
                name: &r.name,
                source: &r.source,
                joints: r
                    .joints
                    .iter()
                    .map(|j| JointJson {
                        pre: FrameJson::from(&j.pre),
                        axis: [j.axis.x, j.axis.y, j.axis.z],
                        post: FrameJson::from(&j.post),
                        offset_deg: j.offset.to_degrees(),
                    })
                    .collect(),
                lower_limit_deg: deg(&r.limits.lower),
                upper_limit_deg: deg(&r.limits.upper),
                base: FrameJson::from(&r.base),
                flange: FrameJson::from(&r.flange),
            },
            axis_map: AxisMapJson {
                matrix: std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)])),
                offset_deg: deg(&r.axis_map.offset),
            },
            springs: s.springs(),
            tool: ToolJson {
                loading_point_mm: mm(&s.tool().loading_point),
                measuring_points_mm: s.tool().measuring_points.iter().map(mm).collect(),
                tcp_mm: mm(&s.tool().tcp),
            },
            loading: LoadingJson {
                load_n: s.load().load,
                anchor_mm: mm(&s.load().anchor),
            },
            noise: NoiseJson {
                variance_mm2: s.noise().variance * 1e6,
                level_multiples: s.noise().levels.clone(),
            },
            bounds: BoundsJson {
                lower_deg: deg(&s.bounds().lower),
                upper_deg: deg(&s.bounds().upper),
            },
            stiffness_nm_per_rad: s.nominal_stiffness().map(|k| (*k).into()),
            characteristic_length_mm: s.characteristic_length().map(|l| l * 1e3),
            test_postures_deg: s.test_postures().iter().map(deg).collect(),
        }
    }
}

/// One group of postures: its simulation, how it was found, its criteria.
#[derive(Serialize, JsonSchema)]
struct GroupSummary<'a> {
    #[serde(flatten)]
    simulation: GroupJson<'a>,
    /// Short label, e.g. `Group 3 (zhang2021, local)`.
    title: &'a str,
    /// The criterion searched; `null` for the start group.
    criterion: Option<&'static str>,
    /// How the group was obtained, in words.
    search: String,
    /// Criterion evaluations the search spent (0 for the start group).
    search_evaluations: usize,
    /// Axis angles q1..q6, deg, one row per posture.
    postures_deg: Vec<[f64; 6]>,
    #[serde(flatten)]
    criteria: CriteriaValuesJson,
    /// Mean over noise levels and joints of `mean_deviation_pct`, percent.
    average_deviation_pct: f64,
    /// `|delta(k_mean) - delta(k_true)|` of every measuring point at every test posture at the
    /// validation level, mm: [test posture][point].
    validation_error_mm: Vec<Vec<f64>>,
}

impl<'a> GroupSummary<'a> {
    fn new(study: &'a Study, g: usize) -> Self {
        let group = &study.groups[g];
        Self {
            simulation: GroupJson::new(&group.name, &group.simulation),
            title: &group.title,
            criterion: group.origin.criterion().map(|c| c.name()),
            search: search_words(&group.origin, study.seed),
            search_evaluations: group.evaluations,
            postures_deg: group.postures.iter().map(deg).collect(),
            criteria: CriteriaValuesJson::from(&group.evaluation),
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
#[derive(Serialize, JsonSchema)]
struct TrialJson {
    /// The seed of the start group.
    seed: u64,
    /// The start group's, percent.
    start_predicted_average_pct: f64,
    /// After SQP on `classical`, percent.
    classical_predicted_average_pct: f64,
    /// After SQP on `zhang2021`, percent.
    zhang2021_predicted_average_pct: f64,
}

/// What the study found (the report's findings).
#[derive(Serialize, JsonSchema)]
struct FindingsJson {
    /// Whether Group 3 (zhang2021) has a lower average deviation rate than Groups 1 and 2.
    group3_beats_groups_1_and_2: bool,
    /// Group 1's average deviation rate over Group 3's (> 1: Group 3 better).
    group3_factor_vs_group1: Option<f64>,
    /// Group 2's over Group 3's.
    group3_factor_vs_group2: Option<f64>,
    /// Group 3's over the globally searched relative-a group's; `null` without that group.
    relative_a_factor_vs_group3: Option<f64>,
    /// Start groups from which SQP on zhang2021 beats both the start group and SQP on classical
    /// (predicted).
    start_groups_where_zhang2021_beats_both: usize,
    /// Start groups tried.
    start_groups: usize,
    /// Mean of |simulated / predicted - 1| over groups, levels and joints (finite ratios only).
    prediction_mean_abs_relative_error: f64,
    /// The findings in words.
    sentences: Vec<String>,
}

/// The text of `summary.json`.
pub fn json(study: &Study) -> Result<String> {
    let f = findings(study);
    let doc = Summary {
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
            sentences: sentences(&f, study),
        },
    };
    // Through a `Value`: its keys in alphabetical order, as summary.json has always had them.
    crate::output::json(&serde_json::to_value(&doc)?)
}
