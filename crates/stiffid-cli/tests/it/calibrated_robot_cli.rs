//! The calibrated robot everywhere: the robot file `calibrate --out` writes, named as a robot or
//! as a setup's `robot`, is what `kinematics`, `predict`,
//! `evaluate`, `select` and `compensate` use. Noise-free readings of a robot with known errors
//! (0.5 mm and 0.5 mrad on joints 2-5): the calibrated positions are the true ones.

use crate::calibrate_cli::{model, postures, readings, truth, SETUP};
use crate::common::{json, numbers, stiffid, temp_dir, write_file};
use nalgebra::{DVector, Vector3, Vector6};
use std::path::{Path, PathBuf};
use stiffid::app::purpose::{self, CalibrationOptions};
use stiffid::internal::metrology::calibration::ErrorModel;

/// Calibrates on noise-free readings in `d`: the robot file, the error model and the true values.
fn calibrated(d: &Path) -> (PathBuf, ErrorModel, DVector<f64>) {
    let model = model();
    let x = truth(&model);
    let tracker = crate::calibrate_cli::tracker();
    let data = write_file(
        d,
        "fit.csv",
        &readings(&model, &x, &tracker, &postures(25, 1)),
    );
    let robot = d.join("robot.toml");
    json(&stiffid(&[
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        data.to_str().unwrap(),
        "--out",
        robot.to_str().unwrap(),
        "--json",
    ]));
    (robot, model, x)
}

/// The built-in setup with a cutting tool's centre point and its robot replaced by `robot`.
fn setup_text(robot: &str) -> String {
    (stiffid::internal::setup::builtin_text(SETUP).unwrap())
        .replace(
            "robot = \"comau-smart5-nj165-3.0\"",
            &format!("robot = \"{robot}\""),
        )
        .replace("[tool]\n", "[tool]\ntcp_mm = [0.0, 0.0, 300.0]\n")
}

/// [`setup_text`] written to `d`, with `robot` a file name in `d`.
fn setup_with(d: &Path, name: &str, robot: &str) -> PathBuf {
    write_file(d, name, &setup_text(robot))
}

/// [`setup_text`] in the library, with the robot `robot` (a robot file, read here) or the preset.
fn library_setup(robot: Option<&Path>) -> stiffid::Setup {
    let text = setup_text(match robot {
        Some(_) => "robot.toml",
        None => "comau-smart5-nj165-3.0",
    });
    stiffid::internal::setup::parse(&text, "setup.toml", |name, _| match robot {
        Some(path) => {
            stiffid::internal::robot::file::parse(&std::fs::read_to_string(path).unwrap(), name)
        }
        None => stiffid::internal::robot::presets::get(name),
    })
    .unwrap()
}

fn deg(q: &Vector6<f64>) -> String {
    let v: Vec<String> = q.iter().map(|v| format!("{:?}", v.to_degrees())).collect();
    v.join(",")
}

fn mm(v: &[f64]) -> Vector3<f64> {
    Vector3::new(v[0], v[1], v[2]) * 1e-3
}

#[test]
fn kinematics_and_predict_reproduce_the_calibrated_positions() {
    let d = temp_dir("calibrated-kinematics");
    let (robot, model, x) = calibrated(&d);
    let setup = setup_with(&d, "calibrated.toml", "robot.toml");
    let nominal = stiffid::internal::setup::builtin(SETUP).unwrap();
    for (i, q) in postures(4, 7).iter().enumerate() {
        let q = Vector6::from_iterator(q.iter().map(|v| v.to_radians()));
        for k in 0..model.points() {
            let want = model.positions(&x, &[(q, k)]).unwrap()[0];
            let point = model.point(&x, k) * 1e3;
            let point = format!("{:?},{:?},{:?}", point.x, point.y, point.z);
            let doc = json(&stiffid(&[
                "kinematics",
                "--robot",
                robot.to_str().unwrap(),
                "--q-deg",
                &deg(&q),
                "--point-mm",
                &point,
                "--json",
            ]));
            let got = mm(&numbers(&doc["point_position_mm"]));
            assert!((got - want).norm() < 1e-12, "{i} {k}: {got} {want}");
        }
        // predict on the setup whose robot is the calibrated file: every measuring point where
        // the calibrated robot puts it, the nominal robot 0.1 mm and more away.
        let doc = json(&stiffid(&[
            "predict",
            "--setup",
            setup.to_str().unwrap(),
            "--q-deg",
            &deg(&q),
            "--wrench",
            "300,-200,-500",
            "--json",
        ]));
        let frames = nominal.robot().frames(&q);
        for (k, p) in doc["measuring_points"]
            .as_array()
            .unwrap()
            .iter()
            .enumerate()
        {
            let got = mm(&numbers(&p["position_mm"]));
            let want = model.positions(&x, &[(q, k)]).unwrap()[0];
            assert!((got - want).norm() < 1e-12, "predict {i} {k}: {got} {want}");
            let off = frames.point(&nominal.tool().measuring_points[k]);
            assert!(
                (off - want).norm() > 1e-4,
                "{i} {k}: the errors move the point"
            );
        }
    }
}

#[test]
fn evaluate_and_select_design_on_the_calibrated_robot() {
    let d = temp_dir("calibrated-design");
    let (robot, _, _) = calibrated(&d);
    let setup = setup_with(&d, "calibrated.toml", "robot.toml");
    let group = postures(10, 3);
    let mut csv = String::from("posture,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg\n");
    for (i, q) in group.iter().enumerate() {
        let v: Vec<String> = q.iter().map(|v| format!("{v:?}")).collect();
        csv += &format!("{},{}\n", i + 1, v.join(","));
    }
    let start = write_file(&d, "group.csv", &csv);
    let q: Vec<Vector6<f64>> = (group.iter())
        .map(|q| Vector6::from_iterator(q.iter().map(|v| v.to_radians())))
        .collect();
    let options = CalibrationOptions::default();
    let on = |s: &stiffid::Setup, q: &[Vector6<f64>]| {
        let c = purpose::design(s, &options).unwrap().evaluate(q).unwrap();
        c.predicted_rms * 1e3
    };
    let calibrated = library_setup(Some(&robot));
    let want = on(&calibrated, &q);
    let nominal = on(&library_setup(None), &q);
    assert!((want - nominal).abs() > 1e-6 * want, "{want} {nominal}");
    let doc = json(&stiffid(&[
        "evaluate",
        "--setup",
        setup.to_str().unwrap(),
        "--postures",
        start.to_str().unwrap(),
        "--for",
        "calibration",
        "--json",
    ]));
    let got = doc["calibration"]["predicted_rms_mm"].as_f64().unwrap();
    assert!((got - want).abs() <= 1e-9 * want, "evaluate: {got} {want}");
    let out = d.join("selected.csv");
    let doc = json(&stiffid(&[
        "select",
        "--setup",
        setup.to_str().unwrap(),
        "--for",
        "calibration",
        "--start",
        start.to_str().unwrap(),
        "--max-evals",
        "40",
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]));
    let chosen: Vec<Vector6<f64>> = (doc["postures_deg"].as_array().unwrap().iter())
        .map(|q| Vector6::from_iterator(numbers(q).iter().map(|v| v.to_radians())))
        .collect();
    let got = doc["calibration"]["predicted_rms_mm"].as_f64().unwrap();
    let want = on(&calibrated, &chosen);
    assert!((got - want).abs() <= 1e-9 * want, "select: {got} {want}");
    assert!(got < on(&calibrated, &q), "the search improved the start");
    // The text gives the minimised predicted error in mm (the document's `value` is in m).
    let value_mm = doc["value"].as_f64().unwrap() * 1e3;
    assert!((value_mm - got).abs() <= 1e-9 * got, "{value_mm} {got}");
    let text = String::from_utf8(
        stiffid(&[
            "select",
            "--setup",
            setup.to_str().unwrap(),
            "--for",
            "calibration",
            "--start",
            start.to_str().unwrap(),
            "--max-evals",
            "40",
            "--out",
            d.join("selected-text.csv").to_str().unwrap(),
        ])
        .stdout,
    )
    .unwrap();
    let line = (text.lines())
        .find(|l| l.starts_with("calibration test-pose (predicted RMS error, mm): "))
        .unwrap_or_else(|| panic!("{text}"));
    let shown: f64 = line
        .split("-> ")
        .nth(1)
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!((shown - got).abs() <= 1e-6, "{line}: {got} mm");
}

#[test]
fn compensate_lands_on_the_target_with_the_calibrated_robot() {
    let d = temp_dir("calibrated-compensate");
    let (robot, _, _) = calibrated(&d);
    let stiffness = write_file(
        &d,
        "k.json",
        r#"{"stiffness_nm_per_rad": [950000, 3000000, 900000, 250000, 200000, 150000]}"#,
    );
    let calibrated = library_setup(Some(&robot));
    let nominal = library_setup(None);
    let tcp = calibrated.tool().tcp;
    // Target poses: where the calibrated robot puts its TCP near the first test posture.
    let mut path = String::from("x_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg,fx_n,fy_n,fz_n,frame\n");
    let mut targets = Vec::new();
    for i in 0..5 {
        let mut q = calibrated.test_postures()[0];
        q[0] += 0.02 * i as f64;
        let pose = stiffid::internal::robot::ik::tool_pose(&calibrated.robot().frames(&q), &tcp);
        let (rx, ry, rz) = pose.rotation.euler_angles();
        let t = pose.translation.vector * 1e3;
        path += &format!(
            "{:?},{:?},{:?},{:?},{:?},{:?},-300,200,-400,tool\n",
            t.x,
            t.y,
            t.z,
            rx.to_degrees(),
            ry.to_degrees(),
            rz.to_degrees()
        );
        targets.push(pose);
    }
    let path = write_file(&d, "path.csv", &path);
    let run = |setup: &Path, out: &str| {
        let out = d.join(out);
        let doc = json(&stiffid(&[
            "compensate",
            "--setup",
            setup.to_str().unwrap(),
            "--stiffness",
            stiffness.to_str().unwrap(),
            "--path",
            path.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--json",
        ]));
        (doc, std::fs::read_to_string(out).unwrap())
    };
    let setup = setup_with(&d, "calibrated.toml", "robot.toml");
    let (doc, csv) = run(&setup, "calibrated.csv");
    assert!(doc["summary"]["max_residual_um"].as_f64().unwrap() < 0.1);
    // The job's own check (the loaded calibrated robot at the compensated angles) is exact;
    // independently, the calibrated robot at those angles moved by the TCP's deflection there
    // is at the target to first order in the deflection (its second-order term about 1 um
    // here), where the nominal robot misses by the calibration's size.
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let column = |row: &[f64], name: &str| row[header.iter().position(|h| *h == name).unwrap()];
    for (line, target) in csv.lines().skip(1).zip(&targets) {
        let row: Vec<f64> = (line.split(','))
            .map(|v| v.parse().unwrap_or(f64::NAN))
            .collect();
        let qc = Vector6::from_fn(|i, _| column(&row, &format!("qc{}_deg", i + 1)).to_radians());
        let deflection =
            Vector3::from_fn(|i, _| column(&row, ["dx_mm", "dy_mm", "dz_mm"][i]) * 1e-3);
        let reached =
            stiffid::internal::robot::ik::tool_pose(&calibrated.robot().frames(&qc), &tcp)
                .translation
                .vector
                + deflection;
        let e = (reached - target.translation.vector).norm();
        assert!(e < 5e-6, "{e} m from the target");
        // The nominal robot at those angles misses by the calibration's size.
        let off = stiffid::internal::robot::ik::tool_pose(&nominal.robot().frames(&qc), &tcp);
        assert!((off.translation.vector + deflection - target.translation.vector).norm() > 1e-4);
    }
}
