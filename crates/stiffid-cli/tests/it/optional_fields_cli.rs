//! Setups without a nominal stiffness or a characteristic length: the commands and criteria that
//! do not use the field work, the others exit 2 naming the field, what needs it and where a value
//! comes from.

use crate::common;
use common::{assert_success, assert_usage_error, json, stiffid, temp_dir, write_file};
use std::path::Path;

/// The paper setup without the line of `field`, written to `dir`.
fn paper_without(dir: &Path, field: &str) -> String {
    let out = stiffid(&["setups", "show", "zhang2021-comau-nj165"]);
    let text: String = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .filter(|l| !l.starts_with(field))
        .map(|l| format!("{l}\n"))
        .collect();
    assert!(text.contains("[bounds]"));
    let path = write_file(dir, &format!("without-{field}.toml"), &text);
    path.to_str().unwrap().to_string()
}

/// `stiffid evaluate --json` of `postures` on `setup` (its schema is checked by
/// `crates/stiffid-py/tests/test_schemas.py`).
fn evaluated(setup: &str, postures: &str) -> serde_json::Value {
    let args = [
        "evaluate",
        "--setup",
        setup,
        "--postures",
        postures,
        "--json",
    ];
    json(&stiffid(&args))
}

/// A group of six postures selected on `setup` by `criterion`, written to `dir`.
fn selected(dir: &Path, setup: &str, criterion: &str) -> String {
    let out = dir.join(format!("{criterion}.csv"));
    let o = out.to_str().unwrap();
    let args = ["select", "--setup", setup, "--criterion", criterion];
    assert_success(&stiffid(
        &[
            &args[..],
            &["--start-random", "--max-evals", "100", "--out", o],
        ]
        .concat(),
    ));
    o.to_string()
}

#[test]
fn without_a_characteristic_length_classical_and_zhang2021_are_not_computed() {
    let dir = temp_dir("no-length");
    let setup = paper_without(&dir, "characteristic_length_mm");
    // The default criterion (relative-a) needs no characteristic length.
    let postures = selected(&dir, &setup, "relative-a");
    let e = evaluated(&setup, &postures);
    assert!(e["classical"].is_null() && e["zhang2021"].is_null(), "{e}");
    for key in ["relative_a", "d_optimal", "scaled_cond", "cond_psi"] {
        assert!(e[key].as_f64().is_some_and(|v| v > 0.0), "{key}");
    }
    assert_eq!(e["predicted_deviation_pct"].as_array().unwrap().len(), 6);
    let text = stiffid(&["evaluate", "--setup", &setup, "--postures", &postures]);
    let text = String::from_utf8(text.stdout).unwrap();
    assert!(
        text.contains("classical    not computed: the setup has no characteristic_length_mm"),
        "{text}"
    );
    for criterion in ["classical", "zhang2021"] {
        let args = [
            "select",
            "--setup",
            &setup,
            "--criterion",
            criterion,
            "--global",
        ];
        let out = dir.join("never.csv");
        let o = stiffid(&[&args[..], &["--out", out.to_str().unwrap()]].concat());
        let needs =
            format!("the setup has no characteristic_length_mm: criterion {criterion} needs it");
        assert_usage_error(&o, &[&needs, "stiffid setups new"]);
        assert!(!out.exists());
    }
    let report = dir.join("report");
    let o = stiffid(&[
        "reproduce",
        "--setup",
        &setup,
        "--runs",
        "5",
        "--out",
        report.to_str().unwrap(),
    ]);
    assert_usage_error(&o, &["characteristic_length_mm", "the study"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn without_a_nominal_stiffness_the_scaled_criteria_and_simulations_say_so() {
    let dir = temp_dir("no-stiffness");
    let setup = paper_without(&dir, "nominal_stiffness_nm_per_rad");
    let postures = selected(&dir, &setup, "zhang2021");
    let e = evaluated(&setup, &postures);
    for key in [
        "relative_a",
        "d_optimal",
        "scaled_cond",
        "predicted_deviation_pct",
    ] {
        assert!(e[key].is_null(), "{key}: {e}");
    }
    for key in ["classical", "zhang2021", "cond_psi"] {
        assert!(e[key].as_f64().is_some_and(|v| v > 0.0), "{key}");
    }
    // The default criterion is relative-a, which needs it.
    let out = dir.join("never.csv");
    let o = stiffid(&[
        "select",
        "--setup",
        &setup,
        "--global",
        "--out",
        out.to_str().unwrap(),
    ]);
    let needs = "the setup has no nominal_stiffness_nm_per_rad: criterion relative-a needs it";
    assert_usage_error(
        &o,
        &[
            needs,
            "a rough prior will do: one scaled from the robot's payload class",
            "; `stiffid setups new --robot R` writes it",
        ],
    );
    let q = ["--q-deg", "10,20,-90,30,20,10", "--wrench", "0,0,-500"];
    let o = stiffid(&[&["predict", "--setup", &setup][..], &q].concat());
    assert_usage_error(
        &o,
        &[
            "nominal_stiffness_nm_per_rad",
            "predict without a stiffness",
        ],
    );
    let k = dir.join("k.json");
    std::fs::write(
        &k,
        r#"{"stiffness_nm_per_rad": [950000, 3000000, 900000, 250000, 200000, 150000]}"#,
    )
    .unwrap();
    let args = [
        "predict",
        "--setup",
        &setup,
        "--stiffness",
        k.to_str().unwrap(),
        "--json",
    ];
    let predicted = json(&stiffid(&[&args[..], &q].concat()));
    let paper = json(&stiffid(
        &[
            &["predict", "--setup", "zhang2021-comau-nj165", "--json"][..],
            &q,
        ]
        .concat(),
    ));
    assert_eq!(predicted["measuring_points"], paper["measuring_points"]);
    let o = stiffid(&[
        "simulate",
        "--setup",
        &setup,
        "--postures",
        &postures,
        "--runs",
        "5",
    ]);
    assert_usage_error(&o, &["nominal_stiffness_nm_per_rad", "the simulation"]);
    let report = dir.join("report");
    let args = [
        "select",
        "--setup",
        &setup,
        "--criterion",
        "classical",
        "--report",
    ];
    let o = stiffid(
        &[
            &args[..],
            &[report.to_str().unwrap(), "--out", out.to_str().unwrap()],
        ]
        .concat(),
    );
    assert_usage_error(&o, &["nominal_stiffness_nm_per_rad", "select --report"]);
    assert!(!out.exists() && !report.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn evaluate_names_the_virtual_springs_without_a_nominal_stiffness() {
    let dir = common::temp_dir("optional-spring-nominal");
    let shown = stiffid(&["setups", "show", "zhang2021-comau-nj165"]);
    let springs =
        "\n[[model.spring]]\nname = \"bend\"\nkind = \"rotation\"\nlink = 3\naxis = [1, 0, 0]\n\
        \n[[model.spring]]\nname = \"shift\"\nkind = \"translation\"\nlink = 2\naxis = [0, 0, 1]\n\
        \n[[model.spring]]\nname = \"given\"\nkind = \"rotation\"\nlink = 2\naxis = [0, 1, 0]\n\
        nominal_stiffness_nm_per_rad = 5e6\n";
    let text = String::from_utf8(shown.stdout).unwrap() + springs;
    let setup = common::write_file(&dir, "s.toml", &text);
    let postures = common::write_file(&dir, "g.csv", common::GROUP);
    let out = stiffid(&[
        "evaluate",
        "--setup",
        setup.to_str().unwrap(),
        "--postures",
        postures.to_str().unwrap(),
    ]);
    common::assert_success(&out);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(!stdout.contains("NaN"), "{stdout}");
    assert!(
        !stdout.contains("the setup has no nominal_stiffness_nm_per_rad"),
        "{stdout}"
    );
    let named = "not computed: [[model.spring]] bend, shift: no nominal stiffness";
    assert_eq!(stdout.matches(named).count(), 4, "{stdout}");
}

/// A setup as a calibration needs it: the robot (the KUKA KR 210, whose calibrated chain a URDF
/// can carry), the measuring points and the noise; no `[loading]`, loading point, `[bounds]`,
/// `[test]` or stiffness. `calibrate` fits noise-free readings on it to 1e-6 mm; the jobs that
/// need the rope load exit 2 naming the table, what needs it and that a calibration needs none.
/// The URDF's warning (it leaves out the sag of the lumped gravity terms) comes only with
/// `--urdf-out`.
#[test]
fn a_calibration_only_setup_calibrates_and_the_loaded_jobs_name_the_loading() {
    use crate::calibrate_cli::{postures, readings, truth};
    use stiffid::internal::metrology::calibration::error_model::MeasuredIn;
    use stiffid::internal::metrology::calibration::{gravity, ErrorModel, Geometry};
    let dir = temp_dir("calibration-only");
    let text = "name = \"tracker-only\"\nrobot = \"kuka-kr210-robond\"\n\n[tool]\n\
        measuring_points_mm = [[80.0, 80.0, 260.0], [-80.0, 80.0, 260.0], [-80.0, -80.0, 260.0]]\n\n\
        [noise]\nreading_sd_mm = 0.01\nlevel_multiples = [1.0]\n";
    let setup = write_file(&dir, "tracker-only.toml", text);
    let setup = setup.to_str().unwrap();
    let robot = stiffid::internal::robot::presets::get("kuka-kr210-robond").unwrap();
    let points = [
        [0.08, 0.08, 0.26],
        [-0.08, 0.08, 0.26],
        [-0.08, -0.08, 0.26],
    ]
    .map(nalgebra::Vector3::from);
    let terms = gravity::Terms::none(&robot);
    let model =
        ErrorModel::new(&robot, &points, MeasuredIn::Tracker, Geometry::Full, terms).unwrap();
    let tracker = nalgebra::Isometry3::new(
        nalgebra::Vector3::new(3.0, -2.0, 1.5),
        nalgebra::Vector3::new(0.0, 0.0, 2.5),
    );
    let data = readings(&model, &truth(&model), &tracker, &postures(25, 1));
    let data = write_file(&dir, "fit.csv", &data);
    let data = data.to_str().unwrap();
    let calibrate = |more: &[&str]| {
        let args = [
            "calibrate",
            "--setup",
            setup,
            "--data",
            data,
            "--gravity",
            "lumped",
        ];
        stiffid(&[&args[..], more].concat())
    };
    let fitted = json(&calibrate(&["--json"]));
    assert!(
        fitted["residual_rms_mm"].as_f64().unwrap() < 1e-6,
        "{fitted}"
    );
    let urdf_warning = |out: &std::process::Output| {
        assert_success(out);
        String::from_utf8_lossy(&out.stderr).contains("the URDF leaves out")
    };
    assert!(!urdf_warning(&calibrate(&[])));
    let urdf = dir.join("robot.urdf");
    assert!(urdf_warning(&calibrate(&[
        "--urdf-out",
        urdf.to_str().unwrap()
    ])));
    let postures = write_file(
        &dir,
        "g.csv",
        "posture,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg\nP1,0,-10,-90,0,45,0\n",
    );
    let postures = postures.to_str().unwrap();
    let out = dir.join("group.csv");
    let out = out.to_str().unwrap();
    let select = [
        "select",
        "--setup",
        setup,
        "--criterion",
        "relative-a",
        "--start-random",
        "--out",
        out,
    ];
    for args in [
        &["simulate", "--setup", setup, "--postures", postures][..],
        &select[..],
    ] {
        let line = assert_usage_error(&stiffid(args), &["the setup has no loading", "load_n"]);
        assert!(
            line.contains(args[0]) && line.contains("a calibration needs none"),
            "{line}"
        );
    }
}
