//! `identify --out` writes the region of its postures; `predict` and `validate` flag and warn
//! about a posture with an axis beyond it, and say once that a stiffness file without it is not
//! checked.

use crate::common::{assert_success, fanuc_csv, json, stiffid, temp_dir, validate_fanuc};
use std::path::Path;

/// The first FANUC posture with axis 2 at `q2`.
fn q_deg(q2: &str) -> String {
    format!("-59.991,{q2},-28.93,3.788,-62.93,144.919")
}

fn predict(stiffness: &Path, q2: &str) -> std::process::Output {
    stiffid(&[
        "predict",
        "--setup",
        "fanuc-r2000ic-165f",
        "--q-deg",
        &q_deg(q2),
        "--wrench",
        "0,0,-1000",
        "--stiffness",
        stiffness.to_str().unwrap(),
        "--json",
    ])
}

fn extrapolation_lines(stderr: &[u8]) -> Vec<String> {
    String::from_utf8_lossy(stderr)
        .lines()
        .filter(|l| l.contains("outside the region") || l.contains("does not record"))
        .map(str::to_string)
        .collect()
}

fn identified(dir: &Path) -> std::path::PathBuf {
    let file = dir.join("k.json");
    let out = stiffid(&[
        "identify",
        "--setup",
        "fanuc-r2000ic-165f",
        "--data",
        fanuc_csv().to_str().unwrap(),
        "--out",
        file.to_str().unwrap(),
    ]);
    assert_success(&out);
    file
}

#[test]
fn predict_and_validate_flag_a_posture_beyond_the_identification_range() {
    let dir = temp_dir("extrapolation");
    let file = identified(&dir);
    let written: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
    assert_eq!(written["region"]["postures"], 43);
    assert_eq!(written["region"]["margin_deg"], 5.0);

    // Inside (a measured posture, and 4 deg past axis 2's largest angle): no flag, no warning.
    for q2 in ["-16.693", "42.5"] {
        let out = predict(&file, q2);
        assert!(extrapolation_lines(&out.stderr).is_empty());
        let doc = json(&out);
        assert_eq!(doc["extrapolates"], false);
        assert_eq!(doc["outside_region"], serde_json::json!([]));
    }
    // 10 deg past: flagged in the document, one warning on stderr.
    let out = predict(&file, "48.5");
    let lines = extrapolation_lines(&out.stderr);
    assert_eq!(lines.len(), 1, "{lines:?}");
    assert!(
        lines[0].starts_with(
            "warning: the posture lies outside the region the stiffness was identified from"
        ),
        "{}",
        lines[0]
    );
    assert!(lines[0].contains("axis 2 at 48.50 deg (identified over -52.03 .. 38.50)"));
    let doc = json(&out);
    assert_eq!(doc["extrapolates"], true);
    assert_eq!(doc["outside_region"][0]["axis"], 2);

    // validate on the identification data: every check inside.
    let out = validate_fanuc(&file, &["--json"]);
    assert!(extrapolation_lines(&out.stderr).is_empty());
    let doc = json(&out);
    assert_eq!(doc["extrapolated_postures"], 0);
    // With posture 2's axis 2 at 60 deg: that posture flagged and named.
    let moved = std::fs::read_to_string(fanuc_csv()).unwrap().replace(
        "2,1,-61.110999989328384,-12.853000013817956,",
        "2,1,-61.110999989328384,60,",
    );
    let data = dir.join("moved.csv");
    std::fs::write(&data, moved).unwrap();
    let out = stiffid(&[
        "validate",
        "--setup",
        "fanuc-r2000ic-165f",
        "--stiffness",
        file.to_str().unwrap(),
        "--data",
        data.to_str().unwrap(),
        "--json",
    ]);
    let lines = extrapolation_lines(&out.stderr);
    assert_eq!(lines.len(), 1, "{lines:?}");
    assert!(lines[0].starts_with("warning: 1 of 43 postures lies outside the region"));
    assert!(lines[0].contains("posture 2: axis 2 at 60.00 deg"));
    let doc = json(&out);
    assert_eq!(doc["extrapolated_postures"], 1);
    let flagged: Vec<&str> = (doc["checks"].as_array().unwrap().iter())
        .filter(|c| c["extrapolates"] == true)
        .map(|c| c["posture"].as_str().unwrap())
        .collect();
    assert_eq!(flagged, ["2"]);
}

#[test]
fn a_stiffness_file_without_its_region_is_read_with_one_warning() {
    let dir = temp_dir("extrapolation-old");
    let file = identified(&dir);
    let mut written: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
    written.as_object_mut().unwrap().remove("region");
    let old = dir.join("old.json");
    std::fs::write(&old, written.to_string()).unwrap();
    let out = predict(&old, "48.5");
    let lines = extrapolation_lines(&out.stderr);
    assert_eq!(lines.len(), 1, "{lines:?}");
    assert!(lines[0].contains("does not record the postures it was identified from"));
    assert_eq!(json(&out)["extrapolates"], serde_json::Value::Null);
    let out = validate_fanuc(&old, &["--json"]);
    assert_eq!(extrapolation_lines(&out.stderr).len(), 1);
    assert_eq!(json(&out)["extrapolated_postures"], serde_json::Value::Null);
}
