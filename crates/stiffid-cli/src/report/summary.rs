//! `summary.json`: the resolved setup, the options, and every group's postures, criteria and
//! deviation rates. mm, deg, N and Nm/rad at the edges, units in the key names.

use super::criteria_values;
use super::findings::sentences;
use super::search_words;
use anyhow::Result;
use nalgebra::{Isometry3, Vector3, Vector6};
use serde_json::{json, Map, Value};
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

fn frame(t: &Isometry3<f64>) -> Value {
    let q = t.rotation.quaternion();
    json!({
        "translation_mm": mm(&t.translation.vector),
        "rotation_quaternion_wxyz": [q.w, q.i, q.j, q.k],
    })
}

/// The resolved setup.
pub fn setup_json(s: &Setup) -> Value {
    let r = &s.robot();
    let m = &r.axis_map.matrix;
    json!({
        "name": s.name(),
        "description": s.description(),
        "robot": {
            "reference": s.robot_ref(),
            "name": r.name,
            "source": r.source,
            "joints": r.joints.iter().map(|j| json!({
                "pre": frame(&j.pre),
                "axis": [j.axis.x, j.axis.y, j.axis.z],
                "post": frame(&j.post),
                "offset_deg": j.offset.to_degrees(),
            })).collect::<Vec<_>>(),
            "lower_limit_deg": deg(&r.lower),
            "upper_limit_deg": deg(&r.upper),
            "base": frame(&r.base),
            "flange": frame(&r.flange),
        },
        "axis_map": {
            "matrix": (0..6).map(|i| (0..6).map(|j| m[(i, j)]).collect::<Vec<_>>()).collect::<Vec<_>>(),
            "offset_deg": deg(&r.axis_map.offset),
        },
        "springs": match s.springs() { Coordinates::Axis => "axis", Coordinates::Kinematic => "kinematic" },
        "tool": {
            "loading_point_mm": mm(&s.tool().loading_point),
            "measuring_points_mm": s.tool().measuring_points.iter().map(mm).collect::<Vec<_>>(),
            "tcp_mm": mm(&s.tool().tcp),
        },
        "loading": { "load_n": s.load().load, "anchor_mm": mm(&s.load().anchor) },
        "noise": { "variance_mm2": s.noise().variance * 1e6, "level_multiples": s.noise().levels },
        "bounds": { "lower_deg": deg(&s.bounds().lower), "upper_deg": deg(&s.bounds().upper) },
        "stiffness_nm_per_rad": s.nominal_stiffness().as_slice(),
        "characteristic_length_mm": s.characteristic_length() * 1e3,
        "test_postures_deg": s.test_postures().iter().map(deg).collect::<Vec<_>>(),
    })
}

fn group_json(study: &Study, g: usize) -> Value {
    let group = &study.groups[g];
    let s = &group.simulation;
    let mut v = Map::new();
    v.insert("name".into(), json!(group.name));
    v.insert("title".into(), json!(group.title));
    v.insert(
        "criterion".into(),
        json!(group.origin.criterion().map(|c| c.name())),
    );
    v.insert(
        "search".into(),
        json!(search_words(&group.origin, study.seed)),
    );
    v.insert("search_evaluations".into(), json!(group.evaluations));
    v.insert(
        "postures_deg".into(),
        json!(group.postures.iter().map(deg).collect::<Vec<_>>()),
    );
    for (key, value) in criteria_values(&group.evaluation) {
        v.insert(key.into(), finite(value));
    }
    v.insert("mean_deviation_pct".into(), json!(s.mean_deviation_pct));
    v.insert("std_deviation_pct".into(), json!(s.std_deviation_pct));
    v.insert(
        "predicted_deviation_pct".into(),
        json!(s.predicted_deviation_pct),
    );
    v.insert(
        "average_deviation_pct".into(),
        json!(group.average_deviation_pct()),
    );
    v.insert(
        "mean_stiffness_nm_per_rad".into(),
        json!(s
            .mean_stiffness
            .iter()
            .map(|k| k.as_slice().to_vec())
            .collect::<Vec<_>>()),
    );
    v.insert(
        "validation_error_mm".into(),
        json!(group
            .validation_error
            .iter()
            .map(|t| t.iter().map(|e| e * 1e3).collect::<Vec<_>>())
            .collect::<Vec<_>>()),
    );
    Value::Object(v)
}

/// A number, or `null` if not finite (JSON has no infinity).
fn finite(v: f64) -> Value {
    match v.is_finite() {
        true => json!(v),
        false => Value::Null,
    }
}

/// The text of `summary.json`.
pub fn json(study: &Study) -> Result<String> {
    let f = findings(study);
    let doc = json!({
        "generator": GENERATOR,
        "version": env!("CARGO_PKG_VERSION"),
        "setup": setup_json(&study.setup),
        "seed": study.seed,
        "runs": study.runs,
        "levels": study.setup.noise().levels,
        "validation_level": study.validation_level + 1,
        "elapsed_s": study.elapsed_s,
        "test_deflection_mm": study.test_deflection.iter()
            .map(|t| t.iter().map(mm).collect::<Vec<_>>()).collect::<Vec<_>>(),
        "groups": (0..study.groups.len()).map(|g| group_json(study, g)).collect::<Vec<_>>(),
        "start_trials": study.trials.iter().map(|t| json!({
            "seed": t.seed,
            "start_predicted_average_pct": t.predicted_average_pct[0],
            "classical_predicted_average_pct": t.predicted_average_pct[1],
            "zhang2021_predicted_average_pct": t.predicted_average_pct[2],
        })).collect::<Vec<_>>(),
        "findings": {
            "group3_beats_groups_1_and_2": f.paper_claim_holds,
            "group3_factor_vs_group1": f.group3.first().map(|v| v.factor),
            "group3_factor_vs_group2": f.group3.get(1).map(|v| v.factor),
            "relative_a_factor_vs_group3": f.relative_a.as_ref().map(|v| v.factor),
            "start_groups_where_zhang2021_beats_both": f.start_check.wins,
            "start_groups": f.start_check.trials,
            "prediction_mean_abs_relative_error": f.prediction_error,
            "sentences": sentences(&f, study),
        },
    });
    crate::output::json(&doc)
}
