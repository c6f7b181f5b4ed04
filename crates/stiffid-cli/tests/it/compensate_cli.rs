//! `stiffid predict --at-mm/--frame`, the covariance of `identify --out`, and `stiffid compensate`
//! on the milling example: results, report, and bad path files refused whole.

use crate::common;

use common::{
    assert_failed_gate, assert_success, assert_usage_error, example, identify_fanuc, json, numbers,
    stiffid, temp_dir, write_file,
};
use std::path::{Path, PathBuf};
use std::process::Output;

const FANUC_Q: &str = "--q-deg=-59.991,-16.693,-28.93,3.788,-62.93,144.919";

#[test]
fn a_tool_frame_wrench_predicts_what_the_rotated_base_wrench_does() {
    let tool = json(&stiffid(&[
        "predict",
        "--setup",
        "fanuc-r2000ic-165f",
        FANUC_Q,
        "--wrench",
        "10,-20,-200,1,2,3",
        "--frame",
        "tool",
        "--at-mm",
        "0,0,300",
        "--json",
    ]));
    let base: Vec<String> = numbers(&tool["wrench_base_frame_n_nm"])
        .iter()
        .map(|v| format!("{v:.12}"))
        .collect();
    let rotated = json(&stiffid(&[
        "predict",
        "--setup",
        "fanuc-r2000ic-165f",
        FANUC_Q,
        "--wrench",
        &base.join(","),
        "--at-mm",
        "0,0,300",
        "--json",
    ]));
    for key in ["tcp_deflection_mm", "tcp_rotation_mrad", "torques_nm"] {
        let (a, b) = (numbers(&tool[key]), numbers(&rotated[key]));
        for (x, y) in a.iter().zip(&b) {
            assert!(
                (x - y).abs() <= 1e-9 * (1.0 + x.abs()),
                "{key}: {a:?} vs {b:?}"
            );
        }
    }
    assert_eq!(numbers(&tool["wrench_point_mm"]), [0.0, 0.0, 300.0]);
    // C_x K_x = I, and C_x is symmetric with positive translation compliance.
    let c = &tool["cartesian_compliance"]["matrix_si"];
    let k = &tool["cartesian_stiffness"]["matrix_si"];
    for i in 0..6 {
        for j in 0..6 {
            let ij: f64 = (0..6)
                .map(|m| c[i][m].as_f64().unwrap() * k[m][j].as_f64().unwrap())
                .sum();
            assert!(
                (ij - if i == j { 1.0 } else { 0.0 }).abs() < 1e-8,
                "{i},{j}: {ij}"
            );
            assert_eq!(c[i][j], c[j][i]);
        }
    }
    assert!(
        tool["cartesian_compliance"]["translation_per_force_m_per_n"][0][0].as_f64() > Some(0.0)
    );
    assert!(tool["tcp_deflection_std_mm"].is_null());
}

#[test]
fn identified_covariance_gives_standard_deviations() {
    let dir = temp_dir("covariance");
    let out = dir.join("k.json");
    let id = json(&identify_fanuc(&["--out", out.to_str().unwrap()]));
    let cov = &id["compliance_covariance_rad2_per_nm2"];
    let se = numbers(&id["compliance_std_error_rad_per_nm"]);
    for j in 0..6 {
        let var = cov[j][j].as_f64().unwrap();
        assert!((var.sqrt() / se[j] - 1.0).abs() < 1e-9, "joint {}", j + 1);
        for m in 0..6 {
            assert_eq!(cov[j][m], cov[m][j]);
        }
    }
    let p = json(&stiffid(&[
        "predict",
        "--setup",
        "fanuc-r2000ic-165f",
        FANUC_Q,
        "--wrench",
        "0,0,-200",
        "--stiffness",
        out.to_str().unwrap(),
        "--json",
    ]));
    let std = numbers(&p["tcp_deflection_std_mm"]);
    let d = numbers(&p["tcp_deflection_mm"]);
    for (s, v) in std.iter().zip(&d) {
        assert!(*s > 0.0 && *s < v.abs().max(1e-3), "std {s} of {v}");
    }
    assert_eq!(
        numbers(&p["measuring_points"][0]["displacement_std_mm"]),
        std
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

fn compensate(path: &str, out: &Path, extra: &[&str]) -> std::process::Output {
    let stiffness = example("milling/stiffness.json");
    let setup = example("milling/fanuc-milling.toml");
    let mut args = vec![
        "compensate",
        "--setup",
        &setup,
        "--stiffness",
        &stiffness,
        "--path",
        path,
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend(extra);
    stiffid(&args)
}

#[test]
fn the_milling_example_is_compensated_with_a_report() {
    let dir = temp_dir("milling");
    let out = dir.join("out.csv");
    let report = dir.join("report");
    let path = example("milling/path.csv");
    let r = json(&compensate(
        &path,
        &out,
        &["--json", "--report", report.to_str().unwrap()],
    ));
    let rows = std::fs::read_to_string(&path).unwrap().lines().count() - 1;
    assert_eq!(r["points"].as_array().unwrap().len(), rows);
    assert_eq!(r["summary"]["points"], rows);
    assert!(r["summary"]["max_residual_um"].as_f64().unwrap() < 0.1);
    assert!(r["summary"]["max_residual_urad"].as_f64().unwrap() < 1.0);
    let max = r["summary"]["max_deflection_mm"].as_f64().unwrap();
    assert!(max > 0.1 && max < 5.0, "{max}");
    let csv = std::fs::read_to_string(&out).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    for column in [
        "q1_deg",
        "x_mm",
        "fx_base_n",
        "dx_mm",
        "dx_std_mm",
        "qc6_deg",
        "residual_um",
    ] {
        assert!(header.contains(&column), "{column}");
    }
    assert_eq!(csv.lines().count(), rows + 1);
    for file in [
        "report.html",
        "summary.json",
        "compensation.csv",
        "figures/deflection.svg",
        "figures/path.svg",
    ] {
        assert!(report.join(file).is_file(), "{file}");
    }
    // The page shows each figure's SVG inline: no PNG copy is drawn for it.
    assert!(!report.join("figures/path.png").exists());
    let html = std::fs::read_to_string(report.join("report.html")).unwrap();
    assert!(html.contains("<svg") && !html.contains("src=\"http"));
    // Again into the same report directory: it is ours, so it may be rewritten.
    assert_success(&compensate(
        &path,
        &out,
        &["--report", report.to_str().unwrap()],
    ));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_path_files_exit_2_naming_line_and_column_without_output() {
    let dir = temp_dir("badpath");
    let out = dir.join("out.csv");
    let report = dir.join("report");
    let pose = "x_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg,fx_n,fy_n,fz_n";
    let cases = [
        (
            "missing.csv",
            "x_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg,fx_n,fy_n\n".to_string(),
            vec!["missing.csv", "line 1", "column fz_n"],
        ),
        (
            "nan.csv",
            format!("{pose}\n1300,-800,400,180,0,0,1,2,3\n1300,-800,NaN,180,0,0,1,2,3\n"),
            vec!["line 3", "column 3 (z_mm)", "NaN"],
        ),
        (
            "far.csv",
            format!("{pose}\n1300,-800,400,180,0,0,1,2,3\n9000,0,400,180,0,0,1,2,3\n"),
            vec!["line 3", "column x_mm..rz_deg", "not reached"],
        ),
    ];
    for (name, text, mentions) in cases {
        let path = write_file(&dir, name, &text);
        let o = compensate(
            path.to_str().unwrap(),
            &out,
            &["--report", report.to_str().unwrap()],
        );
        assert_usage_error(&o, &mentions);
        assert!(!out.exists(), "{name}: wrote {}", out.display());
        assert!(!report.exists(), "{name}: wrote the report");
    }
    // The output is never one of the inputs, and a foreign directory is not written into.
    let path = write_file(
        &dir,
        "ok.csv",
        &format!("{pose}\n1300,-800,400,180,0,0,1,2,3\n"),
    );
    let o = compensate(path.to_str().unwrap(), &path, &[]);
    assert_usage_error(&o, &["refusing"]);
    let foreign = dir.join("foreign");
    std::fs::create_dir_all(&foreign).unwrap();
    write_file(&foreign, "notes.txt", "mine");
    let o = compensate(
        path.to_str().unwrap(),
        &out,
        &["--report", foreign.to_str().unwrap()],
    );
    assert_usage_error(&o, &["not a previous report", "--report"]);
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_bad_free_tool_axis_option_is_named_alone_with_its_value() {
    let dir = temp_dir("freeaxis");
    let out = dir.join("out.csv");
    let path = example("milling/path.csv");
    for (text, option, value, other) in [
        ("tool-rotation=-90..90/0", "step", "0", "range"),
        ("tool-rotation=-90..90/91", "step", "91", "range"),
        ("tool-rotation=-1e108..1e108", "range", "1e108", "step"),
    ] {
        let o = compensate(&path, &out, &["--free", text]);
        let line = assert_usage_error(
            &o,
            &[&format!(
                "--free tool-rotation {option}: {value}: expected a number > 0"
            )],
        );
        assert!(!line.contains(&format!("tool-rotation {other}")), "{line}");
        assert!(!out.exists());
    }
    for (option, value, expected) in [
        ("--margin-deg", "91", "expected 0 to 90"),
        ("--max-condition", "0.5", "expected a finite number >= 1"),
    ] {
        let o = compensate(&path, &out, &["--free", "tool-rotation", option, value]);
        assert_usage_error(&o, &[&format!("{option}: {value}: {expected}")]);
        assert!(!out.exists());
    }
    // The surge objective needs the robot's masses (the example's robot gives none) and means
    // nothing without the free tool axis.
    let surge = ["--minimise", "surge"];
    let free = ["--free", "tool-rotation"];
    let o = compensate(&path, &out, &[&free[..], &surge].concat());
    assert_usage_error(
        &o,
        &["--minimise: surge: the surge needs the robot's masses"],
    );
    assert_usage_error(
        &compensate(&path, &out, &surge),
        &["--minimise: only with --free"],
    );
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `stiffid compensate --program` on the milling example's G-code pocket and process file.
fn program(setup: &str, stiffness: &str, out: &Path, extra: &[&str]) -> std::process::Output {
    let (nc, process) = (
        example("milling/pocket.nc"),
        example("milling/aluminium.toml"),
    );
    let mut args = vec![
        "compensate",
        "--setup",
        setup,
        "--stiffness",
        stiffness,
        "--program",
        &nc,
        "--process",
        &process,
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend(extra);
    stiffid(&args)
}

#[test]
fn a_gcode_pocket_becomes_a_compensated_fanuc_ls_program_with_its_report() {
    let dir = temp_dir("pocket");
    let (ls, csv, report) = (dir.join("POCKET.ls"), dir.join("p.csv"), dir.join("r"));
    let setup = example("milling/fanuc-milling.toml");
    let r = json(&program(
        &setup,
        &example("milling/stiffness.json"),
        &ls,
        &[
            "--csv",
            csv.to_str().unwrap(),
            "--json",
            "--report",
            report.to_str().unwrap(),
        ],
    ));
    // The LS program's targets are Cartesian, one per point but for the chord points of the
    // arcs written as circular motions (`C P[via] : P[end]`), in the configuration of the
    // compensated axis angles (J5 negative: no flip, elbow up, in front of axis 1).
    let text = std::fs::read_to_string(&ls).unwrap();
    let points = r["points"].as_array().unwrap();
    let positions = text.matches("GP1:").count();
    let circles = text.matches(":C P[").count();
    assert!(
        circles >= 1 && positions < points.len(),
        "{circles} {positions}"
    );
    assert_eq!(
        text.matches("CONFIG : 'N U T, 0, 0, 0',").count(),
        positions
    );
    // The G-code's comments of lines of their own (at most 32 characters) and its tool change
    // and spindle words, unmapped ([controller.io]), as remarks before the first move, its
    // spindle stop and end after the last.
    assert!(
        text.contains("  10:  ! pocket wall: 300 x 200 mm, corne ;\n  11:  ! operation: wall ;\n  12:  ! T1 M6 (line 5) ;\n  13:  ! S6000 M3 (line 6) ;\n"),
        "{text}"
    );
    assert!(
        text.contains(":  ! M5 (line 189) ;\n") && text.contains(":  ! M30 (line 190) ;\n/POS")
    );
    // Linear moves at the program's feed (F1800 mm/min, the plunges F300) where it cuts; the
    // first point and the rapid moves are joint motions, exact; the last point is exact.
    assert!(
        text.contains("  14:J P[1] 20% FINE ;\n  15:L P[2] 5mm/sec CNT100 ;\n"),
        "{text}"
    );
    let linear = text.lines().filter(|l| l.contains(":L P[")).count();
    let joint = text.lines().filter(|l| l.contains(":J P[")).count();
    let at_feed = text
        .lines()
        .filter(|l| l.contains(" 30mm/sec CNT100 ;"))
        .count();
    assert!(
        at_feed > 250 && joint == 2 && linear + 2 * circles + joint == positions,
        "{at_feed} {linear} {circles}"
    );
    // The program ends with the retract (G0), exact, then the end's remarks.
    let end = format!(":J P[{positions}] 20% FINE ;\n");
    let after = text.split_once(&end).map(|(_, a)| a).unwrap_or_default();
    let remark = after.lines().next().unwrap_or_default();
    assert!(remark.ends_with(":  ! M5 (line 189) ;"), "{text}");
    assert!(text.starts_with("/PROG  POCKET\n"));
    // The process force: about 240 N where the wall is cut, none on the rapid moves and plunges.
    let force = |p: &serde_json::Value| {
        ["fx_base_n", "fy_base_n", "fz_base_n"]
            .iter()
            .map(|k| p[*k].as_f64().unwrap().powi(2))
            .sum::<f64>()
            .sqrt()
    };
    let cutting = points.iter().filter(|p| force(p) > 100.0).count();
    assert!(cutting >= points.len() - 4, "{cutting} of {}", points.len());
    let segments = r["program"]["segments"].as_array().unwrap();
    assert_eq!(r["program"]["language"], "gcode");
    assert_eq!(r["program"]["output_language"], "ls");
    for s in segments {
        let before = s["deflection_before_mm"].as_f64().unwrap();
        assert!(s["deflection_after_mm"].as_f64().unwrap() < 1e-4 * before.max(1e-3));
    }
    assert!(r["warnings"][0]["message"]
        .as_str()
        .unwrap()
        .contains("plunge"));
    assert_eq!(
        std::fs::read_to_string(&csv).unwrap().lines().count(),
        points.len() + 1
    );
    for f in ["figures/force.svg", "figures/segments.svg", "report.html"] {
        assert!(report.join(f).is_file(), "{f}");
    }
    let html = std::fs::read_to_string(report.join("report.html")).unwrap();
    assert!(html.contains("Force and deflection per segment"));
    // What the report calls "after" is the error predicted to remain, 2 standard deviations of
    // the deflection, not the model's residual.
    assert!(html.contains("<th>remaining after, 2 sd of |d| mm</th>"));
    let table = &html[html.find("Force and deflection per segment").unwrap()..];
    let mut loaded = 0;
    for s in segments.iter().take(40) {
        let start = table.find(&format!("<tr><td>{}</td>", s["line"])).unwrap();
        let row = &table[start..start + table[start..].find("</tr>").unwrap()];
        let cells: Vec<&str> = row
            .split("<td>")
            .skip(1)
            .map(|c| c.trim_end_matches("</td>"))
            .collect();
        let shown: f64 = cells[5].parse().unwrap();
        let sd = s["deflection_std_mm"].as_f64().unwrap();
        assert!((shown - 2.0 * sd).abs() <= 1e-3 * 2.0 * sd, "{row}");
        loaded += usize::from(sd > 0.0);
    }
    assert!(loaded > 20, "{loaded} segments under a force");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_programs_exit_2_naming_the_line_or_the_field() {
    let dir = temp_dir("badprogram");
    let stiffness = example("milling/stiffness.json");
    let fanuc = example("milling/fanuc-milling.toml");
    // The built-in setup has no tool centre point: its measuring point is no tool.
    let o = program("fanuc-r2000ic-165f", &stiffness, &dir.join("o.nc"), &[]);
    assert_usage_error(&o, &["tool.tcp_mm", "fanuc-r2000ic-165f"]);
    // A setup without [workpiece]: a G-code program cannot be placed.
    let text = std::fs::read_to_string(&fanuc).unwrap();
    let placeless = write_file(
        &dir,
        "placeless.toml",
        &text[..text.find("[workpiece]").unwrap()],
    );
    let o = program(
        placeless.to_str().unwrap(),
        &stiffness,
        &dir.join("o.nc"),
        &[],
    );
    assert_usage_error(&o, &["workpiece.base_from_part", "setup file"]);
    // An output a program cannot become, and an unknown extension.
    let o = program(&fanuc, &stiffness, &dir.join("o.txt"), &[]);
    assert_usage_error(&o, &["--out", "o.txt", "expected a program ending in"]);
    let process = example("milling/aluminium.toml");
    let ls = write_file(
        &dir,
        "far.ls",
        "/PROG FAR\n/MN\n   1:J P[1] 10% FINE ;\n   2:J P[2] 10% FINE ;\n/POS\nP[1]{\n   GP1:\n\tUF : 0, UT : 1,\n\tJ1= -60 deg,\tJ2= -17 deg,\tJ3= -29 deg,\n\tJ4= 4 deg,\tJ5= -63 deg,\tJ6= 145 deg\n};\nP[2]{\n   GP1:\n\tUF : 0, UT : 1,\n\tJ1= -60 deg,\tJ2= 170 deg,\tJ3= -29 deg,\n\tJ4= 4 deg,\tJ5= -63 deg,\tJ6= 145 deg\n};\n/END\n",
    );
    let run = |program: &Path, out: &Path| {
        stiffid(&[
            "compensate",
            "--setup",
            &fanuc,
            "--stiffness",
            &stiffness,
            "--program",
            program.to_str().unwrap(),
            "--process",
            &process,
            "--out",
            out.to_str().unwrap(),
        ])
    };
    assert_usage_error(
        &run(&ls, &dir.join("o.nc")),
        &["far.ls", "written back in its own language"],
    );
    assert_usage_error(
        &run(&ls, &dir.join("o.ls")),
        &["far.ls", "line 4", "q2_deg"],
    );
    let nc = write_file(
        &dir,
        "bad.nc",
        "(stiffid: tool_rpy_deg = 180 0 0)\nG0 X0 Y0 Z5\nG1 X10 Q3\n",
    );
    assert_usage_error(&run(&nc, &dir.join("o.nc")), &["bad.nc", "line 3"]);
    for o in ["o.nc", "o.ls"] {
        assert!(!dir.join(o).exists(), "{o}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `text`, a program the command wrote for an infinitely stiff robot, as the milling example
/// ships it: without the bound comments (0 mm: nothing compensated) and its header saying its
/// targets are uncompensated (examples/milling/README.md).
fn uncompensated(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for line in text.split_inclusive('\n') {
        let body = line.trim_end_matches(['\n', '\r']);
        let kept = [" ; bound 0.0000 mm at 95%", " ! bound 0.0000 mm at 95%"]
            .iter()
            .find_map(|c| body.strip_suffix(c))
            .unwrap_or(body);
        out += &kept
            .replace(":\"0.0000 mm\"]", "]")
            .replace("compensated targets", "uncompensated targets");
        out += &line[body.len()..];
    }
    out
}

/// The milling example's programs (examples/milling/pocket.ls, pocket.src with pocket.dat,
/// pocket.mod) are
/// pocket.nc as the command writes it uncompensated (a robot of stiffness 1e10 N m/rad, the
/// bound comments left out): FANUC LS on the FANUC setup, KRL and RAPID on the KUKA KR 210 setup
/// (its spindle's mass in `$LOAD` and the `tooldata`).
#[test]
fn the_milling_examples_generated_programs_are_golden() {
    let dir = temp_dir("golden");
    let stiff = write_file(
        &dir,
        "stiff.json",
        r#"{"stiffness_nm_per_rad": [1e10, 1e10, 1e10, 1e10, 1e10, 1e10]}"#,
    );
    let cases = [
        ("fanuc-milling.toml", "pocket.ls"),
        ("kuka-milling.toml", "pocket.src"),
        ("kuka-milling.toml", "pocket.mod"),
    ];
    for (setup, golden) in cases {
        let out = dir.join(golden);
        let stiff = stiff.to_str().unwrap();
        let o = program(&example(&format!("milling/{setup}")), stiff, &out, &[]);
        assert!(
            o.status.success(),
            "{golden}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let written = uncompensated(&std::fs::read_to_string(&out).unwrap());
        let shipped = std::fs::read_to_string(example(&format!("milling/{golden}"))).unwrap();
        assert!(
            written == shipped,
            "examples/milling/{golden} is not what the command writes (regenerate it as examples/milling/README.md says)"
        );
        assert!(!shipped.contains("bound ") && !shipped.contains(" mm\"]"));
        if golden.ends_with(".src") {
            // The KRL program's points, in the .dat written beside it.
            let dat = std::fs::read_to_string(out.with_extension("dat")).unwrap();
            let shipped = std::fs::read_to_string(example("milling/pocket.dat")).unwrap();
            assert!(
                dat == shipped,
                "examples/milling/pocket.dat is not what the command writes"
            );
            assert!(dat.starts_with("&ACCESS RVP\n&REL 1\nDEFDAT POCKET\n"));
        }
        let first = written.lines().find(|l| l.contains("POCKET")).unwrap();
        assert!(
            ["/PROG  POCKET", "DEF POCKET( )", "MODULE POCKET"].contains(&first),
            "{first}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The controller rules the command enforces on a generated program, each refused with exit 2
/// before anything is written: a name that is a reserved word or too long, a KRL program in a
/// .dat, a feed beyond the robot's TCP speed; and a split program's sub-programs written beside it.
#[test]
fn generated_programs_keep_the_controller_rules() {
    let dir = temp_dir("rules");
    let (kuka, kuka_stiffness) = (
        example("milling/kuka-milling.toml"),
        example("milling/kuka-stiffness.json"),
    );
    let o = program(&kuka, &kuka_stiffness, &dir.join("end.src"), &[]);
    assert_usage_error(&o, &["\"END\"", "reserved word of KUKA KRL"]);
    let o = program(&kuka, &kuka_stiffness, &dir.join("pocket.dat"), &[]);
    assert_usage_error(&o, &["pocket.dat", ".src"]);
    let o = program(&kuka, &kuka_stiffness, &dir.join("proc.mod"), &[]);
    assert_usage_error(&o, &["\"PROC\"", "reserved word of ABB RAPID"]);
    let fanuc = example("milling/fanuc-milling.toml");
    let stiffness = example("milling/stiffness.json");
    let o = program(&fanuc, &stiffness, &dir.join("pocketwall.ls"), &[]);
    assert_usage_error(&o, &["\"POCKETWALL\"", "at most 8", "name_length"]);
    let o = program(
        &fanuc,
        &stiffness,
        &dir.join("p.ls"),
        &["--max-tcp-speed-mm-s", "20"],
    );
    assert_usage_error(&o, &["pocket.nc", "line 10", "largest TCP speed, 20 mm/s"]);
    let o = program(
        &fanuc,
        &stiffness,
        &dir.join("p.ls"),
        &["--moves-per-file", "10"],
    );
    assert_usage_error(&o, &["--moves-per-file", "10: expected 100 to 1000000"]);
    for f in ["end.src", "pocket.dat", "proc.mod", "pocketwall.ls", "p.ls"] {
        assert!(!dir.join(f).exists(), "{f}");
    }
    let o = program(
        &fanuc,
        &stiffness,
        &dir.join("wall.ls"),
        &["--moves-per-file", "100"],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let main = std::fs::read_to_string(dir.join("wall.ls")).unwrap();
    assert!(
        main.contains("CALL WALL_01 ;") && main.contains("CALL WALL_04 ;"),
        "{main}"
    );
    for k in 1..=4 {
        let sub = std::fs::read_to_string(dir.join(format!("WALL_0{k}.ls"))).unwrap();
        assert!(sub.starts_with(&format!("/PROG  WALL_0{k}\n")));
    }
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("4 sub-programs beside it, WALL_01 to WALL_04"),
        "{text}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The text's free tool rotation's gain and largest process force are the document's, which are the
/// means of its sums and the largest of its segments' forces.
#[test]
fn the_free_tool_axis_gain_and_the_largest_force_are_the_documents() {
    let dir = temp_dir("pocket-free");
    let (setup, stiffness) = (
        example("milling/fanuc-milling.toml"),
        example("milling/stiffness.json"),
    );
    let free = ["--free", "tool-rotation", "--minimise", "deflection"];
    let doc = json(&program(
        &setup,
        &stiffness,
        &dir.join("A.ls"),
        &[&free[..], &["--json"]].concat(),
    ));
    let out = program(&setup, &stiffness, &dir.join("B.ls"), &free);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let f = &doc["summary"]["free_tool_axis"];
    let points = doc["summary"]["points"].as_f64().unwrap();
    let number = |key: &str| f[key].as_f64().unwrap();
    let (before, after) = (
        number("mean_deflection_before_mm"),
        number("mean_deflection_after_mm"),
    );
    assert!((before - number("sum_deflection_before_mm") / points).abs() < 1e-12 * before);
    assert!((after - number("sum_deflection_after_mm") / points).abs() < 1e-12 * after);
    let change = number("mean_change_pct");
    assert!((change - 100.0 * (after / before - 1.0)).abs() < 1e-9);
    assert!(
        change < 0.0,
        "the rotations chosen lower the mean deflection: {change}"
    );
    let shown =
        format!("mean TCP deflection {before:.4} mm before, {after:.4} mm after ({change:+.1}%)");
    assert!(text.contains(&shown), "{shown} not in\n{text}");
    let feasible = &doc["feasibility"];
    assert!((feasible["margin_deg"].as_f64().unwrap() - 5.0).abs() < 1e-9);
    assert_eq!(feasible["collisions_checked"].as_bool(), Some(false));
    let shown = format!(
        "states removed {} (limit margin)",
        feasible["states_removed_limit_margin"].as_u64().unwrap()
    );
    assert!(text.contains(&shown), "{shown} not in\n{text}");
    let program = &doc["program"];
    let forces = program["segments"].as_array().unwrap().iter();
    let largest = forces
        .map(|s| s["force_n"].as_f64().unwrap())
        .fold(0.0, f64::max);
    assert_eq!(program["max_force_n"].as_f64().unwrap(), largest);
    assert!(largest > 0.0);
    assert!(
        text.contains(&format!(
            "force on the tool up to {largest:.1} N (the process's and the tool's weight)"
        )),
        "{text}"
    );
}

/// `--max-error-mm` certifies a program: above the largest bound the program is written with
/// every target's bound as a comment; below it the gate fails: the command exits 1 (not 2, bad
/// input) naming the worst points and what dominates them, and writes nothing.
#[test]
fn a_program_whose_bound_exceeds_the_largest_error_accepted_is_refused() {
    let dir = temp_dir("certified");
    let (setup, stiffness) = (
        example("milling/kuka-milling.toml"),
        example("milling/kuka-stiffness.json"),
    );
    let out = dir.join("pocket.src");
    let csv = dir.join("pocket.csv");
    let o = program(
        &setup,
        &stiffness,
        &out,
        &["--csv", csv.to_str().unwrap(), "--json"],
    );
    assert_success(&o);
    let doc = json(&o);
    let worst = doc["summary"]["budget"]["max_bound_mm"].as_f64().unwrap();
    let written = std::fs::read_to_string(&out).unwrap();
    let motions = written
        .lines()
        .filter(|l| l.starts_with("PTP ") || l.starts_with("LIN "))
        .count();
    let commented = written
        .lines()
        .filter(|l| l.contains(" ; bound ") && l.ends_with(" mm at 95%"))
        .count();
    assert_eq!(commented, motions);
    assert_eq!(motions, doc["points"].as_array().unwrap().len());
    std::fs::remove_file(&out).unwrap();
    std::fs::remove_file(&csv).unwrap();
    let limit = format!("{}", worst / 2.0);
    let o = program(
        &setup,
        &stiffness,
        &out,
        &["--csv", csv.to_str().unwrap(), "--max-error-mm", &limit],
    );
    let line = assert_failed_gate(
        &o,
        &["--max-error-mm", "the worst points: line ", "mostly "],
    );
    assert!(line.contains(&format!("largest {worst:.4} mm")), "{line}");
    let said = format!("meets {:.4} mm at 95%: no", worst / 2.0);
    assert!(line.contains(&said), "{line}");
    assert!(!out.exists() && !csv.exists());
    // The limit is said as given.
    let twice: f64 = format!("{:.4}", worst * 2.0).parse().unwrap();
    let o = program(
        &setup,
        &stiffness,
        &out,
        &["--max-error-mm", &twice.to_string()],
    );
    assert_success(&o);
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(
        text.contains(&format!("meets {twice} mm at 95%: yes")),
        "{text}"
    );
    assert!(
        text.contains("the error that remains at 95% is made of"),
        "{text}"
    );
    // At 99.7% the bound is wider, the gate and the document at that level.
    std::fs::remove_file(&out).unwrap();
    let o = program(
        &setup,
        &stiffness,
        &out,
        &[
            "--level",
            "0.997",
            "--max-error-mm",
            &format!("{}", worst * 2.0),
            "--json",
        ],
    );
    assert_success(&o);
    let doc = json(&o);
    let b = &doc["summary"]["budget"];
    assert_eq!(b["level"].as_f64(), Some(0.997));
    // The force part (the largest here) is a tolerance, the same at every level.
    assert!(b["max_bound_mm"].as_f64().unwrap() >= worst);
    assert_eq!(b["meets"]["meets"].as_bool(), Some(true));
    let force = (b["made_of"].as_array().unwrap().iter())
        .find(|p| p["part"] == "force")
        .unwrap();
    assert!(force["max_mm"].as_f64().unwrap() > 0.0);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// On the shipped FANUC pocket every free variable minimises the bound the document reports:
/// with the tool rotation free no point's `bound_mm` rises above its bound at the program's own
/// rotation, and the sum falls.
#[test]
fn a_free_tool_rotation_raises_no_points_bound_on_the_shipped_pocket() {
    let dir = temp_dir("pocket-no-rise");
    let (setup, stiffness) = (
        example("milling/fanuc-milling.toml"),
        example("milling/stiffness.json"),
    );
    let bounds = |name: &str, extra: &[&str]| -> Vec<f64> {
        let out = dir.join(name);
        let doc = json(&program(
            &setup,
            &stiffness,
            &out,
            &[extra, &["--json"]].concat(),
        ));
        (doc["points"].as_array().unwrap().iter())
            .map(|p| p["bound_mm"].as_f64().unwrap())
            .collect()
    };
    let own = bounds("OWN.ls", &[]);
    let free = bounds("FREE.ls", &["--free", "tool-rotation"]);
    assert_eq!((own.len(), free.len()), (372, 372));
    for (i, (a, b)) in own.iter().zip(&free).enumerate() {
        assert!(b <= &(a + 1e-6), "point {i}: {b} mm above {a} mm");
    }
    let sum = |v: &[f64]| v.iter().sum::<f64>();
    assert!(
        sum(&free) < sum(&own),
        "{} against {}",
        sum(&free),
        sum(&own)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The free rotation's dynamic programming is the exhaustive optimum of the bound the document
/// reports: on the first five points of the milling path and a grid of 9 rotations (5 deg
/// cells, at most 10 deg between points), every sequence of the map's cells (the reported bound
/// at every rotation) that keeps the step, the feasibility and no point above its own bound is
/// enumerated; the least sum is the sum of the points' `bound_mm` the job chose.
#[test]
fn the_free_rotation_is_the_exhaustive_optimum_of_the_reported_bound_on_a_small_grid() {
    let dir = temp_dir("free-exhaustive");
    let text = std::fs::read_to_string(example("milling/path.csv")).unwrap();
    let short: Vec<&str> = text.lines().take(6).collect();
    let path = dir.join("short.csv");
    std::fs::write(&path, short.join("\n") + "\n").unwrap();
    let (setup, stiffness) = (
        example("milling/fanuc-milling.toml"),
        example("milling/stiffness.json"),
    );
    let report = dir.join("r");
    let out = stiffid(&[
        "compensate",
        "--setup",
        &setup,
        "--stiffness",
        &stiffness,
        "--path",
        path.to_str().unwrap(),
        "--out",
        dir.join("out.csv").to_str().unwrap(),
        "--free",
        "tool-rotation=-20..20/10",
        "--report",
        report.to_str().unwrap(),
        "--map",
        "--json",
    ]);
    let doc = json(&out);
    let chosen: f64 = (doc["points"].as_array().unwrap().iter())
        .map(|p| p["bound_mm"].as_f64().unwrap())
        .sum();
    // map.csv: point, line, rotation, bound, deflection, condition, limit distance, ...
    let map = std::fs::read_to_string(report.join("map.csv")).unwrap();
    let mut cells = vec![Vec::new(); 5];
    for line in map.lines().skip(1) {
        let v: Vec<&str> = line.split(',').collect();
        let number = |k: usize| v[k].parse::<f64>().ok();
        let point = v[0].parse::<usize>().unwrap() - 1;
        cells[point].push((number(2).unwrap(), number(3), number(5), number(6)));
    }
    let angles: Vec<f64> = cells[0].iter().map(|c| c.0).collect();
    assert_eq!(angles.len(), 9);
    let own = angles.iter().position(|a| *a == 0.0).unwrap();
    // A point's allowed rotations: reached, no worse than its own, feasible (margin 5 deg,
    // condition 1000) unless its own.
    let allowed: Vec<Vec<Option<f64>>> = (cells.iter())
        .map(|row| {
            let own_bound = row[own].1.unwrap();
            (row.iter().enumerate())
                .map(|(k, &(_, b, condition, limit))| {
                    let b = b.filter(|b| *b <= own_bound)?;
                    let feasible =
                        condition.is_some_and(|c| c <= 1000.0) && limit.is_some_and(|l| l >= 5.0);
                    (k == own || feasible).then_some(b)
                })
                .collect()
        })
        .collect();
    let mut best = f64::INFINITY;
    for code in 0..9usize.pow(5) {
        let seq: Vec<usize> = (0..5).map(|i| code / 9usize.pow(i) % 9).collect();
        if seq
            .windows(2)
            .any(|w| (angles[w[0]] - angles[w[1]]).abs() > 10.0 + 1e-9)
        {
            continue;
        }
        let sum: Option<f64> = seq.iter().enumerate().map(|(i, &k)| allowed[i][k]).sum();
        best = sum.map_or(best, |s| best.min(s));
    }
    assert!(
        (chosen - best).abs() <= 1e-6 * best,
        "the job's sum {chosen} mm, the exhaustive optimum {best} mm"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A G-code program that states no units (neither `G20` nor `G21`) before its first motion is
/// read in mm with a warning of kind `units` naming that motion's line; stated, no warning.
#[test]
fn a_gcode_program_without_units_is_read_in_mm_with_a_warning() {
    let dir = temp_dir("no-units");
    let pocket = std::fs::read_to_string(example("milling/pocket.nc")).unwrap();
    let bare = pocket.replacen("G21 G90 G17", "G90 G17", 1);
    assert_ne!(bare, pocket);
    let units_warnings = |text: &str, name: &str| {
        let nc = dir.join(name);
        std::fs::write(&nc, text).unwrap();
        let out = dir.join(format!("out-{name}"));
        let (setup, stiffness, process) = (
            example("milling/fanuc-milling.toml"),
            example("milling/stiffness.json"),
            example("milling/aluminium.toml"),
        );
        let r = json(&stiffid(&[
            "compensate",
            "--setup",
            &setup,
            "--stiffness",
            &stiffness,
            "--program",
            nc.to_str().unwrap(),
            "--process",
            &process,
            "--out",
            out.to_str().unwrap(),
            "--json",
        ]));
        let warnings = r["warnings"].as_array().unwrap().clone();
        (
            r["points"].clone(),
            warnings
                .into_iter()
                .filter(|w| w["kind"] == "units")
                .collect::<Vec<_>>(),
        )
    };
    let (stated, none) = units_warnings(&pocket, "stated.nc");
    assert!(none.is_empty(), "{none:?}");
    let (bare_points, warned) = units_warnings(&bare, "bare.nc");
    assert_eq!(warned.len(), 1, "{warned:?}");
    let message = warned[0]["message"].as_str().unwrap();
    assert!(
        message.contains("line 7") && message.contains("G21"),
        "{message}"
    );
    assert_eq!(bare_points, stated, "read in mm either way");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `text` with `remark` inserted after the first `after`.
fn with_remark(text: &[u8], after: &[u8], remark: &[u8]) -> Vec<u8> {
    let at = text.windows(after.len()).position(|w| w == after).unwrap() + after.len();
    [&text[..at], remark, &text[at..]].concat()
}

/// `compensate --json` of the KRL pocket written as `src` and `dat` into `dir/name`, to
/// `out.src` there: the output and the folder.
fn run_pocket(dir: &Path, name: &str, (src, dat): (&[u8], &[u8])) -> (Output, PathBuf) {
    let sub = dir.join(name);
    std::fs::create_dir_all(&sub).unwrap();
    std::fs::write(sub.join("pocket.src"), src).unwrap();
    std::fs::write(sub.join("pocket.dat"), dat).unwrap();
    let output = stiffid(&[
        "compensate",
        "--setup",
        &example("milling/kuka-milling.toml"),
        "--stiffness",
        &example("milling/kuka-stiffness.json"),
        "--program",
        sub.join("pocket.src").to_str().unwrap(),
        "--process",
        &example("milling/aluminium.toml"),
        "--out",
        sub.join("out.src").to_str().unwrap(),
        "--json",
    ]);
    (output, sub)
}

/// The points of a compensate document, each `by` lines further down.
fn points_moved(r: &serde_json::Value, by: f64) -> Vec<serde_json::Value> {
    let mut points = r["points"].as_array().unwrap().clone();
    for p in &mut points {
        p["line"] = serde_json::json!(p["line"].as_f64().unwrap() + by);
    }
    points
}

/// The messages of a document's warnings of kind `encoding`.
fn encoding_warnings(r: &serde_json::Value) -> Vec<String> {
    let w = r["warnings"].as_array().unwrap();
    w.iter()
        .filter(|w| w["kind"] == "encoding")
        .map(|w| w["message"].as_str().unwrap().to_string())
        .collect()
}

/// "; Punkte für die Tasche" in ISO 8859-1, after the pocket's `DEFDAT`.
const LATIN_REMARK: &[u8] = b"; Punkte f\xfcr die Tasche\n";

/// A KRL program and its `.dat` with German remarks in Latin-1 (as a KUKA controller's backup
/// holds them): read byte for byte with a warning of kind `encoding`, compensated as the same
/// program in UTF-8, and written back in Latin-1, the remarks' bytes as read. A file with a
/// control byte is no text, in Latin-1 or UTF-8: refused naming the file, the byte and its line.
#[test]
fn a_latin1_program_is_compensated_and_written_back_in_latin1() {
    let dir = temp_dir("latin1");
    let src = std::fs::read(example("milling/pocket.src")).unwrap();
    let dat = std::fs::read(example("milling/pocket.dat")).unwrap();
    // "; Fräsen der Tasche" and "; Punkte für die Tasche" in ISO 8859-1.
    let latin_src = with_remark(&src, b"DEF POCKET( )\n", b"; Fr\xe4sen der Tasche\n");
    let latin_dat = with_remark(&dat, b"DEFDAT POCKET\n", LATIN_REMARK);
    let (plain, plain_dir) = run_pocket(&dir, "utf8", (&src, &dat));
    let (latin, latin_dir) = run_pocket(&dir, "latin1", (&latin_src, &latin_dat));
    let (plain, latin) = (json(&plain), json(&latin));
    // The same points, each a line further down (the remark).
    assert!(
        points_moved(&plain, 1.0) == points_moved(&latin, 0.0),
        "the points differ"
    );
    assert!(encoding_warnings(&plain).is_empty());
    let warned = encoding_warnings(&latin);
    assert_eq!(warned.len(), 1, "{warned:?}");
    assert!(warned[0].contains("pocket.src is not UTF-8 text: read as Latin-1"));
    // The files written: the UTF-8 run's with the remarks' Latin-1 bytes, no UTF-8 in them.
    for (file, after, bytes) in [
        (
            "out.src",
            &b"DEF out( )\n"[..],
            &b"; Fr\xe4sen der Tasche\n"[..],
        ),
        ("out.dat", &b"DEFDAT out\n"[..], LATIN_REMARK),
    ] {
        let written = std::fs::read(latin_dir.join(file)).unwrap();
        let expected = with_remark(&std::fs::read(plain_dir.join(file)).unwrap(), after, bytes);
        assert!(written == expected, "{file}");
    }
    // A control byte (an encrypted module, a binary file): no text, in Latin-1 or in UTF-8.
    for (name, src, dat) in [
        ("binary", &latin_src, &latin_dat),
        ("binary-utf8", &src, &dat),
    ] {
        let binary = with_remark(src, b"DEF POCKET( )\n", b"; Fr\x00");
        let (refused, bad_dir) = run_pocket(&dir, name, (&binary, dat));
        let message = assert_usage_error(&refused, &["pocket.src", "control byte 0x00", "line 6"]);
        assert!(message.contains("not text"), "{message}");
        assert!(!bad_dir.join("out.src").exists());
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A `.src` saved with a UTF-8 byte order mark (an editor's) beside the controller's Latin-1
/// `.dat` (both read as Latin-1): read as the same program, the warning naming the `.dat` (the
/// file that is not UTF-8), the mark written back as it was.
#[test]
fn a_src_with_a_byte_order_mark_beside_a_latin1_dat_keeps_it() {
    let dir = temp_dir("latin1-bom");
    let src = std::fs::read(example("milling/pocket.src")).unwrap();
    let dat = std::fs::read(example("milling/pocket.dat")).unwrap();
    let latin_dat = with_remark(&dat, b"DEFDAT POCKET\n", LATIN_REMARK);
    let (plain, plain_dir) = run_pocket(&dir, "utf8", (&src, &dat));
    let marked_src = [&b"\xef\xbb\xbf"[..], &src].concat();
    let (marked, marked_dir) = run_pocket(&dir, "marked", (&marked_src, &latin_dat));
    let (plain, marked) = (json(&plain), json(&marked));
    assert!(
        points_moved(&marked, 0.0) == points_moved(&plain, 0.0),
        "the points differ"
    );
    let warned = encoding_warnings(&marked);
    assert!(
        warned.len() == 1 && warned[0].contains("the .dat beside"),
        "{warned:?}"
    );
    let written = std::fs::read(marked_dir.join("out.src")).unwrap();
    let expected = std::fs::read(plain_dir.join("out.src")).unwrap();
    assert!(written == [&b"\xef\xbb\xbf"[..], &expected].concat());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `G53 G0 Z0.` retracts (Fusion 360's Haas posts) in a setup without a `G53` frame: no point,
/// the same path as without them, and one warning of kind `left-out` naming their lines.
#[test]
fn gcode_g53_rapids_without_the_setups_frame_make_no_point_with_a_warning() {
    let dir = temp_dir("g53-retract");
    let pocket = std::fs::read_to_string(example("milling/pocket.nc")).unwrap();
    let retracted = pocket
        .replacen("G21 G90 G17\n", "G21 G90 G17\nG53 G0 Z0.\n", 1)
        .replacen("M05\n", "G53 G0 Z0.\nM05\n", 1);
    let lines: Vec<usize> = (retracted.lines().enumerate())
        .filter(|(_, l)| l.starts_with("G53"))
        .map(|(i, _)| i + 1)
        .collect();
    assert_eq!(lines.len(), 2);
    let read = |text: &str, name: &str| {
        let nc = dir.join(name);
        std::fs::write(&nc, text).unwrap();
        let out = dir.join(format!("out-{name}"));
        let (setup, stiffness, process) = (
            example("milling/fanuc-milling.toml"),
            example("milling/stiffness.json"),
            example("milling/aluminium.toml"),
        );
        let r = json(&stiffid(&[
            "compensate",
            "--setup",
            &setup,
            "--stiffness",
            &stiffness,
            "--program",
            nc.to_str().unwrap(),
            "--process",
            &process,
            "--out",
            out.to_str().unwrap(),
            "--json",
        ]));
        let warnings = r["warnings"].as_array().unwrap().clone();
        let g53: Vec<_> = warnings
            .into_iter()
            .filter(|w| w["message"].as_str().unwrap().contains("G53"))
            .collect();
        (r["points"].clone(), g53)
    };
    let (plain, none) = read(&pocket, "plain.nc");
    assert!(none.is_empty(), "{none:?}");
    let (points, warned) = read(&retracted, "retracted.nc");
    assert_eq!(warned.len(), 1, "{warned:?}");
    assert_eq!(warned[0]["kind"], "left-out");
    let message = warned[0]["message"].as_str().unwrap();
    let named = format!("lines {}, {}", lines[0], lines[1]);
    assert!(
        message.starts_with("2 G53 rapids") && message.contains(&named),
        "{message}"
    );
    // The same points (one line later, after the first retract) at the same places.
    let places = |points: &serde_json::Value| -> Vec<(f64, [f64; 3])> {
        (points.as_array().unwrap().iter())
            .map(|p| {
                let at = |k: &str| p[k].as_f64().unwrap();
                (at("line"), [at("x_mm"), at("y_mm"), at("z_mm")])
            })
            .collect()
    };
    let (read, want) = (places(&points), places(&plain));
    assert_eq!(read.len(), want.len(), "the retracts make no point");
    for ((line, p), (l, q)) in read.iter().zip(&want) {
        assert_eq!(*line, l + 1.0);
        assert!((0..3).all(|k| (p[k] - q[k]).abs() <= 1e-6), "{p:?} {q:?}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
