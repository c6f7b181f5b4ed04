//! `stiffid simulate` from files: JSON shape, written files, one-line errors with exit code 2.

use crate::common;

use common::{assert_usage_error, json, stiffid, temp_dir, write_file, GROUP};

#[test]
fn simulate_writes_json_and_csv() {
    let dir = temp_dir("simulate");
    let file = write_file(&dir, "start.csv", GROUP);
    let out_dir = dir.join("out");
    let doc = json(&stiffid(&[
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
    ]));
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
    let dir = temp_dir("simulate-bad");
    let file = write_file(&dir, "bad.csv", &GROUP.replace("-160,80", "-160,oops"));
    let out = stiffid(&[
        "simulate",
        "--setup",
        "zhang2021-comau-nj165",
        "--postures",
        file.to_str().unwrap(),
    ]);
    assert_usage_error(&out, &["bad.csv", "line 7", "q5_deg"]);
    std::fs::remove_dir_all(&dir).unwrap();
}
