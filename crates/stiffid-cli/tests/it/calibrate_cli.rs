//! `stiffid calibrate`: noise-free readings of a robot with known errors give a calibration that
//! predicts held-out readings to rounding, write robot files that reproduce them, and agree with
//! `calibrate-cell` when only the cell is fitted.

use crate::common;

use common::{assert_success, assert_usage_error, json, refused, stiffid, temp_dir, write_file};
use nalgebra::{DVector, Isometry3, Point3, Vector3, Vector6};
use serde_json::Value;
use std::path::Path;
use stiffid::internal::metrology::calibration::error_model::MeasuredIn;
use stiffid::internal::metrology::calibration::{gravity, ErrorModel, Geometry};
use stiffid::Setup;

pub(crate) const SETUP: &str = "zhang2021-comau-nj165";

/// Postures spread over the COMAU's range, deg.
pub(crate) fn postures(n: usize, seed: u64) -> Vec<[f64; 6]> {
    let mut state = seed;
    let mut next = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    (0..n)
        .map(|_| {
            [
                100.0 * next(),
                60.0 * next(),
                -90.0 + 60.0 * next(),
                200.0 * next(),
                60.0 + 60.0 * next(),
                200.0 * next(),
            ]
        })
        .collect()
}

pub(crate) fn model() -> ErrorModel {
    let setup = stiffid::internal::setup::builtin(SETUP).unwrap();
    let robot = setup.robot();
    ErrorModel::new(
        robot,
        &setup.tool().measuring_points,
        MeasuredIn::Tracker,
        Geometry::Full,
        gravity::Terms::none(robot),
    )
    .unwrap()
}

/// The true errors: 0.5 mm and 0.5 mrad on the four (M)DH errors of joints 2-5.
pub(crate) fn truth(model: &ErrorModel) -> DVector<f64> {
    let mut x = model.nominal();
    for (c, p) in model.parameters().iter().enumerate() {
        let joint = ["joint2.", "joint3.", "joint4.", "joint5."];
        let dh = [".a", ".alpha", ".theta"];
        if joint.iter().any(|j| p.name.starts_with(j)) && dh.iter().any(|e| p.name.ends_with(e)) {
            x[c] += 5e-4 * if c % 2 == 0 { 1.0 } else { -1.0 };
        }
    }
    x
}

/// The campaigns' tracker: 3 m ahead of the base, 2 m to its right, 1.5 m up, turned 2.5 rad
/// about the vertical.
pub(crate) fn tracker() -> Isometry3<f64> {
    Isometry3::new(Vector3::new(3.0, -2.0, 1.5), Vector3::new(0.0, 0.0, 2.5))
}

/// Readings of every measuring point at `postures`, by a tracker at `tracker`.
pub(crate) fn readings(
    model: &ErrorModel,
    x: &DVector<f64>,
    tracker: &Isometry3<f64>,
    qs: &[[f64; 6]],
) -> String {
    let mut text = stiffid::internal::io::readings::header() + "\n";
    for (i, q_deg) in qs.iter().enumerate() {
        let q = Vector6::from_iterator(q_deg.iter().map(|d| d.to_radians()));
        for k in 0..model.points() {
            let b = model.positions(x, &[(q, k)]).unwrap()[0];
            let t = tracker.inverse() * Point3::from(b);
            let q: Vec<String> = q_deg.iter().map(|v| format!("{v:?}")).collect();
            text += &format!(
                "P{},{},{},{:?},{:?},{:?}\n",
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

/// The fitted readings given as the held-out ones would judge nothing: refused, naming them.
#[test]
fn the_fitted_readings_are_refused_as_held_out_ones() {
    let d = temp_dir("calibrate-same");
    let model = model();
    let (x, tracker) = (truth(&model), tracker());
    let data = write_file(
        &d,
        "fit.csv",
        &readings(&model, &x, &tracker, &postures(25, 1)),
    );
    let data = data.to_str().unwrap();
    let args = [
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        data,
        "--validate",
        data,
    ];
    let args = [&args[..], &["--out", "{dir}/robot.toml"]].concat();
    refused(
        &d,
        &args,
        &[
            "validate",
            "fit.csv: the same readings as the fitted /",
            "judged on",
        ],
    );
}

#[test]
fn calibrate_predicts_held_out_readings_and_writes_robot_files() {
    let d = temp_dir("calibrate");
    let model = model();
    let x = truth(&model);
    let tracker = tracker();
    let data = write_file(
        &d,
        "fit.csv",
        &readings(&model, &x, &tracker, &postures(25, 1)),
    );
    let held = write_file(
        &d,
        "held.csv",
        &readings(&model, &x, &tracker, &postures(10, 2)),
    );
    let robot = d.join("robot.toml");
    let args = [
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        data.to_str().unwrap(),
        "--validate",
        held.to_str().unwrap(),
        "--out",
        robot.to_str().unwrap(),
        "--json",
    ];
    let doc = json(&stiffid(&args));
    assert!(
        doc["residual_rms_mm"].as_f64().unwrap() < 1e-6,
        "{}",
        doc["residual_rms_mm"]
    );
    assert!(doc["nominal_rms_mm"].as_f64().unwrap() > 0.1);
    let v = &doc["validation"];
    assert!(v["rms_mm"].as_f64().unwrap() < 1e-6, "{v}");
    assert!(v["nominal_rms_mm"].as_f64().unwrap() > 0.1);
    assert_eq!(v["errors"].as_array().unwrap().len(), 10 * model.points());
    // The RMS within and beyond the fitted ranges: the readings flagged `outside_range`
    // counted, the two parts' squares adding up to the whole's.
    let errors = v["errors"].as_array().unwrap();
    let beyond = errors
        .iter()
        .filter(|e| !e["outside_range"].is_null())
        .count();
    assert_eq!(v["beyond_range_readings"].as_u64(), Some(beyond as u64));
    let part = |key: &str, n: usize| v[key].as_f64().map_or(0.0, |r| r * r * n as f64);
    let whole =
        part("within_range_rms_mm", errors.len() - beyond) + part("beyond_range_rms_mm", beyond);
    let rms = v["rms_mm"].as_f64().unwrap();
    assert!(
        (whole - rms * rms * errors.len() as f64).abs() < 1e-12,
        "{v}"
    );
    // 6R arm, 4 points: 24 + 12.
    assert_eq!(doc["rank"].as_u64(), Some(36));
    let merged: Vec<&str> = (doc["merged"].as_array().unwrap().iter())
        .map(|m| m["name"].as_str().unwrap())
        .collect();
    assert!(
        merged.contains(&"joint1.theta") && merged.contains(&"joint6.d"),
        "{merged:?}"
    );
    let p = (doc["parameters"].as_array().unwrap().iter())
        .find(|p| p["name"] == "joint3.alpha")
        .unwrap();
    let want = x[model
        .parameters()
        .iter()
        .position(|q| q.name == "joint3.alpha")
        .unwrap()];
    assert!(
        (p["value"].as_f64().unwrap() - want.to_degrees()).abs() < 1e-9,
        "{p}"
    );
    assert_eq!(p["unit"], "deg");
    // The written robot file: the calibrated positions.
    let written =
        stiffid::internal::robot::file::parse(&std::fs::read_to_string(&robot).unwrap(), "r")
            .unwrap();
    let q = Vector6::new(0.3, -0.2, -1.4, 0.5, 0.9, -0.7);
    let c = model.point(&x, 1);
    let want = model.positions(&x, &[(q, 1)]).unwrap()[0];
    let got = written.frames(&q).point(&c);
    assert!((got - want).norm() < 1e-9, "{got:?} vs {want:?}");
    // The COMAU's axis map makes joint 3's angle of q2 and q3: no URDF joint turns so, and
    // --urdf-out is refused before anything is written.
    let empty = temp_dir("calibrate-no-urdf");
    refused(
        &empty,
        &[
            &args[..5],
            &["--out", "{dir}/r.toml", "--urdf-out", "{dir}/r.urdf"],
        ]
        .concat(),
        &["--urdf-out", "axis map", "q2 and q3", "--out"],
    );
    let text = String::from_utf8(stiffid(&args[..7]).stdout).unwrap();
    assert!(
        text.contains("held out") && text.contains("joint3.beta"),
        "{text}"
    );
}

#[test]
fn calibrate_without_geometry_is_calibrate_cell() {
    let d = temp_dir("calibrate-none");
    let model = model();
    let x = truth(&model);
    let tracker = Isometry3::new(Vector3::new(2.0, 1.0, 0.5), Vector3::new(0.1, 0.0, -1.0));
    let data = write_file(
        &d,
        "fit.csv",
        &readings(&model, &x, &tracker, &postures(12, 3)),
    );
    let data = data.to_str().unwrap();
    let cell = json(&stiffid(&[
        "calibrate-cell",
        "--setup",
        SETUP,
        "--data",
        data,
        "--json",
    ]));
    let doc = json(&stiffid(&[
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        data,
        "--geometry",
        "none",
        "--gravity",
        "none",
        "--json",
    ]));
    let (a, b) = (
        cell["absolute_error_rms_mm"].as_f64().unwrap(),
        doc["residual_rms_mm"].as_f64().unwrap(),
    );
    assert!((a - b).abs() < 1e-9 * a, "{a} vs {b}");
    for (k, p) in cell["points"].as_array().unwrap().iter().enumerate() {
        let fitted: Vec<f64> = serde_json::from_value(p["fitted_mm"].clone()).unwrap();
        for (i, axis) in ["x", "y", "z"].iter().enumerate() {
            let name = format!("point{}.{axis}", k + 1);
            let q = (doc["parameters"].as_array().unwrap().iter())
                .find(|q| q["name"] == name.as_str())
                .unwrap();
            assert!(
                (q["value"].as_f64().unwrap() - fitted[i]).abs() < 1e-7,
                "{name}"
            );
        }
    }
}

#[test]
fn calibrate_refuses_bad_input() {
    let d = temp_dir("calibrate-bad");
    let model = model();
    let x = truth(&model);
    let tracker = Isometry3::identity();
    // 2 postures of 4 points: 24 coordinates, nearly all explained by the parameters the two
    // postures can tell apart: a named warning.
    let few = write_file(
        &d,
        "few.csv",
        &readings(&model, &x, &tracker, &postures(2, 4)),
    );
    let out = stiffid(&[
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        few.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("few.csv") && err.contains("degrees of freedom"),
        "{err}"
    );
    // One posture: every coordinate explained, refused.
    let one = write_file(
        &d,
        "one.csv",
        &readings(&model, &x, &tracker, &postures(1, 5)),
    );
    let out = stiffid(&[
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        one.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("one.csv") && err.contains("read more postures"),
        "{err}"
    );
    let masses = stiffid(&[
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        few.to_str().unwrap(),
        "--gravity",
        "masses",
    ]);
    assert_eq!(masses.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&masses.stderr).contains("mass_kg"));
    // The job's typed option error, in the command's spelling.
    let tolerance = stiffid(&[
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        few.to_str().unwrap(),
        "--tolerance-mm=-1",
        "--tolerance-deg",
        "0.1",
    ]);
    assert_eq!(tolerance.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&tolerance.stderr),
        "error: --tolerance-mm, --tolerance-deg: expected [1e-6, 1000] mm and [1e-6, 90] deg, got -1 and 0.1\n"
    );
}

/// With known masses, `--stiffness-out` writes the fitted compliance as a stiffness file that
/// the readers take: noise-free readings of a robot whose joints 2-6 are 30 % more compliant than
/// the setup's nominal give them back (joint 1, vertical, keeps its nominal stiffness).
/// The COMAU preset with a mass and centre of mass on each joint, written to `robot.toml` in `d`.
fn robot_with_masses(d: &Path) -> String {
    let masses = [250.0, 180.0, 120.0, 60.0, 20.0, 40.0];
    let mut robot_text = String::new();
    for (i, part) in include_str!("../../../stiffid-core/presets/comau-smart5-nj165-3.0.toml")
        .split("[[joint]]\n")
        .enumerate()
    {
        robot_text += part;
        if i < 6 {
            robot_text += &format!(
                "[[joint]]\nmass_kg = {}\ncom_mm = [{}, 30.0, {}]\n",
                masses[i],
                100.0 + 50.0 * i as f64,
                -20.0 * i as f64
            );
        }
    }
    write_file(d, "robot.toml", &robot_text);
    robot_text
}

/// The nominal reference is the same with masses (`doc`) and without (`rigid`), and the held-out
/// one is `reference` (mm).
fn assert_nominal_reference(doc: &Value, rigid: &Value, reference: f64) {
    for key in ["nominal_rms_mm", "/validation/nominal_rms_mm"] {
        let (a, b) = match key.strip_prefix('/') {
            Some(p) => (
                doc.pointer(&format!("/{p}")),
                rigid.pointer(&format!("/{p}")),
            ),
            None => (doc.get(key), rigid.get(key)),
        };
        let (a, b) = (a.unwrap().as_f64().unwrap(), b.unwrap().as_f64().unwrap());
        assert!(
            (a - b).abs() <= 1e-9 * b,
            "{key}: {a} with masses, {b} without"
        );
    }
    let held_nominal = doc["validation"]["nominal_rms_mm"].as_f64().unwrap();
    assert!(
        (held_nominal - reference).abs() < 1e-6 * reference,
        "{held_nominal} vs {reference}"
    );
}

/// The stiffness file `k` gives back the compliance `springs` of joints 2-6 (joint 1 fixed, its
/// variance zero), noise-free readings to 1e-5 of it (the bound on the gravity terms, a prior
/// centred on the setup's nominal compliance, moves a noise-free fit by a few millionths).
fn assert_stiffness_file(k: &Path, setup: &Setup, springs: &Vector6<f64>) {
    let file =
        stiffid::internal::io::stiffness::parse(&std::fs::read_to_string(k).unwrap()).unwrap();
    let c = file.compliance(setup.model()).unwrap();
    for j in 0..6 {
        assert!(
            ((c.h[j] - springs[j]) / springs[j]).abs() < 1e-5,
            "joint {}: {:e} vs {:e}",
            j + 1,
            c.h[j],
            springs[j]
        );
    }
    let cov = c.covariance.unwrap();
    assert_eq!(cov[(0, 0)], 0.0);
    assert!((1..6).all(|j| cov[(j, j)] > 0.0));
}

#[test]
fn calibrate_with_masses_writes_the_stiffness_file() {
    let d = temp_dir("calibrate-stiffness");
    let setup = stiffid::internal::setup::builtin(SETUP).unwrap();
    let robot_text = robot_with_masses(&d);
    let setup_text = include_str!("../../../stiffid-core/setups/zhang2021-comau-nj165.toml")
        .replace(
            "robot = \"comau-smart5-nj165-3.0\"",
            "robot = \"robot.toml\"",
        );
    let setup_file = write_file(&d, "setup.toml", &setup_text);
    let robot = stiffid::internal::robot::file::parse(&robot_text, "robot.toml").unwrap();
    let nominal = setup.nominal_compliance().unwrap();
    let springs = Vector6::from_fn(|i, _| nominal[i] * if i == 0 { 1.0 } else { 1.3 });
    let g =
        gravity::Terms::masses(&robot, *robot.masses().unwrap(), setup.springs(), nominal).unwrap();
    let model = ErrorModel::new(
        &robot,
        &setup.tool().measuring_points,
        MeasuredIn::Tracker,
        Geometry::Full,
        g,
    )
    .unwrap();
    let mut x = truth(&model);
    let start = model.gravity_start();
    x.rows_mut(start, 6).copy_from(&springs);
    let tracker = tracker();
    let data = write_file(
        &d,
        "fit.csv",
        &readings(&model, &x, &tracker, &postures(30, 5)),
    );
    let held = write_file(
        &d,
        "held.csv",
        &readings(&model, &x, &tracker, &postures(8, 6)),
    );
    let k = d.join("k.json");
    let args = [
        "calibrate",
        "--setup",
        setup_file.to_str().unwrap(),
        "--data",
        data.to_str().unwrap(),
        "--validate",
        held.to_str().unwrap(),
        "--gravity",
        "masses",
        "--maps",
        "none",
        "--stiffness-out",
        k.to_str().unwrap(),
        "--json",
    ];
    let doc = json(&stiffid(&args));
    assert!(doc["residual_rms_mm"].as_f64().unwrap() < 1e-6, "{doc}");
    // The nominal reference is the rigid nominal robot whatever the model fitted: the same
    // without gravity, and its independent computation here (the tracker registered on the
    // nominal positions, their RMS error).
    let rigid = json(&stiffid(
        &[
            &args[..7],
            &["--gravity", "none", "--maps", "none", "--json"],
        ]
        .concat(),
    ));
    let nominal_model = ErrorModel::new(
        &robot,
        &setup.tool().measuring_points,
        MeasuredIn::Tracker,
        Geometry::None,
        gravity::Terms::none(&robot),
    )
    .unwrap();
    let reference = nominal_rms_mm(&nominal_model, &x, &model, &tracker, &postures(8, 6));
    assert_nominal_reference(&doc, &rigid, reference);
    assert_stiffness_file(&k, &setup, &springs);
    // Without a gravity model there is no compliance to write: refused, nothing written.
    let (setup_arg, data_arg) = (setup_file.to_str().unwrap(), data.to_str().unwrap());
    refused(
        &d,
        &[
            "calibrate",
            "--setup",
            setup_arg,
            "--data",
            data_arg,
            "--gravity",
            "none",
            "--maps",
            "none",
            "--stiffness-out",
            "{dir}/k2.json",
        ],
        &["--stiffness-out", "--gravity masses"],
    );
}

/// The RMS 3D error (mm) of the rigid nominal robot (`nominal`, Geometry::None) predicting the
/// readings of `truth` at `x` by a tracker at `tracker`, the tracker registered on them
/// (Umeyama, [`stiffid::internal::metrology::register::fit`]).
fn nominal_rms_mm(
    nominal: &ErrorModel,
    x: &DVector<f64>,
    truth: &ErrorModel,
    tracker: &Isometry3<f64>,
    qs: &[[f64; 6]],
) -> f64 {
    let mut pairs = Vec::new();
    for q_deg in qs {
        let q = Vector6::from_iterator(q_deg.iter().map(|d| d.to_radians()));
        for k in 0..truth.points() {
            let read = tracker.inverse() * Point3::from(truth.positions(x, &[(q, k)]).unwrap()[0]);
            let base = nominal.positions(&nominal.nominal(), &[(q, k)]).unwrap()[0];
            pairs.push((base, read.coords));
        }
    }
    let correspondences: Vec<_> = (pairs.iter())
        .map(
            |(base, tracker)| stiffid::internal::metrology::register::Correspondence {
                base: *base,
                tracker: *tracker,
            },
        )
        .collect();
    let t = stiffid::internal::metrology::register::fit(&correspondences)
        .unwrap()
        .base_from_tracker;
    let sum: f64 = (pairs.iter())
        .map(|(base, read)| (t * Point3::from(*read) - Point3::from(*base)).norm_squared())
        .sum();
    (sum / pairs.len() as f64).sqrt() * 1e3
}

/// Readings with load steps (`load_step`, the wrench in the base frame at the loading point):
/// every point of every posture unloaded and under two wrenches, by a tracker at `tracker`.
fn loaded_readings(
    model: &ErrorModel,
    x: &DVector<f64>,
    tracker: &Isometry3<f64>,
    qs: &[[f64; 6]],
) -> String {
    use stiffid::internal::metrology::calibration::error_model::Observation;
    let wrenches = [
        Vector6::zeros(),
        Vector6::new(800.0, -300.0, -1200.0, 0.0, 0.0, 0.0),
        Vector6::new(-500.0, 900.0, 400.0, 0.0, 0.0, 0.0),
    ];
    let mut text = stiffid::internal::io::readings::header_with_loads() + "\n";
    for (i, q_deg) in qs.iter().enumerate() {
        let q = Vector6::from_iterator(q_deg.iter().map(|d| d.to_radians()));
        for (step, wrench) in wrenches.iter().enumerate() {
            for k in 0..model.points() {
                let o = Observation {
                    posture: i,
                    point: k,
                    q,
                    measured: Vector3::zeros(),
                    wrench: *wrench,
                    e: stiffid::internal::robot::external::ExternalValues::NONE,
                    table: false,
                    direction: Vector6::zeros(),
                };
                let b = model.predict(x, &[o]).unwrap()[0];
                let t = tracker.inverse() * Point3::from(b);
                let q: Vec<String> = q_deg.iter().map(|v| format!("{v:?}")).collect();
                text += &format!(
                    "P{},{},{},{step},{:?},{:?},{:?},{:?},{:?},{:?}\n",
                    i + 1,
                    k + 1,
                    q.join(","),
                    wrench[0],
                    wrench[1],
                    wrench[2],
                    t.x * 1e3,
                    t.y * 1e3,
                    t.z * 1e3
                );
            }
        }
    }
    text
}

/// With loaded readings the drives' compliances are fitted with the geometry, whatever the
/// gravity model: `--stiffness-out` writes them (noise-free readings of a robot 30 % more
/// compliant than the setup's nominal give them back), and the text says how many readings.
#[test]
fn calibrate_with_loaded_readings_writes_the_stiffness_file() {
    let d = temp_dir("calibrate-loaded");
    let setup = stiffid::internal::setup::builtin(SETUP).unwrap();
    let model = model().with_loads(&setup).unwrap();
    let mut x = truth(&model);
    let columns = model.compliance_columns().unwrap().to_vec();
    for &c in &columns {
        x[c] *= 1.3;
    }
    let tracker = tracker();
    let data = write_file(
        &d,
        "loaded.csv",
        &loaded_readings(&model, &x, &tracker, &postures(25, 7)),
    );
    let k = d.join("k.json");
    let args = [
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        data.to_str().unwrap(),
        "--gravity",
        "lumped",
        "--stiffness-out",
        k.to_str().unwrap(),
        "--json",
    ];
    let doc = json(&stiffid(&args));
    assert!(doc["residual_rms_mm"].as_f64().unwrap() < 1e-6, "{doc}");
    assert_eq!(doc["readings"].as_u64(), Some(25 * 3 * 4));
    let p = (doc["parameters"].as_array().unwrap().iter())
        .find(|p| p["name"] == "compliance.k2")
        .unwrap();
    assert_eq!(
        (p["kind"].as_str(), p["unit"].as_str()),
        (Some("compliance"), Some("urad/(N m)"))
    );
    let file =
        stiffid::internal::io::stiffness::parse(&std::fs::read_to_string(&k).unwrap()).unwrap();
    let c = file.compliance(setup.model()).unwrap();
    for (j, &col) in columns.iter().enumerate() {
        assert!(
            ((c.h[j] - x[col]) / x[col]).abs() < 1e-6,
            "joint {}: {:e} vs {:e}",
            j + 1,
            c.h[j],
            x[col]
        );
    }
    let cov = c.covariance.unwrap();
    assert!((0..6).all(|j| cov[(j, j)] > 0.0));
    let text = String::from_utf8(stiffid(&args[..7]).stdout).unwrap();
    assert!(text.contains("from 300 readings"), "{text}");
}

/// Two held-out readings cannot register the tracker on the nominal robot: the calibrated
/// robot still predicts them, the nominal's errors there take the fitted readings'
/// registration with a warning `left-out`, and `--reregister` (which registers the calibrated
/// robot on them) is refused naming the file.
#[test]
fn validate_with_two_readings_registers_the_nominal_on_the_fitted_readings() {
    let d = temp_dir("calibrate-two-held");
    let model = model();
    let x = truth(&model);
    let tracker = tracker();
    let data = write_file(
        &d,
        "fit.csv",
        &readings(&model, &x, &tracker, &postures(25, 1)),
    );
    let all = readings(&model, &x, &tracker, &postures(10, 2));
    let two: Vec<&str> = all.lines().take(3).collect();
    let held = write_file(&d, "held.csv", &(two.join("\n") + "\n"));
    let args = |extra: &[&'static str]| {
        let mut a = vec![
            "calibrate",
            "--setup",
            SETUP,
            "--data",
            data.to_str().unwrap(),
        ];
        a.extend(["--validate", held.to_str().unwrap()]);
        a.extend(extra);
        a.into_iter().map(String::from).collect::<Vec<String>>()
    };
    let run = |a: Vec<String>| stiffid(&a.iter().map(String::as_str).collect::<Vec<&str>>());
    let doc = json(&run(args(&["--json"])));
    let v = &doc["validation"];
    assert_eq!(v["errors"].as_array().unwrap().len(), 2);
    assert!(v["rms_mm"].as_f64().unwrap() < 1e-6, "{v}");
    let nominal = v["nominal_rms_mm"].as_f64().unwrap();
    assert!(nominal > 0.1 && nominal.is_finite(), "{nominal}");
    let left_out: Vec<&Value> = (doc["warnings"].as_array().unwrap().iter())
        .filter(|w| w["kind"] == "left-out")
        .collect();
    assert_eq!(left_out.len(), 1, "{}", doc["warnings"]);
    assert!(left_out[0]["message"]
        .as_str()
        .unwrap()
        .contains("registered on the fitted readings"));
    let text = run(args(&[]));
    assert_success(&text);
    assert!(String::from_utf8_lossy(&text.stdout).contains("over 2 readings ("));
    assert_usage_error(&run(args(&["--reregister"])), &["held.csv", "3 points"]);
}

/// `--validate --level`: each held-out reading's error gets its jackknife+ interval from the
/// fitted postures' leave-one-posture-out errors, and `validation.coverage` is the share of the
/// held-out coordinates inside; `--level` means nothing without `--validate`.
/// The calibration of `args` (30 fitted postures, `--level` last) at 99.9 %: its ends from the
/// fit.
fn the_fit_bounds_where_the_jackknife_has_none(args: &[&str]) {
    // At 99.9 % the 30 postures' held-out values (three per reading) give the jackknife+ no
    // finite end (it needs 999): every end comes from the fit, finite, and the text says so with
    // the level as it is.
    let mut high = args.to_vec();
    *high.last_mut().unwrap() = "0.999";
    let doc = json(&stiffid(&[&high[..], &["--json"]].concat()));
    let i = &doc["validation"]["intervals"];
    assert_eq!(i["method"], "the fit's Gaussian bound");
    assert_eq!(i["held_out_needed"].as_u64(), Some(999));
    assert_eq!(i["from_fit"], i["coordinates"]);
    let ends = doc["validation"]["errors"].as_array().unwrap().iter();
    let ends: Vec<f64> = ends
        .flat_map(|e| {
            (0..3).flat_map(move |c| {
                [
                    e["interval_mm"][c][0].clone(),
                    e["interval_mm"][c][1].clone(),
                ]
            })
        })
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert!(
        ends.iter().all(|v| v.is_finite() && v.abs() > 0.01),
        "{ends:?}"
    );
    let text = String::from_utf8(stiffid(&high).stdout).unwrap();
    assert!(
        text.contains("99.9% prediction intervals (the fit's Gaussian bound, 30 folds)"),
        "{text}"
    );
    assert!(
        text.contains("the jackknife+ needs 999 held-out values"),
        "{text}"
    );
}

#[test]
fn calibrate_gives_held_out_readings_intervals_and_their_coverage() {
    let d = temp_dir("calibrate-intervals");
    let model = model();
    let x = truth(&model);
    let tracker = tracker();
    let data = write_file(
        &d,
        "fit.csv",
        &readings(&model, &x, &tracker, &postures(30, 11)),
    );
    let held = write_file(
        &d,
        "held.csv",
        &readings(&model, &x, &tracker, &postures(20, 12)),
    );
    // The offsets alone leave the other joint errors unmodelled: held-out errors of a few
    // tenths of a millimetre.
    let args = [
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        data.to_str().unwrap(),
        "--geometry",
        "offsets",
        "--gravity",
        "none",
        "--maps",
        "none",
        "--validate",
        held.to_str().unwrap(),
        "--level",
        "0.9",
    ];
    let doc = json(&stiffid(&[&args[..], &["--json"]].concat()));
    let v = &doc["validation"];
    let i = &v["intervals"];
    assert_eq!(i["method"], "jackknife+");
    assert_eq!(i["level"].as_f64(), Some(0.9));
    assert_eq!(i["folds"].as_u64(), Some(30));
    let errors = v["errors"].as_array().unwrap();
    assert_eq!(i["coordinates"].as_u64(), Some(3 * errors.len() as u64));
    assert!(v["rms_mm"].as_f64().unwrap() > 0.05, "{}", v["rms_mm"]);
    // Every interval holds finite ends around a real width; the coverage counts the errors
    // inside them.
    let mut inside = 0;
    for e in errors {
        for c in 0..3 {
            let end = |k: usize| e["interval_mm"][c][k].as_f64().unwrap();
            let value = e["error_mm"][c].as_f64().unwrap();
            assert!(end(1) - end(0) > 0.01, "{e}");
            inside += usize::from(end(0) <= value && value <= end(1));
        }
    }
    assert_eq!(i["covered"].as_u64(), Some(inside as u64));
    let coverage = inside as f64 / (3 * errors.len()) as f64;
    assert_eq!(v["coverage"].as_f64(), Some(coverage));
    assert!(coverage > 0.5, "{coverage}");
    assert!(doc["cross_validation"].is_null());
    let text = String::from_utf8(stiffid(&args).stdout).unwrap();
    assert!(
        text.contains("90% prediction intervals (jackknife+, 30 folds)"),
        "{text}"
    );
    the_fit_bounds_where_the_jackknife_has_none(&args);
    // A level without held-out readings, or outside [0.5, 0.999], is the option's error.
    for (bad, say) in [
        (&["--level", "0.9"][..], "only with --validate"),
        (
            &["--validate", held.to_str().unwrap(), "--level", "1.5"][..],
            "0.999",
        ),
    ] {
        let out = stiffid(
            &[
                &[
                    "calibrate",
                    "--setup",
                    SETUP,
                    "--data",
                    data.to_str().unwrap(),
                ][..],
                bad,
            ]
            .concat(),
        );
        assert_eq!(out.status.code(), Some(2));
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.starts_with("error: --level: ") && err.contains(say),
            "{err}"
        );
    }
}
