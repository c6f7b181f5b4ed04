//! `select --for check` and `calibrate --update` on the calibrated robot file: a check campaign
//! designed on it, the drifted robot found drifted (the check's gate failed, exit code 1) and
//! updated to rounding, the updated file written beside the input; the options an update does
//! not take refused.

use crate::calibrate_cli::{model, postures, readings, truth, SETUP};
use crate::common::{json, numbers, refused, stiffid, temp_dir, write_file};
use nalgebra::{DVector, Isometry3, Vector3};
use std::path::{Path, PathBuf};
use stiffid::internal::metrology::calibration::ErrorModel;

fn arg(p: &Path) -> String {
    p.to_str().unwrap().to_string()
}

/// A calibration of the true robot `x` (25 postures, 8 held out) written to `robot.toml` in
/// `d`, and a setup on it.
fn calibrated_setup(d: &Path, model: &ErrorModel, x: &DVector<f64>) -> PathBuf {
    let tracker = crate::calibrate_cli::tracker();
    let fit = write_file(
        d,
        "fit.csv",
        &readings(model, x, &tracker, &postures(25, 1)),
    );
    let held = write_file(
        d,
        "held.csv",
        &readings(model, x, &tracker, &postures(8, 2)),
    );
    let robot = d.join("robot.toml");
    json(&stiffid(&[
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        &arg(&fit),
        "--validate",
        &arg(&held),
        "--out",
        &arg(&robot),
        "--json",
    ]));
    assert!(std::fs::read_to_string(&robot)
        .unwrap()
        .contains("[held_out]"));
    let setup_text = stiffid::internal::setup::builtin_text(SETUP)
        .unwrap()
        .replace(
            "robot = \"comau-smart5-nj165-3.0\"",
            "robot = \"robot.toml\"",
        );
    write_file(d, "calibrated.toml", &setup_text)
}

/// The check campaign `select --for check` designs on the calibrated robot of `setup`: 10
/// postures of the offsets, deg.
fn check_postures(d: &Path, setup: &Path) -> Vec<[f64; 6]> {
    let check = d.join("check.csv");
    let doc = json(&stiffid(&[
        "select",
        "--setup",
        &arg(setup),
        "--for",
        "check",
        "--global",
        "--starts",
        "2",
        "--out",
        &arg(&check),
        "--json",
    ]));
    assert_eq!(doc["calibration"]["geometry"], "offsets");
    let designed: Vec<[f64; 6]> = (doc["postures_deg"].as_array().unwrap().iter())
        .map(|q| std::array::from_fn(|i| numbers(q)[i]))
        .collect();
    assert_eq!(designed.len(), 10);
    designed
}

/// What an update does not take: another geometry, the input as its output, a robot that is
/// not a calibrated file.
fn an_update_refuses_what_it_does_not_take(d: &Path) {
    let again = [
        "calibrate",
        "--setup",
        "{dir}/calibrated.toml",
        "--update",
        "--data",
    ];
    let check_data = "{dir}/check-readings.csv";
    refused(
        d,
        &[&again[..], &[check_data, "--geometry", "full"]].concat(),
        &["--geometry"],
    );
    refused(
        d,
        &[&again[..], &[check_data, "--out", "{dir}/robot.toml"]].concat(),
        &["--out"],
    );
    let plain = [
        "calibrate",
        "--setup",
        SETUP,
        "--update",
        "--data",
        check_data,
    ];
    refused(d, &plain, &["update", "not a calibrated robot file"]);
}

#[test]
fn the_check_finds_the_drift_and_the_update_recovers_it() {
    let d = temp_dir("update-cli");
    let model = model();
    let x = truth(&model);
    let setup = calibrated_setup(&d, &model, &x);
    let designed = check_postures(&d, &setup);
    // The drift: joints 2 to 5's offsets by 0.05 degrees, the tracker moved.
    let mut drifted = x.clone();
    for (c, p) in model.parameters().iter().enumerate() {
        if [
            "joint2.theta",
            "joint3.theta",
            "joint4.theta",
            "joint5.theta",
        ]
        .contains(&p.name.as_str())
        {
            drifted[c] += 0.05_f64.to_radians();
        }
    }
    let moved = Isometry3::new(Vector3::new(2.0, -2.5, 1.0), Vector3::new(0.0, 0.0, 2.0));
    let data = write_file(
        &d,
        "check-readings.csv",
        &readings(&model, &drifted, &moved, &designed),
    );
    let later = write_file(
        &d,
        "later.csv",
        &readings(&model, &drifted, &moved, &postures(8, 3)),
    );
    let updated = d.join("updated.toml");
    let o = stiffid(&[
        "calibrate",
        "--setup",
        &arg(&setup),
        "--update",
        "--data",
        &arg(&data),
        "--validate",
        &arg(&later),
        "--out",
        &arg(&updated),
        "--json",
    ]);
    // The drifted robot fails the check's gate: exit code 1 (2 is bad input), one error line
    // (after the warning that the later readings lie beyond the fitted range of joint 5), the
    // document printed and the update written.
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{stderr}");
    let errors: Vec<&str> = stderr
        .lines()
        .filter(|l| !l.starts_with("warning:"))
        .collect();
    assert_eq!(errors.len(), 1, "{stderr}");
    assert!(
        stderr.contains("outside the fitted postures' range of joint 5"),
        "{stderr}"
    );
    let gate = "error: --update: the robot drifted beyond its intervals: ";
    assert!(errors[0].starts_with(gate), "{stderr}");
    let doc: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(doc["geometry"], "offsets");
    assert_eq!(doc["check"]["drifted"], true);
    assert_eq!(doc["check"]["readings"], 40);
    let after = doc["validation"]["rms_mm"].as_f64().unwrap();
    let before = doc["validation"]["nominal_rms_mm"].as_f64().unwrap();
    assert!(after < 1e-9 && before > 0.1, "{after} {before}");
    assert!(std::fs::read_to_string(&updated)
        .unwrap()
        .contains("(calibrated)"));
    an_update_refuses_what_it_does_not_take(&d);
}
