//! `stiffid place`: the setup written with the placement chosen and the document beside it, the
//! same for a seed, never over an input, its ranges refused naming the option.

use crate::common::{assert_success, assert_usage_error, json, stiffid, temp_dir};
use std::path::PathBuf;

fn example(name: &str) -> String {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/milling");
    root.join(name).display().to_string()
}

fn args<'a>(setup: &'a str, out: &'a str, rest: &[&'a str]) -> Vec<&'a str> {
    let mut v = vec!["place", "--setup", setup, "--out", out, "--json"];
    v.extend_from_slice(rest);
    v
}

#[test]
fn the_panel_is_placed_better_than_its_own_and_the_reach_only_placement() {
    let dir = temp_dir("place-panel");
    let out = dir.join("placed.toml").display().to_string();
    let (setup, stiffness) = (example("fanuc-milling.toml"), example("stiffness.json"));
    let (program, process) = (example("panel.nc"), example("drilling.toml"));
    let rest = [
        "--stiffness",
        &stiffness,
        "--program",
        &program,
        "--process",
        &process,
        "--region-mm",
        "500,2000,-1500,500",
    ];
    let d = json(&stiffid(&args(&setup, &out, &rest)));
    let gain = d["gain_vs_own_percent"].as_f64().unwrap();
    assert!(gain >= 25.0, "{d}");
    assert!(
        d["gain_vs_reach_only_percent"].as_f64().unwrap() > 0.0,
        "{d}"
    );
    assert!(d["own"]["feasible"].as_bool().unwrap());
    // The setup written holds the placement the document names, and compensating the panel
    // there gives the peak bound the document states.
    let written = std::fs::read_to_string(&out).unwrap();
    let xyz = d["placed"]["xyz_mm"].as_array().unwrap();
    assert!(
        written.contains(&format!("xyz_mm = [{:.6}", xyz[0].as_f64().unwrap())),
        "{written}"
    );
    let csv = dir.join("panel.nc").display().to_string();
    let c = json(&stiffid(&[
        "compensate",
        "--setup",
        &out,
        "--stiffness",
        &stiffness,
        "--program",
        &program,
        "--process",
        &process,
        "--out",
        &csv,
        "--json",
    ]));
    let peak = c["summary"]["budget"]["max_bound_mm"].as_f64().unwrap();
    let placed = d["placed"]["peak_bound_mm"].as_f64().unwrap();
    assert!((peak - placed).abs() < 1e-6 * placed, "{peak} vs {placed}");
    // The same seed, the same placement; the written file is never an input.
    let again = dir.join("again.toml").display().to_string();
    let e = json(&stiffid(&args(&setup, &again, &rest)));
    assert_eq!(d["placed"], e["placed"]);
    assert_usage_error(&stiffid(&args(&setup, &setup, &rest)), &["--out"]);
    let mut bad = rest.to_vec();
    bad[7] = "2000,500,-1500,500";
    assert_usage_error(
        &stiffid(&args(&setup, &again, &bad)),
        &["--region-mm", "2000, 500"],
    );
    assert_success(&stiffid(&["place", "--help"]));
}
