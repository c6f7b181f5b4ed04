//! `stiffid calibrate` on a fixed cell (no positioner) with reflectors on the part: noise-free
//! readings of the arm and of the three reflectors (`T1`..`T3` rows) locate the part where it
//! truly is, 2 mm from the setup's `[workpiece] base_from_part`; the robot file records it
//! (`[part]`), `kinematics` on a setup pointing at that file places the part there, and the old
//! `base_from_part` kept in that setup is refused naming both places.

use crate::calibrate_cli::{model, postures, readings, truth, SETUP};
use crate::common::{json, numbers, refused, stiffid, temp_dir, write_file};
use nalgebra::{Isometry3, Point3, Vector3};

/// The reflectors on the part, part frame, mm.
const ON_PART_MM: [[f64; 3]; 3] = [
    [300.0, 0.0, 40.0],
    [-200.0, 250.0, 40.0],
    [-100.0, -300.0, 60.0],
];

/// The built-in setup on `robot` with `[workpiece]` at `xyz_mm` (turned 30 deg about z) and,
/// with `reflectors`, the reflectors on the part.
fn setup_text(robot: &str, xyz_mm: [f64; 3], reflectors: bool) -> String {
    let text = stiffid::internal::setup::builtin_text(SETUP)
        .unwrap()
        .replace(
            "robot = \"comau-smart5-nj165-3.0\"",
            &format!("robot = \"{robot}\""),
        );
    let [x, y, z] = xyz_mm;
    let mut workpiece = format!(
        "\n[workpiece]\nbase_from_part = {{ xyz_mm = [{x:?}, {y:?}, {z:?}], rpy_deg = [0.0, 0.0, 30.0] }}\n"
    );
    if reflectors {
        workpiece += &format!("reflectors_mm = {ON_PART_MM:?}\n");
    }
    text + &workpiece
}

#[test]
fn calibrate_locates_a_fixed_part_from_its_reflectors() {
    let d = temp_dir("fixed-part");
    let model = model();
    let x = truth(&model);
    let tracker = crate::calibrate_cli::tracker();
    let part = Isometry3::new(
        Vector3::new(1.5, 0.2, 0.6),
        Vector3::z() * 30f64.to_radians(),
    );
    // The arm's readings, then each reflector read once, beside the first posture.
    let mut text = readings(&model, &x, &tracker, &postures(25, 1));
    let line = text.lines().nth(1).unwrap().to_string();
    let first: Vec<&str> = line.split(',').collect();
    for (k, r) in ON_PART_MM.iter().enumerate() {
        let t = tracker.inverse() * part * Point3::from(Vector3::from(*r) * 1e-3);
        text += &format!(
            "P1,T{},{},{:?},{:?},{:?}\n",
            k + 1,
            first[2..8].join(","),
            t.x * 1e3,
            t.y * 1e3,
            t.z * 1e3
        );
    }
    let data = write_file(&d, "fit.csv", &text);
    // The setup's part frame 2 mm from where the part is.
    let setup = write_file(
        &d,
        "setup.toml",
        &setup_text("comau-smart5-nj165-3.0", [1502.0, 200.0, 600.0], true),
    );
    let robot = d.join("robot.toml");
    let doc = json(&stiffid(&[
        "calibrate",
        "--setup",
        setup.to_str().unwrap(),
        "--data",
        data.to_str().unwrap(),
        "--out",
        robot.to_str().unwrap(),
        "--json",
    ]));
    assert_eq!(doc["readings"].as_u64(), Some(25 * 4 + 3));
    let warnings = doc["warnings"].to_string();
    assert!(
        warnings.contains("the part located from the reflectors T1..T3 lies 2")
            && warnings.contains("from the setup's [workpiece] base_from_part"),
        "{warnings}"
    );
    let file = std::fs::read_to_string(&robot).unwrap();
    let located = stiffid::internal::robot::file::parse(&file, "robot.toml").unwrap();
    let located = *located.part().expect("[part]");
    assert!((located.translation.vector - part.translation.vector).norm() < 1e-9);
    assert!(located.rotation.angle_to(&part.rotation) < 1e-9);
    // A setup pointing at the file: the part where the file puts it.
    let pointing = setup_text("robot.toml", [1502.0, 200.0, 600.0], true);
    let without = pointing.replace(
        "base_from_part = { xyz_mm = [1502.0, 200.0, 600.0], rpy_deg = [0.0, 0.0, 30.0] }\n",
        "",
    );
    let at = write_file(&d, "at.toml", &without);
    let kinematics = json(&stiffid(&[
        "kinematics",
        "--setup",
        at.to_str().unwrap(),
        "--q-deg",
        "0,0,-90,0,60,0",
        "--json",
    ]));
    let origin = Vector3::from_iterator(numbers(&kinematics["part_position_mm"]));
    assert!(
        (origin - Vector3::new(1500.0, 200.0, 600.0)).norm() < 1e-6,
        "{origin}"
    );
    // The old part frame kept there is refused, naming both places.
    write_file(&d, "kept.toml", &pointing);
    refused(
        &d,
        &[
            "kinematics",
            "--setup",
            "{dir}/kept.toml",
            "--q-deg",
            "0,0,-90,0,60,0",
        ],
        &[
            "workpiece.base_from_part",
            "[part]",
            "robot.toml",
            "mm away",
        ],
    );
}

/// `select --for calibration` on the fixed cell with reflectors on the part: the postures as
/// without them (no external axis column), the campaign's plan listing the part's reflectors as
/// fixed points of the cell to read in the same session.
#[test]
fn select_plans_the_reflectors_of_a_fixed_part() {
    let d = temp_dir("fixed-part-select");
    let setup = write_file(
        &d,
        "setup.toml",
        &setup_text("comau-smart5-nj165-3.0", [1500.0, 200.0, 600.0], true),
    );
    let out = d.join("campaign.csv");
    let args = |setup: &str, out: &str| {
        let args = [
            "select",
            "--setup",
            setup,
            "--for",
            "calibration",
            "--start-random",
            "--count",
            "12",
            "--seed",
            "1",
            "--max-evals",
            "100",
            "--out",
            out,
            "--json",
        ];
        json(&stiffid(&args))
    };
    let doc = args(setup.to_str().unwrap(), out.to_str().unwrap());
    assert!(
        doc.get("posture_stations").is_none_or(|s| s.is_null()),
        "{doc}"
    );
    let csv = std::fs::read_to_string(&out).unwrap();
    assert!(csv.lines().next().unwrap().ends_with("q6_deg"), "{csv}");
    // The same postures as on the setup without the reflectors: they change no design.
    let plain = write_file(
        &d,
        "plain.toml",
        &setup_text("comau-smart5-nj165-3.0", [1500.0, 200.0, 600.0], false),
    );
    let plain_out = d.join("plain.csv");
    args(plain.to_str().unwrap(), plain_out.to_str().unwrap());
    assert_eq!(std::fs::read_to_string(&plain_out).unwrap(), csv);
    let plan = d.join("plan");
    stiffid(&[
        "select",
        "--setup",
        setup.to_str().unwrap(),
        "--for",
        "calibration",
        "--start-random",
        "--count",
        "12",
        "--seed",
        "1",
        "--max-evals",
        "100",
        "--out",
        d.join("again.csv").to_str().unwrap(),
        "--report",
        plan.to_str().unwrap(),
    ]);
    let page = std::fs::read_to_string(plan.join("plan.html")).unwrap();
    for k in 1..=3 {
        let line = format!("Part reflector T{k} (point T{k} of the readings)");
        assert!(page.contains(&line), "{line}");
    }
    assert!(page.contains("a fixed point of the cell, read it once"));
    assert!(!page.contains("table angles"), "{page}");
}

/// Reflectors read on a fixed cell whose setup does not place them locate nothing: a warning
/// says which, and the robot file records no part.
#[test]
fn reflectors_the_setup_does_not_place_are_named() {
    let d = temp_dir("fixed-part-unplaced");
    let model = model();
    let x = truth(&model);
    let tracker = crate::calibrate_cli::tracker();
    let mut text = readings(&model, &x, &tracker, &postures(25, 1));
    let line = text.lines().nth(1).unwrap().to_string();
    let first: Vec<&str> = line.split(',').collect();
    text += &format!("P1,T1,{},1500.0,200.0,600.0\n", first[2..8].join(","));
    let data = write_file(&d, "fit.csv", &text);
    let setup = write_file(
        &d,
        "setup.toml",
        &setup_text("comau-smart5-nj165-3.0", [1500.0, 200.0, 600.0], false),
    );
    let robot = d.join("robot.toml");
    let doc = json(&stiffid(&[
        "calibrate",
        "--setup",
        setup.to_str().unwrap(),
        "--data",
        data.to_str().unwrap(),
        "--out",
        robot.to_str().unwrap(),
        "--json",
    ]));
    let warnings = doc["warnings"].to_string();
    assert!(
        warnings.contains("reflectors T1 fixed in the cell and the setup places 0"),
        "{warnings}"
    );
    let file = std::fs::read_to_string(&robot).unwrap();
    assert!(!file.contains("[part]"), "{file}");
}

/// A held-out reading of a reflector the fitted readings never read (`T1` in `--validate`, none
/// in `--data`; `T2` where the fitted readings read `T1` alone) is refused naming its line and
/// the reflectors the fit located: the calibration has no position to predict it from.
#[test]
fn held_out_reflectors_the_fit_never_read_are_refused() {
    let d = temp_dir("fixed-part-held-reflector");
    let model = model();
    let x = truth(&model);
    let tracker = crate::calibrate_cli::tracker();
    // A reflector read beside the first posture of `text`, at its axis angles.
    let reflector = |text: &str, k: usize| {
        let line = text.lines().nth(1).unwrap().to_string();
        let first: Vec<&str> = line.split(',').collect();
        format!("P1,T{k},{},1500.0,200.0,600.0\n", first[2..8].join(","))
    };
    let arm = readings(&model, &x, &tracker, &postures(25, 1));
    write_file(&d, "fit.csv", &arm);
    write_file(&d, "fit-t1.csv", &(arm.clone() + &reflector(&arm, 1)));
    let held = readings(&model, &x, &tracker, &postures(5, 2));
    write_file(&d, "held-t1.csv", &(held.clone() + &reflector(&held, 1)));
    write_file(&d, "held-t2.csv", &(held.clone() + &reflector(&held, 2)));
    // The reflector's row comes after the 5 postures' 4 points and the header: line 22.
    let cases = [
        ("{dir}/fit.csv", "{dir}/held-t1.csv", "T1", "locate none"),
        ("{dir}/fit-t1.csv", "{dir}/held-t2.csv", "T2", "locate T1:"),
    ];
    for (fit, held, name, located) in cases {
        let args = [
            "calibrate",
            "--setup",
            SETUP,
            "--data",
            fit,
            "--validate",
            held,
        ];
        let message = format!("reflector {name} is not read in the fitted readings");
        refused(&d, &args, &["line 22", &message, located]);
    }
    // Read in the fitted readings too, the held-out reflector is predicted.
    let doc = json(&stiffid(&[
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        d.join("fit-t1.csv").to_str().unwrap(),
        "--validate",
        d.join("held-t1.csv").to_str().unwrap(),
        "--json",
    ]));
    let errors = doc["validation"]["errors"].as_array().unwrap();
    assert_eq!(errors.len(), 5 * model.points() + 1);
}

/// A reflector read beside one posture only has no reading in the fold that holds that posture
/// out: the cross-validation leaves it out with a warning, instead of an "error" of the fit's
/// start (hundreds of mm) in its RMS and in the robot file's `[held_out]`.
#[test]
fn cross_validation_leaves_out_a_reflector_read_once() {
    let d = temp_dir("fixed-part-cross-validated");
    let model = model();
    let x = truth(&model);
    let tracker = crate::calibrate_cli::tracker();
    let mut text = readings(&model, &x, &tracker, &postures(25, 1));
    let line = text.lines().nth(1).unwrap().to_string();
    let first: Vec<&str> = line.split(',').collect();
    text += &format!("P1,T1,{},1500.0,200.0,600.0\n", first[2..8].join(","));
    let data = write_file(&d, "fit.csv", &text);
    let robot = d.join("robot.toml");
    let doc = json(&stiffid(&[
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        data.to_str().unwrap(),
        "--cross-validate",
        "--out",
        robot.to_str().unwrap(),
        "--json",
    ]));
    let cv = &doc["cross_validation"];
    assert_eq!(cv["errors"].as_array().unwrap().len(), 25 * model.points());
    assert!(cv["max_mm"].as_f64().unwrap() < 1e-6, "{}", cv["max_mm"]);
    let warnings = doc["warnings"].to_string();
    assert!(
        warnings.contains("reflector T1 read in one posture only"),
        "{warnings}"
    );
    let file = std::fs::read_to_string(&robot).unwrap();
    let held: toml::Value = toml::from_str(&file).unwrap();
    let errors = numbers(&serde_json::to_value(&held["held_out"]["errors_mm"]).unwrap());
    assert_eq!(errors.len(), 25 * model.points());
    assert!(errors.iter().all(|e| *e < 1e-3), "{errors:?}");
}

/// The held-out reading of a reflector the fitted readings read beside one posture only: the
/// fold holding that posture out has no reading of it, and its interval leaves that fold out
/// (with it, one side of the interval reached the fit's start, 100 mm and more away).
#[test]
fn intervals_of_a_reflector_read_once_leave_out_the_fold_without_it() {
    let d = temp_dir("fixed-part-intervals");
    let model = model();
    let x = truth(&model);
    let tracker = crate::calibrate_cli::tracker();
    let reflector = |text: &str| {
        let line = text.lines().nth(1).unwrap().to_string();
        let first: Vec<&str> = line.split(',').collect();
        format!("P1,T1,{},1500.0,200.0,600.0\n", first[2..8].join(","))
    };
    let fit = readings(&model, &x, &tracker, &postures(25, 1));
    let held = readings(&model, &x, &tracker, &postures(5, 2));
    let data = write_file(&d, "fit.csv", &(fit.clone() + &reflector(&fit)));
    let held = write_file(&d, "held.csv", &(held.clone() + &reflector(&held)));
    let doc = json(&stiffid(&[
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        data.to_str().unwrap(),
        "--validate",
        held.to_str().unwrap(),
        "--json",
    ]));
    let errors = doc["validation"]["errors"].as_array().unwrap();
    let t1 = errors.iter().find(|e| e["point_name"] == "T1").unwrap();
    assert!(t1["error_norm_mm"].as_f64().unwrap() < 1e-6, "{t1}");
    for side in t1["interval_mm"].as_array().unwrap() {
        let [lo, hi] = [side[0].as_f64().unwrap(), side[1].as_f64().unwrap()];
        assert!(lo <= 0.0 && hi >= 0.0 && hi - lo < 0.01, "{t1}");
    }
}

/// A reflector read at two places (a reading of another reflector under its name) is refused
/// naming the reflector as the file does, `T1`, not the tool's measuring point 1.
#[test]
fn a_reflector_read_at_two_places_is_named_as_a_reflector() {
    let d = temp_dir("fixed-part-two-places");
    let model = model();
    let x = truth(&model);
    let tracker = crate::calibrate_cli::tracker();
    let mut text = readings(&model, &x, &tracker, &postures(25, 1));
    let angles = |n: usize| {
        let line = text.lines().nth(n).unwrap().to_string();
        line.split(',')
            .skip(2)
            .take(6)
            .collect::<Vec<_>>()
            .join(",")
    };
    let (first, second) = (angles(1), angles(5));
    text += &format!("P1,T1,{first},1500.0,200.0,600.0\n");
    text += &format!("P2,T1,{second},2500.0,200.0,600.0\n");
    write_file(&d, "fit.csv", &text);
    let args = ["calibrate", "--setup", SETUP, "--data", "{dir}/fit.csv"];
    refused(&d, &args, &["point T1), residual_norm_mm"]);
}
