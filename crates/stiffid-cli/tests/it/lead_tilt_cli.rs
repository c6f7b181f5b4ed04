//! `stiffid compensate --free lead-tilt`: a path file leans within its cone (the CSV's and
//! the JSON's `lead_deg`, `tilt_deg`), no point worse than at its own axis; a G-code program
//! leans within its process file's cone and its robot program's joint targets are the leaned
//! compensated postures; written back as G-code it is refused, as are bad values, naming the
//! option, nothing written.

use crate::common;

use common::{assert_success, example, json, refused, stiffid, temp_dir, write_file};
use std::path::Path;

/// The CSV `csv`'s columns `names` of every row.
fn columns(csv: &Path, names: &[&str]) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let at: Vec<usize> = (names.iter())
        .map(|n| header.iter().position(|h| h == n).unwrap())
        .collect();
    lines
        .map(|l| {
            let cells: Vec<&str> = l.split(',').collect();
            at.iter().map(|&k| cells[k].parse().unwrap()).collect()
        })
        .collect()
}

/// The milling example's first 40 path points compensated with `extra` into `out`.
pub(crate) fn milling(dir: &Path, out: &str, extra: &[&str]) -> std::process::Output {
    let text = std::fs::read_to_string(example("milling/path.csv")).unwrap();
    let head: Vec<&str> = text.lines().take(41).collect();
    let path = write_file(dir, "path.csv", &(head.join("\n") + "\n"));
    let (setup, stiffness) = (
        example("milling/fanuc-milling.toml"),
        example("milling/stiffness.json"),
    );
    let out = dir.join(out);
    let mut args = vec!["compensate", "--setup", &setup, "--stiffness", &stiffness];
    args.extend([
        "--path",
        path.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    args.extend(extra);
    stiffid(&args)
}

#[test]
fn a_path_leans_within_its_cone_and_no_point_rises() {
    let dir = temp_dir("lead-tilt-path");
    assert_success(&milling(&dir, "own.csv", &[]));
    let flags = [
        "--free",
        "lead-tilt=-6..6/3",
        "--objective",
        "max",
        "--json",
    ];
    let out = milling(&dir, "lean.csv", &flags);
    assert_success(&out);
    let doc = json(&out);
    // One entry per free variable, in the units of --free; the objective once.
    let free = doc["free"].as_array().unwrap();
    assert_eq!(free.len(), 1);
    assert_eq!(free[0]["variable"], "lead-tilt");
    assert!((free[0]["range"].as_f64().unwrap() - 6.0).abs() < 1e-12);
    assert!((free[0]["step"].as_f64().unwrap() - 3.0).abs() < 1e-12);
    assert_eq!(
        (&free[0]["unit"], &free[0]["per"]),
        (&"deg".into(), &serde_json::Value::Null)
    );
    assert_eq!(
        (&doc["minimise"], &doc["objective"]),
        (&"bound".into(), &"max".into())
    );
    let names = ["bound_mm", "lead_deg", "tilt_deg"];
    let (own, lean) = (
        columns(&dir.join("own.csv"), &names),
        columns(&dir.join("lean.csv"), &names),
    );
    let points = doc["points"].as_array().unwrap();
    assert_eq!(points.len(), lean.len());
    let mut leaned = 0;
    for (i, (a, b)) in own.iter().zip(&lean).enumerate() {
        assert_eq!(a[1..], [0.0, 0.0], "{i}: no lean without the flag");
        assert!(b[0] <= a[0] + 1e-6, "{i}: {} mm > {} mm", b[0], a[0]);
        assert!(b[1].hypot(b[2]) <= 6.0 + 1e-9, "{i}: outside the cone");
        assert!((points[i]["lead_deg"].as_f64().unwrap() - b[1]).abs() < 1e-9);
        leaned += usize::from(b[1] != 0.0 || b[2] != 0.0);
    }
    for w in lean.windows(2) {
        assert!((w[1][1] - w[0][1]).abs() <= 3.0 + 1e-9 && (w[1][2] - w[0][2]).abs() <= 3.0 + 1e-9);
    }
    assert!(leaned > 0, "the tool leans somewhere");
    let peak = |rows: &[Vec<f64>]| rows.iter().map(|r| r[0]).fold(0.0, f64::max);
    assert!(peak(&lean) < peak(&own), "the peak bound falls");
    // The summary's leans are the points' (the largest magnitudes, the mean angle), and the
    // text states them.
    let s = &doc["summary"]["free_lead_tilt"];
    let angles: Vec<f64> = lean.iter().map(|r| r[1].hypot(r[2])).collect();
    let expected = [
        (
            "max_lead_deg",
            lean.iter().map(|r| r[1].abs()).fold(0.0, f64::max),
        ),
        (
            "max_tilt_deg",
            lean.iter().map(|r| r[2].abs()).fold(0.0, f64::max),
        ),
        ("max_lean_deg", angles.iter().copied().fold(0.0, f64::max)),
        (
            "mean_lean_deg",
            angles.iter().sum::<f64>() / angles.len() as f64,
        ),
    ];
    for (key, value) in expected {
        assert!(
            (s[key].as_f64().unwrap() - value).abs() < 1e-9,
            "{key}: {s}"
        );
    }
    assert!(expected[2].1 > 0.0);
    let text = milling(&dir, "lean-text.csv", &flags[..flags.len() - 1]);
    assert_success(&text);
    let stdout = String::from_utf8_lossy(&text.stdout);
    let line = format!(
        "lead and tilt: largest lead {:.2} deg, largest tilt {:.2} deg, largest lean {:.2} deg, mean lean {:.2} deg",
        expected[0].1, expected[1].1, expected[2].1, expected[3].1
    );
    assert!(stdout.contains(&line), "{stdout}");
    let own_text = milling(&dir, "own-text.csv", &[]);
    assert!(!String::from_utf8_lossy(&own_text.stdout).contains("lead and tilt"));
}

#[test]
fn a_program_leans_within_its_process_cone_into_its_joint_targets() {
    let dir = temp_dir("lead-tilt-program");
    let process = std::fs::read_to_string(example("milling/trim.toml")).unwrap();
    let process = write_file(
        &dir,
        "trim.toml",
        &(process + "\n[operation.tool_axis]\ncone_deg = 4\n"),
    );
    let (setup, stiffness, program) = (
        example("milling/fanuc-milling.toml"),
        example("milling/stiffness.json"),
        example("milling/trim.nc"),
    );
    let run = |name: &str, extra: &[&str]| {
        let (out, csv) = (
            dir.join(format!("{name}.ls")),
            dir.join(format!("{name}.csv")),
        );
        let mut args = vec!["compensate", "--setup", &setup, "--stiffness", &stiffness];
        args.extend([
            "--program",
            &program,
            "--process",
            process.to_str().unwrap(),
        ]);
        args.extend([
            "--out",
            out.to_str().unwrap(),
            "--csv",
            csv.to_str().unwrap(),
        ]);
        args.extend(["--targets", "joint"]);
        args.extend(extra);
        assert_success(&stiffid(&args));
        (std::fs::read_to_string(out).unwrap(), csv)
    };
    let (_, own_csv) = run("OWN", &[]);
    let lean = ["--free", "lead-tilt=/2"];
    let (ls, csv) = run("LEAN", &lean);
    let names = [
        "lead_deg", "tilt_deg", "qc1_deg", "qc2_deg", "qc3_deg", "qc4_deg", "qc5_deg",
    ];
    let (rows, own) = (columns(&csv, &names), columns(&own_csv, &names));
    assert!(rows.iter().all(|r| r[0].hypot(r[1]) <= 4.0 + 1e-9));
    let moved: Vec<&Vec<f64>> = (rows.iter().zip(&own))
        .filter(|(r, o)| (r[0] != 0.0 || r[1] != 0.0) && (r[2] - o[2]).abs() > 0.01)
        .map(|(r, _)| r)
        .collect();
    assert!(!moved.is_empty(), "some compensated posture leans");
    // Every joint target of the LS program is a compensated posture of the CSV, leaned ones too.
    let targets: Vec<Vec<f64>> = (ls.split("J1=").skip(1))
        .map(|t| {
            (t.split('=').take(5))
                .map(|v| v.trim().split(' ').next().unwrap().parse().unwrap())
                .collect()
        })
        .collect();
    assert!(!targets.is_empty());
    let near = |t: &[f64], r: &[f64]| t.iter().zip(&r[2..]).all(|(a, b)| (a - b).abs() < 2e-3);
    for t in &targets {
        assert!(
            rows.iter().any(|r| near(t, r)),
            "{t:?} is no compensated posture"
        );
    }
    assert!(moved.iter().any(|r| targets.iter().any(|t| near(t, r))));
}

#[test]
fn bad_lean_options_and_gcode_written_as_gcode_are_refused() {
    let dir = temp_dir("lead-tilt-refused");
    let (setup, stiffness) = (
        example("milling/fanuc-milling.toml"),
        example("milling/stiffness.json"),
    );
    let path = example("milling/path.csv");
    let base = [
        "compensate",
        "--setup",
        &setup,
        "--stiffness",
        &stiffness,
        "--path",
        &path,
        "--out",
        "{dir}/out.csv",
        "--free",
    ];
    for (text, option) in [
        ("lead-tilt=-40..40", "--free lead-tilt range"),
        ("lead-tilt=2..-2", "--free: lead-tilt=2..-2"),
        ("lead-tilt=-NaN..NaN", "--free: lead-tilt=-NaN..NaN"),
        ("lead-tilt=-5..5/0", "--free lead-tilt step"),
        ("lead-tilt=-5..5/6", "--free lead-tilt step"),
        ("lead-tilt", "--free lead-tilt range"),
    ] {
        let args: Vec<&str> = base.iter().copied().chain([text]).collect();
        refused(&dir, &args, &[option]);
    }
    let process = std::fs::read_to_string(example("milling/trim.toml")).unwrap();
    write_file(
        &dir,
        "trim.toml",
        &(process + "\n[operation.tool_axis]\ncone_deg = 4\n"),
    );
    let program = example("milling/trim.nc");
    let args = [
        "compensate",
        "--setup",
        &setup,
        "--stiffness",
        &stiffness,
        "--program",
        &program,
        "--process",
        "{dir}/trim.toml",
        "--out",
        "{dir}/trim.nc",
        "--free",
        "lead-tilt",
    ];
    refused(&dir, &args, &["--free lead-tilt", "robot program"]);
}
