//! `stiffid simulate` from files: JSON shape, written files, one-line errors with exit code 2.

mod common;

use common::{fresh_dir, stiffid, GROUP};

#[test]
fn simulate_writes_json_and_csv() {
    let dir = fresh_dir("simulate");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("start.csv");
    std::fs::write(&file, GROUP).unwrap();
    let out_dir = dir.join("out");
    let out = stiffid(&[
        "simulate",
        "--setup",
        "zhang2021-comau-nj165",
        "--postures",
        file.to_str().unwrap(),
        "--runs",
        "20",
        "--json",
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(doc["runs"], 20);
    let group = &doc["groups"][0];
    assert_eq!(group["name"], "start");
    assert_eq!(group["mean_deviation_pct"].as_array().unwrap().len(), 6);
    let csv = std::fs::read_to_string(out_dir.join("deviation_rates.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 6 * 6);
    assert!(out_dir.join("simulation.json").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_bad_postures_file_is_one_line_and_exit_2() {
    let dir = fresh_dir("simulate-bad");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("bad.csv");
    std::fs::write(&file, GROUP.replace("-160,80", "-160,oops")).unwrap();
    let out = stiffid(&[
        "simulate",
        "--setup",
        "zhang2021-comau-nj165",
        "--postures",
        file.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("bad.csv") && err.contains("line 7") && err.contains("q5_deg"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
