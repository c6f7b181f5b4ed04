//! `stiffid identify`, `validate` and `predict` from the command line: the real FANUC data against
//! an independent NumPy fit, noise-free round trips through `predict`, and bad input.

use crate::common;

use common::{
    assert_usage_error, fanuc_csv, identify_fanuc, json, numbers, stiffid, temp_dir,
    validate_fanuc, write_file,
};
use serde_json::Value;

#[test]
fn fanuc_data_agree_with_the_numpy_least_squares_fit() {
    let r = json(&identify_fanuc(&[]));
    // Printed by examples/data/fanuc-r2000ic-165f/numpy_reference.py (numpy.linalg.lstsq on the
    // original rad/N/m files, its own kinematics from the data's README).
    let numpy = [
        860895.9548537338,
        2719582.5090577677,
        1959759.573843235,
        270828.31110452657,
        424693.0311889889,
        206019.76170944763,
    ];
    let k = numbers(&r["stiffness_nm_per_rad"]);
    for j in 0..6 {
        let rel = (k[j] - numpy[j]).abs() / numpy[j];
        assert!(
            rel < 1e-6,
            "joint {}: {} vs NumPy {}",
            j + 1,
            k[j],
            numpy[j]
        );
    }
    let cond = r["cond_psi"].as_f64().unwrap();
    assert!(
        (cond - 87.05172094537497).abs() < 1e-6 * 87.05,
        "cond {cond}"
    );
    assert_eq!(r["rows"], 129);
    assert_eq!(r["postures"], 43);
    assert_eq!(r["residuals"].as_array().unwrap().len(), 43);
    let ci = r["ci95_nm_per_rad"].as_array().unwrap();
    for j in 0..6 {
        let [lo, hi] = [ci[j][0].as_f64().unwrap(), ci[j][1].as_f64().unwrap()];
        assert!(lo < k[j] && k[j] < hi);
    }
    // Joint 1 is well determined, joint 6 is not (relative standard errors 3.5% and 48%).
    let se = numbers(&r["std_error_nm_per_rad"]);
    assert!(se[0] / k[0] < 0.05 && se[5] / k[5] > 0.4, "{se:?}");
    // Flagged poorly determined: a relative standard error above 0.25, joint 6 and not joint 1.
    let poor: Vec<bool> = r["poorly_determined"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_bool().unwrap())
        .collect();
    for j in 0..6 {
        assert_eq!(poor[j], se[j] / k[j] > 0.25, "joint {}: {poor:?}", j + 1);
    }
    assert!(!poor[0] && poor[5], "{poor:?}");
    // The text names the same joints.
    let out = stiffid(&[
        "identify",
        "--setup",
        "fanuc-r2000ic-165f",
        "--data",
        fanuc_csv().to_str().unwrap(),
    ]);
    let text = String::from_utf8(out.stdout).unwrap();
    let named: Vec<String> = (0..6)
        .filter(|&j| poor[j])
        .map(|j| (j + 1).to_string())
        .collect();
    let list = match named.len() {
        1 => format!("joint {}", named[0]),
        _ => format!("joints {}", named.join(", ")),
    };
    assert!(
        text.contains(&format!(
            "poorly determined (std error > 25% of the value): {list};"
        )),
        "{text}"
    );
}

#[test]
fn out_file_feeds_validate_and_predict() {
    let dir = temp_dir("identify-out");
    let result = dir.join("result.json");
    let data = fanuc_csv();
    let id = json(&identify_fanuc(&["--out", result.to_str().unwrap()]));
    let written: Value = serde_json::from_slice(&std::fs::read(&result).unwrap()).unwrap();
    assert_eq!(written, id);
    // Validating on the fitted data: delta_b of each measurement is the norm of its residual.
    let v = json(&validate_fanuc(&result, &["--json"]));
    let checks = v["checks"].as_array().unwrap();
    for (c, res) in checks.iter().zip(id["residuals"].as_array().unwrap()) {
        let norm = numbers(&res["residual_mm"])
            .iter()
            .map(|x| x * x)
            .sum::<f64>()
            .sqrt();
        assert!((c["delta_b_mm"].as_f64().unwrap() - norm).abs() < 1e-9);
    }
    let rms = v["rms_delta_b_mm"].as_f64().unwrap();
    assert!((rms - id["residual_rms_mm"].as_f64().unwrap() * 3f64.sqrt()).abs() < 1e-9);
    // The explained share in %, as the text prints it.
    let explained = 1.0 - rms / v["rms_measured_mm"].as_f64().unwrap();
    let percent = v["explained_pct"].as_f64().unwrap();
    assert!((percent - 100.0 * explained).abs() < 1e-9, "{percent}");
    let text = String::from_utf8(validate_fanuc(&result, &[]).stdout).unwrap();
    let shown = format!("1 - RMS(delta_b)/RMS(|delta_m|): {percent:.1}%\n");
    assert!(text.contains(&shown), "{shown} not in\n{text}");
    // With held-out residuals in the stiffness file: the intervals' coverage in %.
    let cv = dir.join("cv.json");
    json(&identify_fanuc(&[
        "--cross-validate",
        "--out",
        cv.to_str().unwrap(),
    ]));
    let v = json(&validate_fanuc(&cv, &["--json"]));
    let p = &v["prediction_intervals"];
    let (covered, all) = (
        p["covered"].as_f64().unwrap(),
        p["coordinates"].as_f64().unwrap(),
    );
    let coverage = p["coverage_pct"].as_f64().unwrap();
    assert!(
        (coverage - 100.0 * covered / all).abs() < 1e-9,
        "{coverage}"
    );
    let text = String::from_utf8(validate_fanuc(&cv, &[]).stdout).unwrap();
    let shown = format!("{coverage:.1}% of {all} measured coordinates inside");
    assert!(text.contains(&shown), "{shown} not in\n{text}");
    // predict with the identified stiffness reproduces validate's prediction of line 2.
    let first = &checks[0];
    let q: Vec<String> = {
        let text = std::fs::read_to_string(&data).unwrap();
        let row: Vec<String> = text
            .lines()
            .nth(1)
            .unwrap()
            .split(',')
            .map(str::to_string)
            .collect();
        vec![row[2..8].join(","), row[8..11].join(",")]
    };
    let p = json(&stiffid(&[
        "predict",
        "--setup",
        "fanuc-r2000ic-165f",
        "--q-deg",
        &q[0],
        "--wrench",
        &q[1],
        "--stiffness",
        result.to_str().unwrap(),
        "--json",
    ]));
    let predicted = numbers(&p["measuring_points"][0]["displacement_mm"]);
    let expected = numbers(&first["predicted_mm"]);
    for a in 0..3 {
        assert!(
            (predicted[a] - expected[a]).abs() < 1e-9,
            "{predicted:?} vs {expected:?}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Postures inside the paper setup's bounds and wrenches with moments.
const POSTURES: [(&str, &str); 7] = [
    ("10,-20,-100,30,40,50", "300,-200,-400,20,-30,15"),
    ("-40,10,-70,-60,-30,120", "-250,350,-300,-10,25,40"),
    ("60,-40,-140,90,60,-90", "100,100,-500,30,10,-20"),
    ("-70,30,-60,-150,-70,10", "400,-50,-200,-25,-15,35"),
    ("30,-50,-160,160,20,-150", "-150,-300,-350,15,40,-30"),
    ("0,0,-90,45,-45,90", "200,250,-450,-35,20,10"),
    ("-20,-10,-120,-30,70,-60", "-350,150,-250,25,-35,-25"),
];

#[test]
fn noise_free_predictions_identify_back_to_the_nominal_stiffness() {
    let dir = temp_dir("roundtrip");
    let mut relative =
        "posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,fx_n,fy_n,fz_n,mx_nm,my_nm,mz_nm,dx_mm,dy_mm,dz_mm\n"
            .to_string();
    let mut positions = "posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,fx_n,fy_n,fz_n,mx_nm,my_nm,mz_nm,x_loaded_mm,y_loaded_mm,z_loaded_mm,x_unloaded_mm,y_unloaded_mm,z_unloaded_mm\n".to_string();
    for (i, (q, w)) in POSTURES.iter().enumerate() {
        let p = json(&stiffid(&[
            "predict",
            "--setup",
            "zhang2021-comau-nj165",
            "--q-deg",
            q,
            "--wrench",
            w,
            "--json",
        ]));
        for point in p["measuring_points"].as_array().unwrap() {
            let d = numbers(&point["displacement_mm"]);
            let x = numbers(&point["position_mm"]);
            let k = point["point"].as_u64().unwrap();
            let f = |v: &[f64]| {
                v.iter()
                    .map(|x| format!("{x:?}"))
                    .collect::<Vec<_>>()
                    .join(",")
            };
            relative += &format!("P{},{k},{q},{w},{}\n", i + 1, f(&d));
            let loaded: Vec<f64> = x.iter().zip(&d).map(|(a, b)| a + b).collect();
            positions += &format!("P{},{k},{q},{w},{},{}\n", i + 1, f(&loaded), f(&x));
        }
    }
    let nominal = [950000.0, 3000000.0, 900000.0, 250000.0, 200000.0, 150000.0];
    for (name, text, tolerance) in [
        ("relative.csv", relative, 1e-9),
        ("positions.csv", positions, 1e-7),
    ] {
        let file = write_file(&dir, name, &text);
        let r = json(&stiffid(&[
            "identify",
            "--setup",
            "zhang2021-comau-nj165",
            "--data",
            file.to_str().unwrap(),
            "--json",
        ]));
        assert_eq!(
            (r["rows"].as_u64(), r["postures"].as_u64()),
            (Some(84), Some(7))
        );
        let k = numbers(&r["stiffness_nm_per_rad"]);
        for j in 0..6 {
            let rel = (k[j] - nominal[j]).abs() / nominal[j];
            assert!(
                rel < tolerance,
                "{name}, joint {}: relative error {rel:e}",
                j + 1
            );
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Runs `identify --out` on `text` and checks: exit code 2, one error line containing every
/// `expected` part, no panic, no output file.
fn rejects(name: &str, text: &str, setup: &str, expected: &[&str]) {
    let dir = temp_dir(&format!("bad-{name}"));
    let file = write_file(&dir, &format!("{name}.csv"), text);
    let out_file = dir.join("result.json");
    let out = stiffid(&[
        "identify",
        "--setup",
        setup,
        "--data",
        file.to_str().unwrap(),
        "--out",
        out_file.to_str().unwrap(),
    ]);
    assert_usage_error(&out, &[&[file.to_str().unwrap()], expected].concat());
    assert!(!out_file.exists(), "{name}: output file left behind");
    assert!(
        std::fs::read_dir(&dir).unwrap().count() == 1,
        "{name}: temporary file left"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

fn fanuc_lines() -> Vec<String> {
    std::fs::read_to_string(fanuc_csv())
        .unwrap()
        .lines()
        .map(str::to_string)
        .collect()
}

/// The FANUC file with line `line` (1-based) changed by `edit`.
fn fanuc_with(line: usize, edit: impl Fn(&str) -> String) -> String {
    let mut lines = fanuc_lines();
    lines[line - 1] = edit(&lines[line - 1]);
    lines.join("\n") + "\n"
}

/// Replaces field `column` (1-based) of a CSV line.
fn field(line: &str, column: usize, value: &str) -> String {
    let mut fields: Vec<&str> = line.split(',').collect();
    fields[column - 1] = value;
    fields.join(",")
}

#[test]
fn bad_data_files_are_one_line_errors_naming_line_and_column() {
    let fanuc = "fanuc-r2000ic-165f";
    rejects("empty", "", fanuc, &["empty"]);
    rejects(
        "header-only",
        &(fanuc_lines()[0].clone() + "\n"),
        fanuc,
        &["at least one measurement"],
    );
    rejects(
        "missing-column",
        &fanuc_with(1, |l| l.replace("q4_deg", "q4")),
        fanuc,
        &[
            "line 1, column 6",
            "unknown column 'q4'",
            "did you mean 'q4_deg'",
        ],
    );
    rejects(
        "misspelled",
        &fanuc_with(1, |l| l.replace("fx_n", "fx_N")),
        fanuc,
        &["line 1, column 9", "'fx_N'", "did you mean 'fx_n'"],
    );
    let dropped: String = fanuc_lines()
        .iter()
        .map(|l| {
            let mut f: Vec<&str> = l.split(',').collect();
            f.remove(12);
            f.join(",") + "\n"
        })
        .collect();
    rejects(
        "dropped-column",
        &dropped,
        fanuc,
        &["line 1", "missing column 'dy_mm'"],
    );
    rejects(
        "text",
        &fanuc_with(4, |l| field(l, 10, "abc")),
        fanuc,
        &["line 4, column 10 (fy_n)", "'abc' is not a finite number"],
    );
    rejects(
        "nan",
        &fanuc_with(7, |l| field(l, 13, "NaN")),
        fanuc,
        &["line 7, column 13 (dy_mm)", "'NaN'"],
    );
    rejects(
        "point",
        &fanuc_with(5, |l| field(l, 2, "2")),
        fanuc,
        &[
            "line 5, column 2 (point)",
            "measuring point 2 does not exist",
        ],
    );
    rejects(
        "limits",
        &fanuc_with(9, |l| field(l, 3, "300")),
        fanuc,
        &["line 9, column 3 (q1_deg)", "outside the robot's limits"],
    );
    rejects(
        "short-row",
        &fanuc_with(3, |l| l.rsplit_once(',').unwrap().0.to_string()),
        fanuc,
        &["line 3", "expected 14 fields"],
    );
    let two_rows = fanuc_lines()[..2].join("\n") + "\n";
    rejects(
        "one-row",
        &two_rows,
        fanuc,
        &["3 observation rows", "at least 6"],
    );
    // The same posture three times: 9 rows, but only 3 independent ones.
    let line = &fanuc_lines()[1];
    let repeated = format!("{}\n{line}\n{line}\n{line}\n", fanuc_lines()[0]);
    rejects(
        "dependent",
        &repeated,
        fanuc,
        &["cannot be identified", "linearly dependent"],
    );
}

#[test]
fn out_never_overwrites_the_data_file() {
    let dir = temp_dir("overwrite");
    let text = std::fs::read_to_string(fanuc_csv()).unwrap();
    let file = write_file(&dir, "data.csv", &text);
    let out = stiffid(&[
        "identify",
        "--setup",
        "fanuc-r2000ic-165f",
        "--data",
        file.to_str().unwrap(),
        "--out",
        file.to_str().unwrap(),
    ]);
    assert_usage_error(&out, &["refusing"]);
    assert_eq!(std::fs::read_to_string(&file).unwrap(), text);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_stiffness_files_and_arguments_are_errors() {
    let dir = temp_dir("bad-stiffness");
    let file = write_file(
        &dir,
        "k.json",
        r#"{"stiffness_nm_per_rad": [1, 2, 3, 4, 5, -6]}"#,
    );
    let data = fanuc_csv();
    let cases: [(&[&str], &str); 4] = [
        (
            &[
                "validate",
                "--setup",
                "fanuc-r2000ic-165f",
                "--stiffness",
                file.to_str().unwrap(),
                "--data",
                data.to_str().unwrap(),
            ],
            "stiffness_nm_per_rad[6]: -6 is outside",
        ),
        (
            &[
                "predict",
                "--setup",
                "fanuc-r2000ic-165f",
                "--q-deg",
                "0,0,0,0,0",
                "--wrench",
                "0,0,-500",
            ],
            "--q-deg: expected 6",
        ),
        (
            &[
                "predict",
                "--setup",
                "fanuc-r2000ic-165f",
                "--q-deg",
                "0,0,0,0,0,0",
                "--wrench",
                "0,-500",
            ],
            "--wrench: expected fx,fy,fz",
        ),
        (
            &[
                "predict",
                "--setup",
                "fanuc-r2000ic-165f",
                "--q-deg",
                "400,0,0,0,0,0",
                "--wrench",
                "0,0,-500",
            ],
            "--q-deg[1] = 400.00 deg: expected within the robot's limits [-185.00, 185.00] deg",
        ),
    ];
    for (args, expected) in cases {
        assert_usage_error(&stiffid(args), &[expected]);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn robust_flag_alone_is_the_huber_fit_and_lists_down_weighted_rows() {
    let alone = json(&identify_fanuc(&["--robust"]));
    let huber = json(&identify_fanuc(&["--robust", "huber"]));
    let plain = json(&identify_fanuc(&[]));
    assert_eq!(alone, huber);
    assert_ne!(
        numbers(&alone["stiffness_nm_per_rad"]),
        numbers(&plain["stiffness_nm_per_rad"]),
        "the robust fit reweights the FANUC rows"
    );
    assert!(plain["robust"].is_null());
    assert_eq!(alone["robust"]["loss"], "huber");
    let down = alone["robust"]["down_weighted"].as_array().unwrap();
    assert!(
        !down.is_empty() && down.len() < 43,
        "some, not all, of the 43 FANUC rows are down-weighted: {down:?}"
    );
}

/// The document and the text of the FANUC data identified with `--cross-validate`.
fn cross_validated_fanuc() -> (Value, String) {
    let doc = json(&identify_fanuc(&["--cross-validate"]));
    let data = fanuc_csv();
    let setup = ["identify", "--setup", "fanuc-r2000ic-165f", "--data"];
    let out = stiffid(&[&setup[..], &[data.to_str().unwrap(), "--cross-validate"]].concat());
    assert!(out.status.success());
    (doc, String::from_utf8(out.stdout).unwrap())
}

#[test]
fn text_figures_of_the_cross_validation_are_the_documents() {
    let (doc, text) = cross_validated_fanuc();
    let cv = &doc["cross_validation"];
    // std/full: the document's percentage, itself the fold std over the full fit's stiffness.
    let (std, full) = (
        numbers(&cv["stiffness_std_nm_per_rad"]),
        numbers(&doc["stiffness_nm_per_rad"]),
    );
    let percent = numbers(&cv["stiffness_std_pct"]);
    let spread = text.split("spread across folds:\n").nth(1).unwrap();
    for j in 0..6 {
        assert!((percent[j] - 100.0 * std[j] / full[j].abs()).abs() < 1e-9 * percent[j]);
        let row = spread.lines().nth(1 + j).unwrap();
        let shown = row.split_whitespace().nth(4).unwrap();
        assert_eq!(shown, format!("{:.1}%", percent[j]), "joint {}", j + 1);
    }
    // The 95% quantile: the ceil(0.95 N)-th smallest of the held-out scores the document holds.
    let p = &doc["prediction"];
    let mut scores: Vec<f64> = (p["folds"].as_array().unwrap().iter())
        .flat_map(|f| numbers(&f["scores"]))
        .collect();
    scores.sort_by(f64::total_cmp);
    let q95 = p["score_q95"].as_f64().unwrap();
    assert_eq!(
        q95,
        scores[(0.95 * scores.len() as f64).ceil() as usize - 1]
    );
    assert!(q95 > scores[0] && q95 < scores[scores.len() - 1]);
    assert_eq!(p["score_q95_pct"].as_f64().unwrap(), 100.0 * q95);
    let within = format!(
        "95% of the held-out errors are within {:.1}% of the predicted displacement",
        p["score_q95_pct"].as_f64().unwrap()
    );
    assert!(text.contains(&within), "{within} not in\n{text}");
}

#[test]
fn text_relative_errors_and_largest_residuals_are_the_documents() {
    let (doc, text) = cross_validated_fanuc();
    // rel.: the standard error over the stiffness, %, in the document and in the text's tables
    // (from the residual variance, then from the tracker noise).
    let k = numbers(&doc["stiffness_nm_per_rad"]);
    let tables: Vec<&str> = text
        .split("joint  stiffness Nm/rad  std error  rel.")
        .collect();
    assert_eq!(tables.len(), 3, "{text}");
    for (t, intervals) in [&doc, &doc["tracker_noise"]].into_iter().enumerate() {
        let (se, percent) = (
            numbers(&intervals["std_error_nm_per_rad"]),
            numbers(&intervals["std_error_pct"]),
        );
        for j in 0..6 {
            assert!((percent[j] - 100.0 * se[j] / k[j].abs()).abs() < 1e-12 * percent[j]);
            let row = tables[1 + t].lines().nth(1 + j).unwrap();
            let shown = row.split_whitespace().nth(3).unwrap();
            assert_eq!(shown, format!("{:.1}%", percent[j]), "joint {}", j + 1);
        }
    }
    assert_eq!(doc["poorly_determined_above_pct"], 25.0);
    // The five longest of the 43 residuals, the longest first, as the text lists them.
    let all = doc["residuals"].as_array().unwrap();
    let norm = |r: &Value| {
        numbers(&r["residual_mm"])
            .iter()
            .map(|v| v * v)
            .sum::<f64>()
            .sqrt()
    };
    let largest = doc["largest_residuals"].as_array().unwrap();
    assert_eq!(largest.len(), 5);
    let listed = text.split("largest residuals").nth(1).unwrap();
    for (i, r) in largest.iter().enumerate() {
        let n = r["norm_mm"].as_f64().unwrap();
        assert!((n - norm(r)).abs() < 1e-12 * n);
        let same = all.iter().find(|a| a["line"] == r["line"]).unwrap();
        assert_eq!(same, r);
        let longer = all.iter().filter(|a| norm(a) > n * (1.0 + 1e-12)).count();
        assert_eq!(
            longer,
            i,
            "residual {} is the {}-th longest",
            i + 1,
            longer + 1
        );
        let line = listed.lines().nth(1 + i).unwrap();
        assert!(line.ends_with(&format!("|{n:.4}|")), "{line}");
        assert!(
            line.contains(&format!("line {:>4}", r["line"].as_u64().unwrap())),
            "{line}"
        );
    }
    // The held-out share and its standard error in %.
    let cv = &doc["cross_validation"];
    let explained = cv["explained"].as_f64().unwrap();
    assert_eq!(cv["explained_pct"].as_f64().unwrap(), 100.0 * explained);
    let shown = format!(
        "the model explains {:.1}% (standard error {:.1},",
        100.0 * explained,
        100.0 * cv["explained_std_error"].as_f64().unwrap()
    );
    assert!(text.contains(&shown), "{shown} not in\n{text}");
}

/// `--compare-models --bootstrap`: the text's bootstrap table shows the document's figures (the
/// same seed, the same resamples), one row per parameter chosen; without `--bootstrap` the
/// document has no `bootstrap` and the text no table.
#[test]
fn text_of_the_bootstrap_is_the_documents() {
    let args = [
        "--compare-models",
        "--candidates",
        "tilt3_x,tool_y",
        "--bootstrap",
        "12",
        "--seed",
        "4",
    ];
    let doc = json(&identify_fanuc(&args));
    let b = &doc["bootstrap"];
    let data = fanuc_csv();
    let base = ["identify", "--setup", "fanuc-r2000ic-165f", "--data"];
    let out = stiffid(&[&base[..], &[data.to_str().unwrap()], &args[..]].concat());
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.contains("Posture bootstrap (12 resamples, seed 4;"),
        "{text}"
    );
    let share = 100.0 * b["recommended_share"].as_f64().unwrap();
    assert!(text.contains(&format!("the recommended model exactly: {share:.1}%")));
    let table = text.split("97.5%  unit\n").nth(1).unwrap();
    let parameters = b["parameters"].as_array().unwrap();
    assert!(parameters.len() >= 6);
    for (p, row) in parameters.iter().zip(table.lines()) {
        let fields: Vec<&str> = row.split_whitespace().collect();
        let value = |key: &str| format!("{:.0}", p[key].as_f64().unwrap());
        let chosen = format!("{:.1}%", 100.0 * p["chosen_share"].as_f64().unwrap());
        let expected = [
            p["name"].as_str().unwrap().to_string(),
            chosen,
            value("median"),
            value("percentile_2_5"),
            value("percentile_97_5"),
            p["unit"].as_str().unwrap().to_string(),
        ];
        assert_eq!(fields, expected, "{row}");
    }
    let without = json(&identify_fanuc(&args[..3]));
    assert!(without.get("bootstrap").is_none());
}
