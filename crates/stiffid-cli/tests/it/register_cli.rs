//! `stiffid register`: readings of a known tracker transform give it back, with the fragment the
//! setup reads; bad readings exit 2 naming the file, line and column.

use crate::common;

use common::{assert_usage_error, json, stiffid, temp_dir, write_file};
use nalgebra::{Isometry3, Point3, Vector3, Vector6};

/// Readings of the paper setup's four measuring points in three postures, seen by a tracker at
/// `truth` (base_from_tracker).
fn readings(truth: &Isometry3<f64>) -> String {
    shifted_readings(truth, Vector3::zeros())
}

/// As [`readings`] with every measuring point shifted by `shift` (flange frame, m).
fn shifted_readings(truth: &Isometry3<f64>, shift: Vector3<f64>) -> String {
    let setup = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    let mut text = stiffid::internal::io::readings::header() + "\n";
    let postures = [
        [0.0, 0.0, -90.0, 0.0, 30.0, 0.0],
        [35.0, -20.0, -110.0, 40.0, -30.0, 60.0],
        [-40.0, 15.0, -70.0, -60.0, 45.0, -90.0],
        [10.0, -30.0, -120.0, 90.0, 60.0, 30.0],
    ];
    for (i, q_deg) in postures.iter().enumerate() {
        let q = Vector6::from_iterator(q_deg.iter().map(|d: &f64| d.to_radians()));
        let frames = setup.robot().frames(&q);
        for (k, p) in setup.tool().measuring_points.iter().enumerate() {
            let t = truth.inverse() * Point3::from(frames.point(&(p + shift)));
            let q: Vec<String> = q_deg.iter().map(|v| v.to_string()).collect();
            text += &format!(
                "P{},{},{},{:.9},{:.9},{:.9}\n",
                i + 1,
                k + 1,
                q.join(","),
                t.x * 1e3,
                t.y * 1e3,
                t.z * 1e3
            );
        }
    }
    text
}

#[test]
fn register_gives_the_transform_back_and_writes_the_fragment() {
    let d = temp_dir("register");
    let truth = Isometry3::new(Vector3::new(3.0, -2.0, 1.5), Vector3::new(0.0, 0.0, 2.5));
    let data = write_file(&d, "readings.csv", &readings(&truth));
    let out = d.join("tracker.toml");
    let args = [
        "register",
        "--setup",
        "zhang2021-comau-nj165",
        "--data",
        data.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--json",
    ];
    let doc = json(&stiffid(&args));
    let xyz: Vec<f64> = serde_json::from_value(doc["xyz_mm"].clone()).unwrap();
    for (got, want) in xyz.iter().zip([3000.0, -2000.0, 1500.0]) {
        assert!((got - want).abs() < 1e-5, "{got} {want}");
    }
    assert!(doc["residual_rms_mm"].as_f64().unwrap() < 1e-5);
    assert_eq!(doc["points"].as_array().unwrap().len(), 16);
    let fragment = std::fs::read_to_string(&out).unwrap();
    assert_eq!(fragment, doc["fragment"].as_str().unwrap());
    let setup = String::from_utf8(stiffid(&["setups", "show", "zhang2021-comau-nj165"]).stdout)
        .unwrap()
        + "\n"
        + &fragment;
    let s = stiffid::internal::setup::parse(&setup, "s.toml", |r, _| {
        stiffid::internal::robot::presets::get(r)
    })
    .unwrap();
    let back = s.tracker().unwrap().base_from_tracker.unwrap();
    assert!(back.rotation.angle_to(&truth.rotation) < 1e-8);
}

#[test]
fn bad_readings_exit_2_naming_file_line_and_column() {
    let d = temp_dir("register-bad");
    let truth = Isometry3::identity();
    let text = readings(&truth).replacen("P2,1,35", "P2,1,x", 1);
    let data = write_file(&d, "readings.csv", &text);
    let args = ["register", "--setup", "zhang2021-comau-nj165", "--data"];
    let out = stiffid(&[&args[..], &[data.to_str().unwrap()]].concat());
    assert_eq!(out.status.code(), Some(2));
    let e = String::from_utf8(out.stderr).unwrap();
    assert!(
        e.contains("readings.csv: line 6, column 3 (q1_deg): 'x' is not a finite number"),
        "{e}"
    );
    let line = readings(&truth)
        .lines()
        .take(3)
        .collect::<Vec<_>>()
        .join("\n");
    let data = write_file(&d, "two.csv", &line);
    let out = stiffid(&[&args[..], &[data.to_str().unwrap()]].concat());
    assert_eq!(out.status.code(), Some(2));
    let e = String::from_utf8(out.stderr).unwrap();
    assert!(
        e.contains("two.csv: points: 2 given: a registration needs at least 3"),
        "{e}"
    );
    // The proposal's options mean nothing with readings: refused, named.
    for option in ["--seed", "--candidates", "--restarts"] {
        let out = stiffid(&[&args[..], &[data.to_str().unwrap(), option, "5"]].concat());
        assert_usage_error(&out, &[option, "cannot be used with", "--data"]);
    }
}

#[test]
fn calibrate_cell_finds_tool_points_shifted_by_2_mm() {
    let d = temp_dir("calibrate-cell");
    let truth = Isometry3::new(Vector3::new(3.0, -2.0, 1.5), Vector3::new(0.0, 0.0, 2.5));
    let shift = Vector3::new(2e-3, 0.0, 0.0);
    let data = write_file(&d, "readings.csv", &shifted_readings(&truth, shift));
    let out = d.join("cell.toml");
    let args = [
        "calibrate-cell",
        "--setup",
        "zhang2021-comau-nj165",
        "--data",
        data.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--json",
    ];
    let doc = json(&stiffid(&args));
    for p in doc["points"].as_array().unwrap() {
        let s: Vec<f64> = serde_json::from_value(p["shift_mm"].clone()).unwrap();
        assert!(
            (s[0] - 2.0).abs() < 1e-5 && s[1].abs() < 1e-5 && s[2].abs() < 1e-5,
            "{s:?}"
        );
    }
    assert!(doc["absolute_error_rms_mm"].as_f64().unwrap() < 1e-5);
    let fragment = std::fs::read_to_string(&out).unwrap();
    assert_eq!(fragment, doc["fragment"].as_str().unwrap());
    assert!(fragment.contains("[tracker]") && fragment.contains("measuring_points_mm"));
    let text = String::from_utf8(stiffid(&args[..5]).stdout).unwrap();
    assert!(text.contains("robot's unloaded absolute error"), "{text}");
}

#[test]
fn proposed_postures_filled_in_register_the_tracker() {
    let d = temp_dir("register-postures");
    let template = d.join("template.csv");
    let cell = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/cell/zhang2021-tracker.toml");
    let args = [
        "register",
        "--setup",
        cell.to_str().unwrap(),
        "--count",
        "3",
        "--candidates",
        "500",
        "--out",
        template.to_str().unwrap(),
        "--json",
    ];
    let doc = json(&stiffid(&args));
    assert_eq!(doc["postures"].as_array().unwrap().len(), 3);
    let total = doc["rotation_std_total_deg"].as_f64().unwrap();
    assert!(
        total
            < doc["random_median_rotation_std_total_deg"]
                .as_f64()
                .unwrap()
    );
    let text = std::fs::read_to_string(&template).unwrap();
    assert_eq!(text, doc["readings_template"].as_str().unwrap());
    // The operator's readings: the tracker at its place in the cell, turned by 180 deg.
    let truth = Isometry3::new(
        Vector3::new(3.0, -2.0, 1.5),
        Vector3::new(0.0, 0.0, std::f64::consts::PI),
    );
    let setup = stiffid::internal::setup::parse(
        &std::fs::read_to_string(&cell).unwrap(),
        "cell.toml",
        |r, _| stiffid::internal::robot::presets::get(r),
    )
    .unwrap();
    let mut filled = String::new();
    for line in text.lines() {
        let cells: Vec<&str> = line.split(',').collect();
        let Ok(point) = cells[1].parse::<usize>() else {
            filled += &format!("{line}\n");
            continue;
        };
        let q = Vector6::from_iterator(cells[2..8].iter().map(|v| {
            let deg: f64 = v.parse().unwrap();
            deg.to_radians()
        }));
        let p = setup.tool().measuring_points[point - 1];
        let t = truth.inverse() * Point3::from(setup.robot().frames(&q).point(&p));
        let head = cells[..8].join(",");
        filled += &format!("{head},{},{},{}\n", t.x * 1e3, t.y * 1e3, t.z * 1e3);
    }
    let data = write_file(&d, "filled.csv", &filled);
    let args = [
        "register",
        "--setup",
        cell.to_str().unwrap(),
        "--data",
        data.to_str().unwrap(),
        "--json",
    ];
    let fit = json(&stiffid(&args));
    let xyz: Vec<f64> = serde_json::from_value(fit["xyz_mm"].clone()).unwrap();
    for (got, want) in xyz.iter().zip([3000.0, -2000.0, 1500.0]) {
        assert!((got - want).abs() < 1e-3, "{got} {want}");
    }
    let out = stiffid(&[
        "register",
        "--setup",
        "zhang2021-comau-nj165",
        "--count",
        "0",
    ]);
    assert_eq!(out.status.code(), Some(2));
}

/// `text` with each data row's tracker x negated (a mirror image), or its z shifted by `dz_mm`
/// on the row of `line`.
fn edited(text: &str, edit: impl Fn(usize, &mut Vec<f64>)) -> String {
    let mut out = String::new();
    for (i, row) in text.lines().enumerate() {
        let cells: Vec<&str> = row.split(',').collect();
        let Ok(mut xyz) = cells[8..]
            .iter()
            .map(|v| v.parse::<f64>())
            .collect::<Result<Vec<f64>, _>>()
        else {
            out += &format!("{row}\n");
            continue;
        };
        edit(i + 1, &mut xyz);
        let xyz: Vec<String> = xyz.iter().map(|v| format!("{v:.9}")).collect();
        out += &format!("{},{}\n", cells[..8].join(","), xyz.join(","));
    }
    out
}

#[test]
fn mirrored_readings_and_far_residuals_are_refused_unless_forced() {
    let d = temp_dir("register-suspect");
    let truth = Isometry3::new(Vector3::new(3.0, -2.0, 1.5), Vector3::new(0.0, 0.0, 2.5));
    let mirrored = write_file(
        &d,
        "mirrored.csv",
        &edited(&readings(&truth), |_, v| v[0] = -v[0]),
    );
    let far = edited(&readings(&truth), |line, v| {
        if line == 6 {
            v[2] += 50.0
        }
    });
    let far = write_file(&d, "far.csv", &far);
    let out = d.join("tracker.toml");
    for command in ["register", "calibrate-cell"] {
        let run = |data: &std::path::Path, force: bool| {
            let mut args = vec![
                command,
                "--setup",
                "zhang2021-comau-nj165",
                "--data",
                data.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
            ];
            if force {
                args.push("--force");
            }
            stiffid(&args)
        };
        let refused = run(&mirrored, false);
        assert_eq!(refused.status.code(), Some(2), "{command}");
        let e = String::from_utf8(refused.stderr).unwrap();
        assert!(
            e.contains("mirrored.csv: readings: the tracker's readings are a mirror image")
                && e.contains("--force"),
            "{command}: {e}"
        );
        assert!(!out.exists(), "{command}: nothing written");
        let refused = run(&far, false);
        assert_eq!(refused.status.code(), Some(2), "{command}");
        let e = String::from_utf8(refused.stderr).unwrap();
        assert!(
            e.contains("far.csv: line 6 (posture P2, point 1), residual_norm_mm: ")
                && e.contains("expected at most 10.000 mm"),
            "{command}: {e}"
        );
        assert!(!out.exists(), "{command}: nothing written");
        let forced = run(&far, true);
        assert_eq!(forced.status.code(), Some(0), "{command}: {forced:?}");
        assert!(out.exists(), "{command}: forced, the fragment is written");
        std::fs::remove_file(&out).unwrap();
    }
}
