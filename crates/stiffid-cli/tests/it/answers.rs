//! Inputs that used to give exit 0 with a wrong or meaningless answer: readings in other units,
//! held-out readings beyond the gate, a bad reading blamed on the model, repeated postures, an
//! output path spelt as a directory, a FIFO given as an input file. Each is refused (exit 2, one
//! `error:` line naming the file and the cause, nothing written) or named in its warning.

use crate::calibrate_cli::{model, postures, readings, truth, SETUP};
use crate::common::{json, refused, stiffid, temp_dir, write_file};
use nalgebra::{Isometry3, Vector3};

/// `readings` (the text of [`readings`]) with every tracker coordinate multiplied by `factor`
/// (the last three fields of each row).
fn scaled(text: &str, factor: f64) -> String {
    let mut lines = text.lines();
    let mut out = format!("{}\n", lines.next().unwrap());
    for line in lines {
        let mut fields: Vec<String> = line.split(',').map(str::to_string).collect();
        let n = fields.len();
        for f in &mut fields[n - 3..] {
            *f = format!("{:?}", f.parse::<f64>().unwrap() * factor);
        }
        out += &(fields.join(",") + "\n");
    }
    out
}

/// `text` with `dx_mm` added to the x coordinate of the reading on line `line` (1-based).
fn moved(text: &str, line: usize, dx_mm: f64) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let mut fields: Vec<String> = lines[line - 1].split(',').map(str::to_string).collect();
    let n = fields.len();
    fields[n - 3] = format!("{:?}", fields[n - 3].parse::<f64>().unwrap() + dx_mm);
    lines[line - 1] = fields.join(",");
    lines.join("\n") + "\n"
}

fn tracker() -> Isometry3<f64> {
    Isometry3::new(Vector3::new(3.0, -2.0, 1.5), Vector3::new(0.0, 0.0, 2.5))
}

#[test]
fn readings_in_metres_or_centimetres_are_refused_by_every_reader() {
    let d = temp_dir("answers-units");
    let model = model();
    let mm = readings(&model, &truth(&model), &tracker(), &postures(25, 1));
    write_file(&d, "mm.csv", &mm);
    write_file(&d, "m.csv", &scaled(&mm, 1e-3));
    write_file(&d, "cm.csv", &scaled(&mm, 0.1));
    let out = ["--out", "{dir}/robot.toml"];
    for (file, unit) in [("m.csv", "metres"), ("cm.csv", "centimetres")] {
        let data = format!("{{dir}}/{file}");
        for command in ["calibrate", "calibrate-cell", "register"] {
            let args = [command, "--setup", SETUP, "--data", &data];
            let args = match command {
                "calibrate" => [&args[..], &out].concat(),
                _ => args.to_vec(),
            };
            let line = refused(&d, &args, &[file, "readings", unit, "expected millimetres"]);
            assert!(line.contains("times the robot's size"), "{line}");
        }
    }
    // The held-out readings of a calibration pass the same check.
    let args = ["calibrate", "--setup", SETUP, "--data", "{dir}/mm.csv"];
    let held = ["--validate", "{dir}/m.csv"];
    refused(&d, &[&args[..], &held, &out].concat(), &["m.csv", "metres"]);
}

#[test]
fn held_out_readings_beyond_the_gate_are_refused_naming_the_reading() {
    let d = temp_dir("answers-held");
    let model = model();
    let x = truth(&model);
    let fit = readings(&model, &x, &tracker(), &postures(25, 1));
    write_file(&d, "fit.csv", &fit);
    let held = readings(&model, &x, &tracker(), &postures(10, 2));
    // Line 12: the 11th reading, posture P3, point 3; 50 mm off where the fitted readings'
    // gate is 10 mm.
    write_file(&d, "held.csv", &moved(&held, 12, 50.0));
    let args = ["calibrate", "--setup", SETUP, "--data", "{dir}/fit.csv"];
    let held = ["--validate", "{dir}/held.csv", "--out", "{dir}/robot.toml"];
    let line = refused(
        &d,
        &[&args[..], &held].concat(),
        &[
            "held.csv",
            "line 12 (posture P3, point 3)",
            "residual_norm_mm",
        ],
    );
    assert!(line.contains("expected at most 10.000 mm"), "{line}");
}

/// A robot whose nominal model misses its own readings by centimetres (20 mm and 20 mrad on the
/// (M)DH errors of joints 2-5): the gate judges held-out readings by the calibrated robot, which
/// explains them, and keeps them without `--force`; a reading neither explains is still refused.
#[test]
fn held_out_readings_the_calibration_explains_pass_the_gate_the_nominal_misses() {
    let d = temp_dir("answers-calibrated-gate");
    let model = model();
    let nominal = model.nominal();
    let x = &nominal + (truth(&model) - &nominal) * 40.0;
    write_file(
        &d,
        "fit.csv",
        &readings(&model, &x, &tracker(), &postures(25, 1)),
    );
    let held = readings(&model, &x, &tracker(), &postures(10, 2));
    write_file(&d, "held.csv", &held);
    let fit = d.join("fit.csv");
    let args = [
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        fit.to_str().unwrap(),
    ];
    let held_path = d.join("held.csv");
    let validate = ["--validate", held_path.to_str().unwrap(), "--json"];
    let doc = json(&stiffid(&[&args[..], &validate].concat()));
    let v = &doc["validation"];
    // An RMS beyond the 10 mm gate: some reading the nominal robot misses beyond it.
    assert!(v["nominal_rms_mm"].as_f64().unwrap() > 10.0, "{v}");
    assert!(v["max_mm"].as_f64().unwrap() < 1e-3, "{v}");
    // 50 mm off: the calibration misses it as far as the nominal robot does.
    write_file(&d, "held.csv", &moved(&held, 12, 50.0));
    let args = ["calibrate", "--setup", SETUP, "--data", "{dir}/fit.csv"];
    let held = ["--validate", "{dir}/held.csv", "--out", "{dir}/robot.toml"];
    refused(
        &d,
        &[&args[..], &held].concat(),
        &[
            "held.csv",
            "line 12 (posture P3, point 3)",
            "residual_norm_mm",
        ],
    );
}

#[test]
fn a_bad_reading_inside_the_gate_is_named_in_the_misfit_warning() {
    let d = temp_dir("answers-outlier");
    let model = model();
    let fit = readings(&model, &truth(&model), &tracker(), &postures(25, 1));
    // Line 39: the 38th reading, posture P10, point 2, 9 mm off.
    write_file(&d, "fit.csv", &moved(&fit, 39, 9.0));
    let data = d.join("fit.csv");
    let out = stiffid(&[
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        data.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(out.status.success(), "{stderr}");
    let misfit = stderr
        .lines()
        .find(|l| l.contains("times the tracker noise"))
        .unwrap_or_else(|| panic!("no misfit warning: {stderr}"));
    assert!(
        misfit.contains("the longest residual is")
            && misfit.contains("line 39 (posture P10, point 2)"),
        "{misfit}"
    );
}

#[test]
fn readings_of_too_few_distinct_postures_are_refused_with_their_count() {
    let d = temp_dir("answers-repeated");
    let model = model();
    let one = postures(1, 1);
    let text = readings(&model, &truth(&model), &tracker(), &vec![one[0]; 30]);
    write_file(&d, "one.csv", &text);
    let args = ["calibrate", "--setup", SETUP, "--data", "{dir}/one.csv"];
    // The refusal comes after the first model's fit, before the ladder's and the maps' choices:
    // with the defaults as with the geometry alone.
    let geometry = ["--gravity", "none", "--maps", "none"];
    for model in [&[][..], &geometry[..]] {
        let out = ["--out", "{dir}/robot.toml"];
        refused(
            &d,
            &[&args[..], model, &out].concat(),
            &[
                "one.csv",
                "120 readings of 1 distinct posture ",
                "read more distinct postures",
            ],
        );
    }
}

/// A short search on the paper setup, before its start and output.
const SELECT: [&str; 5] = [
    "select",
    "--setup",
    "zhang2021-comau-nj165",
    "--criterion",
    "classical",
];

#[test]
fn an_output_spelt_as_a_directory_is_refused_and_nothing_is_written() {
    let d = temp_dir("answers-out-dir");
    for out in ["{dir}/new/", "{dir}/new/.", "{dir}/.."] {
        let more = ["--start-random", "--max-evals", "5", "--out", out];
        refused(
            &d,
            &[&SELECT[..], &more].concat(),
            &["--out", "a directory, expected a file name"],
        );
        assert!(!d.join("new").exists());
    }
}

#[test]
fn a_fifo_given_as_an_input_file_is_refused_at_once() {
    let d = temp_dir("answers-fifo");
    let fifo = d.join("start.csv");
    let _ = std::fs::remove_file(&fifo);
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo");
    let out = d.join("out.csv");
    let more = [
        "--start",
        fifo.to_str().unwrap(),
        "--max-evals",
        "5",
        "--out",
        out.to_str().unwrap(),
    ];
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_stiffid"))
        .args([&SELECT[..], &more].concat())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // Before the fix, the command waited forever in open(): give it 60 s, then fail.
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
    while child.try_wait().unwrap().is_none() {
        if std::time::Instant::now() > deadline {
            child.kill().unwrap();
            panic!("stiffid waits on a FIFO with no writer");
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    let out = child.wait_with_output().unwrap();
    let line = crate::common::assert_usage_error(&out, &["start.csv", "a FIFO"]);
    assert!(line.contains("not a regular file; give a file"), "{line}");
}

#[test]
fn a_stiffness_files_prediction_data_and_its_two_stiffness_keys_are_checked() {
    let doc = crate::common::json(&crate::common::identify_fanuc(&["--cross-validate"]));
    let parse = |v: &serde_json::Value| stiffid::internal::io::stiffness::parse(&v.to_string());
    parse(&doc).unwrap();
    let mut floor = doc.clone();
    floor["prediction"]["noise_floor_mm"] = 1e300.into();
    let e = parse(&floor).unwrap_err().to_string();
    assert!(
        e.starts_with("prediction.noise_floor_mm: 1e300: expected 0 or"),
        "{e}"
    );
    let mut negative = doc.clone();
    let h = &mut negative["prediction"]["folds"][1]["compliance_si"][2];
    *h = (-h.as_f64().unwrap()).into();
    let e = parse(&negative).unwrap_err().to_string();
    assert!(
        e.starts_with("prediction.folds[2].compliance_si[3] as a stiffness: -"),
        "{e}"
    );
    let mut rho = doc.clone();
    rho["prediction"]["model_error_pct"] = 1e9.into();
    let e = parse(&rho).unwrap_err().to_string();
    assert!(
        e.starts_with("prediction.model_error_pct: 1e9: expected a share in [0, 10000]"),
        "{e}"
    );
    let mut score = doc.clone();
    score["prediction"]["deflection_scores"][4] = (-1.0).into();
    let e = parse(&score).unwrap_err().to_string();
    assert!(
        e.starts_with("prediction.deflection_scores[5]: -1: expected a finite number >= 0"),
        "{e}"
    );
    let mut alone = doc.clone();
    alone["prediction"]
        .as_object_mut()
        .unwrap()
        .remove("deflection_scores");
    let e = parse(&alone).unwrap_err().to_string();
    assert!(e.contains("together, or neither"), "{e}");
    // A file written before the deflection intervals: its measurement intervals serve.
    alone["prediction"]
        .as_object_mut()
        .unwrap()
        .remove("model_error_pct");
    let old = parse(&alone).unwrap().prediction.unwrap().calibration();
    assert!(old.deflection.is_none());
    let h = old.folds[0].compliance.clone();
    let rows = nalgebra::DMatrix::from_fn(3, h.len(), |r, c| 1e3 * (1 + r + c) as f64);
    assert_eq!(
        old.deflection_interval(&rows, &h, 0.9),
        old.interval(&rows, 0.9)
    );
    let new = parse(&doc).unwrap().prediction.unwrap().calibration();
    assert_ne!(
        new.deflection_interval(&rows, &h, 0.9),
        new.interval(&rows, 0.9)
    );
    let mut two = doc.clone();
    let k1 = doc["parameters"][0]["stiffness"].as_f64().unwrap();
    two["stiffness_nm_per_rad"] = serde_json::json!([2.0 * k1, 1e6, 1e6, 1e6, 1e6, 1e6]);
    let e = parse(&two).unwrap_err().to_string();
    assert!(
        e.starts_with("stiffness_nm_per_rad[1]: ")
            && e.contains("where parameters gives drive 'k1'"),
        "{e}"
    );
    // The drives' compliance and covariance, written twice, agree or the file is refused.
    assert!(parse(&doc).is_ok());
    let mut h = doc.clone();
    h["compliance_rad_per_nm"][0] = 1.0.into();
    let e = parse(&h).unwrap_err().to_string();
    assert!(
        e.starts_with("compliance_rad_per_nm[1]: 1 where the stiffness ")
            && e.contains("contradicts itself"),
        "{e}"
    );
    let mut zero = doc.clone();
    zero["compliance_covariance_rad2_per_nm2"][1][1] = 0.0.into();
    let e = parse(&zero).unwrap_err().to_string();
    assert!(
        e.starts_with(
            "compliance_covariance_rad2_per_nm2[2][2]: 0 where compliance_covariance_si gives "
        ),
        "{e}"
    );
    let mut drives = doc.clone();
    drives
        .as_object_mut()
        .unwrap()
        .remove("compliance_covariance_si");
    let e = parse(&drives).unwrap_err().to_string();
    assert!(
        e.starts_with("compliance_covariance_rad2_per_nm2: beside parameters"),
        "{e}"
    );
    let mut alone = serde_json::json!({"stiffness_nm_per_rad": doc["stiffness_nm_per_rad"]});
    alone["compliance_covariance_si"] = doc["compliance_covariance_si"].clone();
    let e = parse(&alone).unwrap_err().to_string();
    assert!(
        e.starts_with("compliance_covariance_si: without parameters"),
        "{e}"
    );
}

fn example(name: &str) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    path.join(name).to_str().unwrap().to_string()
}

/// `stiffid compensate` of `program` on the FANUC milling setup, writing `out`.
fn compensate(program: &str, out: &str) -> std::process::Output {
    let (setup, stiffness) = (
        example("milling/fanuc-milling.toml"),
        example("milling/stiffness.json"),
    );
    let process = example("milling/aluminium.toml");
    stiffid(&[
        "compensate",
        "--setup",
        &setup,
        "--stiffness",
        &stiffness,
        "--program",
        program,
        "--process",
        &process,
        "--out",
        out,
    ])
}

#[test]
fn a_robot_program_written_under_another_name_declares_that_name() {
    let d = temp_dir("answers-rename");
    let krl = "&ACCESS RVP\nDEF far( )\nPTP {A1 -60, A2 -17, A3 -29, A4 4, A5 -63, A6 145}\nPTP {A1 -58, A2 -15, A3 -28, A4 4, A5 -62, A6 140}\nEND\n";
    let src = write_file(&d, "far.src", krl);
    let out = d.join("pocket_c.src");
    let o = compensate(src.to_str().unwrap(), out.to_str().unwrap());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(
        text.starts_with("&ACCESS RVP\nDEF pocket_c( )\nPTP {A1 "),
        "{text}"
    );
    let position = |i: usize, q: [&str; 6]| {
        format!(
            "P[{i}]{{\n   GP1:\n\tUF : 0, UT : 1,\n\tJ1= {} deg,\tJ2= {} deg,\tJ3= {} deg,\n\tJ4= {} deg,\tJ5= {} deg,\tJ6= {} deg\n}};\n",
            q[0], q[1], q[2], q[3], q[4], q[5]
        )
    };
    let ls = format!(
        "/PROG  FAR\n/MN\n   1:J P[1] 10% FINE ;\n   2:J P[2] 10% FINE ;\n/POS\n{}{}/END\n",
        position(1, ["-60", "-17", "-29", "4", "-63", "145"]),
        position(2, ["-58", "-15", "-28", "4", "-62", "140"])
    );
    let ls = write_file(&d, "far.ls", &ls);
    let out = d.join("wall.ls");
    let o = compensate(ls.to_str().unwrap(), out.to_str().unwrap());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.starts_with("/PROG  WALL\n/MN\n"), "{text}");
    // A name the controller does not take is refused, nothing written.
    let long = d.join(format!("{}.ls", "w".repeat(37)));
    let o = compensate(ls.to_str().unwrap(), long.to_str().unwrap());
    crate::common::assert_usage_error(&o, &[&"W".repeat(37), "at most 36"]);
    let o = compensate(src.to_str().unwrap(), d.join("spl.src").to_str().unwrap());
    crate::common::assert_usage_error(&o, &["\"spl\"", "reserved word of KUKA KRL"]);
}

#[test]
fn a_program_name_is_refused_before_the_compensation_runs() {
    let d = temp_dir("answers-name-first");
    // The second point is 50 m away: its compensation fails, but the name is checked first.
    let nc = write_file(
        &d,
        "far.nc",
        "(stiffid: tool_rpy_deg = 180 0 0)\nG0 X0 Y0 Z5\nG1 X50000 F100\n",
    );
    let o = compensate(
        nc.to_str().unwrap(),
        d.join("pocketwall.ls").to_str().unwrap(),
    );
    crate::common::assert_usage_error(&o, &["\"POCKETWALL\"", "at most 8", "name_length"]);
    let o = compensate(nc.to_str().unwrap(), d.join("wall.ls").to_str().unwrap());
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && stderr.contains("far.nc"), "{stderr}");
}

#[test]
fn a_model_comparison_that_no_model_fits_physically_is_refused() {
    let d = temp_dir("answers-compare");
    // The first four postures of the FANUC data: the drives alone fit them with k4 < 0.
    let text = std::fs::read_to_string(crate::common::fanuc_csv()).unwrap();
    let four: Vec<&str> = text
        .lines()
        .filter(|l| !l.starts_with('#'))
        .take(5)
        .collect();
    let data = write_file(&d, "four.csv", &(four.join("\n") + "\n"));
    let args = [
        "identify",
        "--setup",
        "fanuc-r2000ic-165f",
        "--data",
        data.to_str().unwrap(),
    ];
    let out = stiffid(&[&args[..], &["--compare-models", "--json"]].concat());
    let line = crate::common::assert_usage_error(&out, &["4 given", "every stiffness positive"]);
    assert!(line.contains("measure more postures"), "{line}");
}

/// `select --margin-mm M` keeps M as `evaluate` measures it: one margin computation, the same
/// figure in both documents (the tool's part of a line of sight used to be exempt over M more,
/// so a search "kept" 30 mm where `evaluate` measured 7.9 mm of line of sight).
#[test]
fn the_margin_select_keeps_is_the_margin_evaluate_measures() {
    let d = temp_dir("answers-margin");
    let setup = example("cell/zhang2021-tracker.toml");
    for margin in [10.0, 30.0] {
        let out = d.join(format!("margin{margin}.csv"));
        let out = out.to_str().unwrap();
        let (m, s) = (format!("{margin}"), setup.as_str());
        let o = stiffid(&[
            "select",
            "--setup",
            s,
            "--global",
            "--seed",
            "1",
            "--margin-mm",
            &m,
            "--out",
            out,
            "--json",
        ]);
        let selected = crate::common::json(&o);
        let o = stiffid(&["evaluate", "--setup", s, "--postures", out, "--json"]);
        let evaluated = crate::common::json(&o);
        let kept = crate::common::numbers(&selected["min_margin_mm"]);
        let measured: Vec<f64> = evaluated["feasibility"]
            .as_array()
            .unwrap()
            .iter()
            .map(|f| f["min_margin_mm"].as_f64().unwrap())
            .collect();
        assert_eq!(kept.len(), measured.len());
        for (k, e) in kept.iter().zip(&measured) {
            // The postures file holds 6 decimals of a degree: 1e-6 deg moves a point by 1e-5 mm.
            assert!((k - e).abs() < 1e-3, "select {k} mm, evaluate {e} mm");
            assert!(*e >= margin, "{e} mm kept, {margin} mm asked");
        }
    }
}

/// `calibrate --cross-validate` takes one fold per posture: beyond its documented 5000 postures it
/// is refused before any fit, naming the limit and the way out.
#[test]
fn cross_validation_beyond_its_posture_limit_is_refused_at_once() {
    let d = temp_dir("answers-cross-limit");
    let model = model();
    let text = readings(&model, &truth(&model), &tracker(), &postures(5001, 1));
    write_file(&d, "many.csv", &text);
    let args = ["calibrate", "--setup", SETUP, "--data", "{dir}/many.csv"];
    let line = refused(
        &d,
        &[&args[..], &["--cross-validate"]].concat(),
        &[
            "cross_validate",
            "at most 5000 postures",
            "got 5001",
            "held-out",
        ],
    );
    assert!(line.starts_with("error: "), "{line}");
}

/// The maps' coefficients, held by their ridge, are not free parameters: 12 distinct postures
/// of 4 points (144 coordinates) calibrate with two 32-harmonic maps (128 coefficients beside
/// the geometry's), which the count of every fitted coefficient refused.
#[test]
fn map_coefficients_do_not_count_against_distinct_postures() {
    let d = temp_dir("answers-maps-count");
    let model = model();
    let text = readings(&model, &truth(&model), &tracker(), &postures(12, 3));
    write_file(&d, "twelve.csv", &text);
    let data = d.join("twelve.csv");
    let out = stiffid(&[
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        data.to_str().unwrap(),
        "--maps",
        "J1:32,J2:32",
        "--json",
    ]);
    let doc = crate::common::json(&out);
    assert!(doc["parameters"].as_array().unwrap().len() > 144, "{doc}");
}
