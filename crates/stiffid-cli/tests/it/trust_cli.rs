//! `stiffid identify` on real and broken FANUC data: the model check, warnings for results that are
//! not physical or a likely unit mix-up, `--nonnegative`, `--cross-validate`, `validate`'s share
//! explained, and bad cases that end in one clear error line (exit 2) without a NaN printed.

use crate::common;

use common::{assert_usage_error, fanuc_csv, json, stiffid, temp_dir, validate_fanuc, write_file};
use std::process::Output;

const FANUC: &str = "fanuc-r2000ic-165f";

/// The FANUC file with every data row's fields changed by `edit` (fields as strings, 0-based:
/// posture, point, q1..q6, fx..fz, dx..dz); rows `keep` only.
fn fanuc_edited(keep: impl Fn(usize) -> bool, edit: impl Fn(usize, &mut Vec<String>)) -> String {
    let text = std::fs::read_to_string(fanuc_csv()).unwrap();
    let mut lines = text.lines();
    let mut out = lines.next().unwrap().to_string() + "\n";
    for (i, line) in lines.enumerate().filter(|(i, _)| keep(*i)) {
        let mut fields: Vec<String> = line.split(',').map(str::to_string).collect();
        edit(i, &mut fields);
        out += &(fields.join(",") + "\n");
    }
    out
}

fn scaled(fields: &mut [String], columns: std::ops::Range<usize>, factor: f64) {
    for f in &mut fields[columns] {
        *f = format!("{:e}", f.parse::<f64>().unwrap() * factor);
    }
}

/// Runs `identify` on `text` with extra arguments.
fn identify(name: &str, text: &str, extra: &[&str]) -> Output {
    let dir = temp_dir(&format!("trust-{name}"));
    let file = write_file(&dir, "data.csv", text);
    let out = stiffid(
        &[
            &[
                "identify",
                "--setup",
                FANUC,
                "--data",
                file.to_str().unwrap(),
            ][..],
            extra,
        ]
        .concat(),
    );
    std::fs::remove_dir_all(&dir).unwrap();
    out
}

fn assert_no_nan(out: &Output) {
    for stream in [&out.stdout, &out.stderr] {
        let text = String::from_utf8_lossy(stream);
        for word in ["NaN", "nan", "inf"] {
            let bad = text
                .split(|c: char| !c.is_alphanumeric())
                .any(|w| w == word || w == "-inf");
            assert!(!bad, "'{word}' printed: {text}");
        }
    }
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn fanuc_model_check_says_the_model_limits_the_fit() {
    let r = json(&stiffid(&[
        "identify",
        "--setup",
        FANUC,
        "--data",
        fanuc_csv().to_str().unwrap(),
        "--json",
    ]));
    let ratio = r["noise_ratio"].as_f64().unwrap();
    // s = 0.2200 mm against the setup's sigma = sqrt(9.23e-5) mm.
    assert!((ratio - 0.2200 / 9.23e-5f64.sqrt()).abs() < 0.01, "{ratio}");
    assert!(r["chi2_p_value"].as_f64().unwrap() < 1e-10);
    assert_eq!(r["model_error_dominates"], true);
    assert_eq!(
        r["physical"],
        serde_json::json!([true, true, true, true, true, true])
    );
    assert_eq!(r["intervals_from"], "residual variance");
    let narrow = r["tracker_noise"]["std_error_nm_per_rad"][0]
        .as_f64()
        .unwrap();
    let wide = r["std_error_nm_per_rad"][0].as_f64().unwrap();
    assert!(
        (wide / narrow - ratio).abs() < 0.05 * ratio,
        "{wide} / {narrow}"
    );
    assert!(r["unit_warning"].is_null());
    let text = stiffid(&[
        "identify",
        "--setup",
        FANUC,
        "--data",
        fanuc_csv().to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&text.stdout);
    assert!(stdout.contains("the model error dominates"), "{stdout}");
    assert!(stdout.contains("intervals from the residual variance"));
    assert!(stdout.contains("intervals from the tracker noise"));
    assert!(
        stderr(&text).is_empty(),
        "no warning on the original: {}",
        stderr(&text)
    );
}

#[test]
fn unit_warning_fires_on_metres_and_kilonewtons_not_on_the_original() {
    let metres = identify(
        "m",
        &fanuc_edited(|_| true, |_, f| scaled(f, 11..14, 1e-3)),
        &[],
    );
    let warning = stderr(&metres);
    assert!(metres.status.success());
    assert!(
        warning.contains("a unit is the likely cause")
            && warning.contains("dx_mm,dy_mm,dz_mm")
            && warning.contains("in m instead of mm"),
        "{warning}"
    );
    let kilo = identify(
        "kn",
        &fanuc_edited(|_| true, |_, f| scaled(f, 8..11, 1e-3)),
        &[],
    );
    let warning = stderr(&kilo);
    assert!(
        warning.contains("fx_n,fy_n,fz_n") && warning.contains("in kN instead of N"),
        "{warning}"
    );
}

/// Angles in radians under `_deg` names: the identify job warns, naming the file; positions far
/// beyond any tracker's range are refused, naming the line and column.
#[test]
fn radians_are_warned_about_and_absurd_positions_refused() {
    let radians = fanuc_edited(|_| true, |_, f| scaled(f, 2..8, 1f64.to_radians()));
    let out = identify("rad", &radians, &[]);
    assert!(out.status.success());
    let warning = stderr(&out);
    assert!(
        warning.contains("data.csv: every axis angle of the 43 postures lies within")
            && warning.contains("radians under _deg names"),
        "{warning}"
    );
    // The likely cause comes first, before what it causes (negative or far-off compliances).
    let lines: Vec<&str> = warning.lines().collect();
    assert!(lines.len() > 1, "{warning}");
    assert!(lines[0].contains("radians under _deg names"), "{warning}");
    let header = "posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,fx_n,fy_n,fz_n,\
x_loaded_mm,y_loaded_mm,z_loaded_mm,x_unloaded_mm,y_unloaded_mm,z_unloaded_mm\n";
    let row = |p: usize, x: &str| format!("{p},1,{p},10,-10,0,20,0,0,0,-1000,{x},0,0,1e15,0,0\n");
    let text = format!("{header}{}{}", row(1, "1e15"), row(2, "1000000000000000.1"));
    let out = identify("far", &text, &[]);
    assert_usage_error(
        &out,
        &["line 2, column 12 (x_loaded_mm): x_loaded_mm = 1e15 is outside"],
    );
}

#[test]
fn sign_flipped_displacements_are_not_physical_and_nonnegative_holds_them_at_zero() {
    let flipped = fanuc_edited(|_| true, |_, f| scaled(f, 11..14, -1.0));
    let out = identify("flip", &flipped, &[]);
    assert!(out.status.success());
    assert!(
        stderr(&out).contains("every compliance is negative"),
        "{}",
        stderr(&out)
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("not physical"));
    assert_no_nan(&out);
    let r = json(&identify("flip-json", &flipped, &["--json"]));
    assert_eq!(
        r["physical"],
        serde_json::json!([false, false, false, false, false, false])
    );
    let bounded = identify("flip-nn", &flipped, &["--nonnegative"]);
    assert_no_nan(&bounded);
    let text = String::from_utf8_lossy(&bounded.stdout);
    assert!(
        text.contains("bounds h >= 0 active on joints 1, 2, 3, 4, 5, 6"),
        "{text}"
    );
    let r = json(&identify(
        "flip-nn-json",
        &flipped,
        &["--nonnegative", "--json"],
    ));
    assert_eq!(
        r["active_bounds"],
        serde_json::json!([true, true, true, true, true, true])
    );
    assert_eq!(r["method"], "nonnegative-least-squares");
    assert!(
        r["stiffness_nm_per_rad"][0].is_null(),
        "infinite stiffness is null in JSON"
    );
}

#[test]
fn nonnegative_on_the_original_is_the_least_squares_fit() {
    let data = std::fs::read_to_string(fanuc_csv()).unwrap();
    let plain = json(&identify("nn-plain", &data, &["--json"]));
    let bounded = json(&identify("nn-bounded", &data, &["--json", "--nonnegative"]));
    assert_eq!(
        bounded["active_bounds"],
        serde_json::json!([false, false, false, false, false, false])
    );
    for j in 0..6 {
        let (a, b) = (
            plain["stiffness_nm_per_rad"][j].as_f64().unwrap(),
            bounded["stiffness_nm_per_rad"][j].as_f64().unwrap(),
        );
        assert!((a - b).abs() < 1e-9 * a, "joint {}: {a} vs {b}", j + 1);
    }
}

#[test]
fn few_postures_print_no_nan() {
    for keep in [[0usize, 1, 2], [5, 20, 40], [10, 16, 23]] {
        let text = fanuc_edited(|i| keep.contains(&i), |_, _| {});
        let out = identify("three", &text, &[]);
        assert!(out.status.success(), "{}", stderr(&out));
        assert_no_nan(&out);
        let out = identify("three-nn", &text, &["--nonnegative"]);
        assert_no_nan(&out);
    }
}

#[test]
fn cross_validation_reports_folds_spread_and_influential_postures() {
    let data = std::fs::read_to_string(fanuc_csv()).unwrap();
    let r = json(&identify("cv", &data, &["--cross-validate", "--json"]));
    let cv = &r["cross_validation"];
    assert_eq!(cv["folds"], 43);
    assert_eq!(cv["per_fold"].as_array().unwrap().len(), 43);
    let explained = cv["explained"].as_f64().unwrap();
    assert!(explained > 0.5 && explained < 1.0, "{explained}");
    let spread = cv["stiffness_std_nm_per_rad"][0].as_f64().unwrap();
    assert!(spread > 0.0 && spread < 0.05 * 860_896.0, "{spread}");
    let r = json(&identify("cv5", &data, &["--folds", "5", "--json"]));
    assert_eq!(r["cross_validation"]["folds"], 5);
    let text = identify("cv-text", &data, &["--cross-validate"]);
    let stdout = String::from_utf8_lossy(&text.stdout);
    assert!(
        stdout.contains("leave one posture out") && stdout.contains("influential"),
        "{stdout}"
    );
    for folds in ["1", "44"] {
        assert_usage_error(
            &identify("cv-bad", &data, &["--folds", folds]),
            &["folds", "expected 2 to 43"],
        );
    }
}

#[test]
fn bad_cases_end_in_one_clear_error() {
    let zero = fanuc_edited(|_| true, |_, f| scaled(f, 11..14, 0.0));
    assert_usage_error(
        &identify("zero", &zero, &[]),
        &["every measured displacement is zero"],
    );
    let huge = fanuc_edited(
        |_| true,
        |i, f| {
            if i == 6 {
                f[11] = "1e308".into()
            }
        },
    );
    assert_usage_error(
        &identify("huge", &huge, &[]),
        &["line 8, column 12 (dx_mm)", "above the limit"],
    );
    let force = fanuc_edited(
        |_| true,
        |i, f| {
            if i == 2 {
                f[9] = "-2e6".into()
            }
        },
    );
    assert_usage_error(
        &identify("force", &force, &[]),
        &["line 4, column 9 (fx_n)", "above the limit"],
    );
    let tracker = fanuc_edited(|_| true, |_, _| {}).replacen(
        "dx_mm,dy_mm,dz_mm",
        "dx_tracker_mm,dy_tracker_mm,dz_tracker_mm",
        1,
    );
    assert_usage_error(&identify("tracker", &tracker, &[]), &["base_from_tracker"]);
    let both = fanuc_edited(|_| true, |_, _| {}).replacen("fx_n", "fx_tool_n", 1);
    assert_usage_error(
        &identify("mixed", &both, &[]),
        &[
            "line 1",
            "fx_n,fy_n,fz_n",
            "fx_tool_n,fy_tool_n,fz_tool_n",
            "not both",
        ],
    );
}

#[test]
fn validate_prints_the_measured_deflection_and_the_share_explained() {
    let dir = temp_dir("trust-validate");
    let k = write_file(
        &dir,
        "k.json",
        r#"{"stiffness_nm_per_rad": [860896, 2719583, 1959760, 270828, 424693, 206020]}"#,
    );
    let r = json(&validate_fanuc(&k, &["--json"]));
    let (rms, measured) = (
        r["rms_delta_b_mm"].as_f64().unwrap(),
        r["rms_measured_mm"].as_f64().unwrap(),
    );
    assert!((r["explained"].as_f64().unwrap() - (1.0 - rms / measured)).abs() < 1e-12);
    assert!(measured > 1.0 && measured < 3.0, "{measured}");
    let text = validate_fanuc(&k, &[]);
    assert!(String::from_utf8_lossy(&text.stdout)
        .contains("share of the measured deflection the model explains"));
    std::fs::remove_dir_all(&dir).unwrap();
}
