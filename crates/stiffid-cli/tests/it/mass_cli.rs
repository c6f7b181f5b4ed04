//! The robot's mass through the command: `predict --json` and `kinematics --json` give the
//! library's frequencies, effective masses and surge (the same document), placeholder masses a
//! warning and `null` fields.

use crate::common::{assert_success, json, stiffid, temp_dir, write_file};
use nalgebra::{Vector3, Vector6};
use stiffid::app::{kinematics, predict};
use stiffid::internal::observation::deflection::Frame;

const COMAU: &str = include_str!("../../../stiffid-core/presets/comau-smart5-nj165-3.0.toml");
const SETUP: &str = include_str!("../../../stiffid-core/setups/zhang2021-comau-nj165.toml");

/// The COMAU preset with a mass, centre and inertia tensor on each joint (`equal`: every mass
/// 1 kg, ROS-Industrial's placeholders).
fn robot_text(equal: bool) -> String {
    let masses = [420.0, 260.0, 180.0, 45.0, 25.0, 12.0];
    let mut parts = COMAU.split("[[joint]]\n");
    let mut text = parts.next().unwrap().to_string();
    for (i, part) in parts.enumerate() {
        let m = if equal { 1.0 } else { masses[i] };
        let j = m * 0.01;
        text += &format!(
            "[[joint]]\nmass_kg = {m:?}\ncom_mm = [{:?}, 20.0, -30.0]\ninertia_kg_m2 = [{j:?}, {:?}, {:?}, 0, 0, 0]\n{part}",
            50.0 * i as f64,
            j * 1.2,
            j * 0.8
        );
    }
    text
}

/// A scratch folder with `robot.toml` and `setup.toml` (the paper's setup on it); the setup's
/// path.
fn files(name: &str, equal: bool) -> String {
    let d = temp_dir(name);
    write_file(&d, "robot.toml", &robot_text(equal));
    let setup = SETUP.replace(
        "robot = \"comau-smart5-nj165-3.0\"",
        "robot = \"robot.toml\"",
    );
    write_file(&d, "setup.toml", &setup)
        .to_string_lossy()
        .into_owned()
}

#[test]
fn predict_gives_the_librarys_modes_effective_mass_and_surge() {
    let setup_path = files("mass-predict", false);
    let q = "10,-20,-100,30,40,50";
    let predict = |json: bool| {
        let mut args = vec!["predict", "--setup", &setup_path, "--q-deg", q];
        args.extend(["--wrench", "200,-100,-1500"]);
        args.extend(json.then_some("--json"));
        stiffid(&args)
    };
    let out = predict(true);
    assert_success(&out);
    let v = json(&out);
    let setup = stiffid::internal::setup::parse(
        &SETUP.replace(
            "robot = \"comau-smart5-nj165-3.0\"",
            "robot = \"robot.toml\"",
        ),
        "setup.toml",
        |_, _| stiffid::internal::robot::file::parse(&robot_text(false), "robot.toml"),
    )
    .unwrap();
    let outcome = predict::run(&predict::Request {
        setup_name: setup_path.clone(),
        setup: &setup,
        q: Vector6::new(10.0, -20.0, -100.0, 30.0, 40.0, 50.0).map(f64::to_radians),
        wrench: Vector6::new(200.0, -100.0, -1500.0, 0.0, 0.0, 0.0),
        frame: Frame::Base,
        at: None,
        compliance: None,
        level: None,
    })
    .unwrap();
    let library = serde_json::to_value(outcome.written()).unwrap();
    for key in [
        "natural_frequencies_hz",
        "mode_shapes",
        "mass_matrix_kg_m2",
        "operational_inertia_si",
        "effective_mass_kg",
        "effective_mass_free_kg",
        "surge_mm_s",
        "surge_energy_j",
    ] {
        assert_eq!(v[key], library[key], "{key}");
    }
    let hz: Vec<f64> = serde_json::from_value(v["natural_frequencies_hz"].clone()).unwrap();
    assert!(hz.windows(2).all(|w| w[0] <= w[1]) && hz[0] > 0.0, "{hz:?}");
    // The energy balance from the document's own fields: m v^2 / 2 = F^2 c / 2.
    let (m, s) = (
        v["effective_mass_kg"].as_f64().unwrap(),
        v["surge_mm_s"].as_f64().unwrap(),
    );
    let c = v["compliance_along_force_mm_per_n"].as_f64().unwrap() * 1e-3;
    let f2 = 200.0f64.powi(2) + 100.0f64.powi(2) + 1500.0f64.powi(2);
    assert!((0.5 * m * (s * 1e-3).powi(2) - 0.5 * f2 * c).abs() < 1e-12 * f2 * c);
    assert!(m >= v["effective_mass_free_kg"].as_f64().unwrap());
    let text = predict(false);
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(
        text.contains(&format!("natural frequencies Hz: {:.2}", hz[0])),
        "{text}"
    );
    assert!(text.contains("breakthrough surge"), "{text}");
}

#[test]
fn kinematics_gives_the_librarys_frequencies_with_a_stiffness() {
    let d = temp_dir("mass-kinematics");
    let path = write_file(&d, "robot.toml", &robot_text(false));
    let path = path.to_string_lossy();
    let k = "950000,3000000,900000,250000,200000,150000";
    let kinematics = |extra: &[&str]| {
        let mut args = vec![
            "kinematics",
            "--robot",
            &path,
            "--q-deg",
            "10,-20,-100,30,40,50",
        ];
        args.extend(extra);
        stiffid(&args)
    };
    let out = kinematics(&[
        "--point-mm",
        "150,0,200",
        "--stiffness-nm-per-rad",
        k,
        "--json",
    ]);
    assert_success(&out);
    let v = json(&out);
    let robot = stiffid::internal::robot::file::parse(&robot_text(false), "robot.toml").unwrap();
    let report = kinematics::run(&kinematics::Request {
        robot: &robot,
        q: Vector6::new(10.0, -20.0, -100.0, 30.0, 40.0, 50.0).map(f64::to_radians),
        point: Vector3::new(0.15, 0.0, 0.2),
        characteristic_length: None,
        coordinates: stiffid::Coordinates::Axis,
        stiffness: Some(Vector6::new(
            950000.0, 3e6, 900000.0, 250000.0, 200000.0, 150000.0,
        )),
        external: Vec::new(),
        workpiece: None,
    })
    .unwrap();
    let expected = report.report.modes.unwrap().frequencies;
    let got: Vec<f64> = serde_json::from_value(v["natural_frequencies_hz"].clone()).unwrap();
    assert_eq!(got, expected.to_vec());
    // Without a stiffness: the mass matrix, no frequencies.
    let out = kinematics(&["--json"]);
    let v = json(&out);
    assert!(v["natural_frequencies_hz"].is_null() && v["mass_matrix_kg_m2"].is_array());
}

#[test]
fn placeholder_masses_are_a_warning_and_null_fields() {
    let setup_path = files("mass-placeholder", true);
    let out = stiffid(&[
        "predict",
        "--setup",
        &setup_path,
        "--q-deg",
        "10,-20,-100,30,40,50",
        "--wrench",
        "0,0,-1000",
        "--json",
    ]);
    assert_success(&out);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("warning:")
            && stderr.contains("placeholders")
            && stderr.contains("inertia_kg_m2"),
        "{stderr}"
    );
    let v = json(&out);
    assert!(v["natural_frequencies_hz"].is_null() && v["surge_mm_s"].is_null());
    assert_eq!(v["warnings"][0]["kind"], "masses");
}
