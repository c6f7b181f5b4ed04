//! `stiffid compensate --refine`: the free tool axis' grid refined around the line chosen on it
//! (the document's `refine`), the peak and the sum of the bound never above the grid's, every
//! rotation on the halved steps and within the step of the previous point's; bad values
//! refused naming `--refine`, nothing written.

use crate::common::example;
use crate::common::{json, refused, temp_dir};
use crate::lead_tilt_cli::milling;

/// The peak and the sum of the points' `bound_mm`, and their `tool_rotation_deg`.
fn bounds(doc: &serde_json::Value) -> (f64, f64, Vec<f64>) {
    let points = doc["points"].as_array().unwrap();
    let bound: Vec<f64> = points
        .iter()
        .map(|p| p["bound_mm"].as_f64().unwrap())
        .collect();
    let rotation = (points.iter())
        .map(|p| p["tool_rotation_deg"].as_f64().unwrap())
        .collect();
    (
        bound.iter().copied().fold(0.0, f64::max),
        bound.iter().sum(),
        rotation,
    )
}

#[test]
fn the_refined_rotation_never_rises_and_keeps_its_step() {
    let dir = temp_dir("refine-cli");
    let free = [
        "--free",
        "tool-rotation=-90..90/5",
        "--objective",
        "max",
        "--json",
    ];
    let grid = json(&milling(
        &dir,
        "grid.csv",
        &[&free[..], &["--refine", "0"]].concat(),
    ));
    let refined = json(&milling(
        &dir,
        "refined.csv",
        &[&free[..], &["--refine", "2"]].concat(),
    ));
    assert_eq!(grid["refine"], 0);
    assert_eq!(refined["refine"], 2);
    let (peak, sum, _) = bounds(&grid);
    let (peak_refined, sum_refined, rotation) = bounds(&refined);
    assert!(
        peak_refined <= peak * (1.0 + 1e-6),
        "{peak_refined} above {peak}"
    );
    assert!(
        sum_refined <= sum * (1.0 + 1e-6),
        "{sum_refined} above {sum}"
    );
    for w in rotation.windows(2) {
        assert!((w[1] - w[0]).abs() <= 5.0 + 1e-6, "{w:?}");
    }
    assert!(rotation
        .iter()
        .all(|r| ((r / 1.25) - (r / 1.25).round()).abs() < 1e-6));
    // Without a free variable the document has no refinement.
    assert!(json(&milling(&dir, "own.csv", &["--json"]))["refine"].is_null());
}

#[test]
fn bad_refine_values_are_refused() {
    let dir = temp_dir("refine-cli-refused");
    let (setup, stiffness, path) = (
        example("milling/fanuc-milling.toml"),
        example("milling/stiffness.json"),
        example("milling/path.csv"),
    );
    let base = [
        "compensate",
        "--setup",
        &setup,
        "--stiffness",
        &stiffness,
        "--path",
        &path,
        "--out",
        "{dir}/out.csv",
    ];
    for (extra, words) in [
        (
            vec!["--free", "tool-rotation", "--refine", "5"],
            "expected 0 to 4",
        ),
        (vec!["--refine", "1"], "only with --free"),
    ] {
        let args: Vec<&str> = base.iter().copied().chain(extra).collect();
        refused(&dir, &args, &["--refine", words]);
    }
}
