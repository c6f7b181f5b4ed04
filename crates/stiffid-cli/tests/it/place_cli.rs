//! `stiffid place`: the setup written with the placement chosen and the document beside it, the
//! same for a seed, never over an input, its ranges refused naming the option.

use crate::common::{assert_success, assert_usage_error, json, stiffid, temp_dir};
use std::path::PathBuf;

fn example(name: &str) -> String {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/milling");
    root.join(name).display().to_string()
}

fn args<'a>(setup: &'a str, out: &'a str, rest: &[&'a str]) -> Vec<&'a str> {
    let mut v = vec!["place", "--setup", setup, "--out", out, "--json"];
    v.extend_from_slice(rest);
    v
}

#[test]
fn the_panel_is_placed_better_than_its_own_and_the_reach_only_placement() {
    let dir = temp_dir("place-panel");
    let out = dir.join("placed.toml").display().to_string();
    let (setup, stiffness) = (example("fanuc-milling.toml"), example("stiffness.json"));
    let (program, process) = (example("panel.nc"), example("drilling.toml"));
    let rest = [
        "--stiffness",
        &stiffness,
        "--program",
        &program,
        "--process",
        &process,
        "--region-mm",
        "500,2000,-1500,500",
    ];
    let d = json(&stiffid(&args(&setup, &out, &rest)));
    let gain = d["gain_vs_own_pct"].as_f64().unwrap();
    assert!(gain >= 25.0, "{d}");
    assert!(d["gain_vs_reach_only_pct"].as_f64().unwrap() > 0.0, "{d}");
    assert!(d["own"]["feasible"].as_bool().unwrap());
    // The setup written holds the placement the document names, and compensating the panel
    // there gives the peak bound the document states.
    let written = std::fs::read_to_string(&out).unwrap();
    let xyz = d["placed"]["xyz_mm"].as_array().unwrap();
    assert!(
        written.contains(&format!("xyz_mm = [{:.6}", xyz[0].as_f64().unwrap())),
        "{written}"
    );
    let csv = dir.join("panel.nc").display().to_string();
    let c = json(&stiffid(&[
        "compensate",
        "--setup",
        &out,
        "--stiffness",
        &stiffness,
        "--program",
        &program,
        "--process",
        &process,
        "--out",
        &csv,
        "--json",
    ]));
    let peak = c["summary"]["budget"]["max_bound_mm"].as_f64().unwrap();
    let placed = d["placed"]["peak_bound_mm"].as_f64().unwrap();
    assert!((peak - placed).abs() < 1e-6 * placed, "{peak} vs {placed}");
    // The same seed, the same placement; the written file is never an input.
    let again = dir.join("again.toml").display().to_string();
    let e = json(&stiffid(&args(&setup, &again, &rest)));
    assert_eq!(d["placed"], e["placed"]);
    assert_usage_error(&stiffid(&args(&setup, &setup, &rest)), &["--out"]);
    let mut bad = rest.to_vec();
    bad[7] = "2000,500,-1500,500";
    assert_usage_error(
        &stiffid(&args(&setup, &again, &bad)),
        &["--region-mm", "2000, 500"],
    );
    assert_success(&stiffid(&["place", "--help"]));
}

/// The example's path file with its poses in the part frame (its own placement at (1300, -700,
/// 400) mm, not turned), each row moved by `shift_mm`.
fn path_in_part_frame(shift_mm: [f64; 3]) -> String {
    let text = std::fs::read_to_string(example("path.csv")).unwrap();
    let mut lines = text.lines();
    let mut out = format!("{}\n", lines.next().unwrap());
    for line in lines {
        let mut fields: Vec<String> = line.split(',').map(String::from).collect();
        for (k, own) in [1300.0, -700.0, 400.0].iter().enumerate() {
            let v: f64 = fields[k].parse().unwrap();
            fields[k] = format!("{:.9}", v - own + shift_mm[k]);
        }
        out += &(fields.join(",") + "\n");
    }
    out
}

#[test]
fn a_path_file_is_placed_and_compensating_it_there_gives_the_bound_stated() {
    let dir = temp_dir("place-path");
    let part = dir.join("part.csv");
    std::fs::write(&part, path_in_part_frame([0.0; 3])).unwrap();
    let (part, out) = (
        part.display().to_string(),
        dir.join("placed.toml").display().to_string(),
    );
    let (setup, stiffness) = (example("fanuc-milling.toml"), example("stiffness.json"));
    let rest = [
        "--stiffness",
        &stiffness,
        "--path",
        &part,
        "--region-mm",
        "500,2000,-1500,500",
        "--rotation-deg",
        "0,0",
        "--grid",
        "3",
        "--samples",
        "8",
        "--starts",
        "1",
    ];
    // A process file with a path is refused: the path's rows carry their wrenches.
    let process = example("aluminium.toml");
    let with_process = [&rest[..], &["--process", &process]].concat();
    assert_usage_error(
        &stiffid(&args(&setup, &out, &with_process)),
        &["--process: only with --program"],
    );
    let d = json(&stiffid(&args(&setup, &out, &rest)));
    assert!(d["gain_vs_own_pct"].as_f64().unwrap() > 0.0, "{d}");
    // The rows carried to the placement, in the base frame as compensate reads them.
    let xyz: Vec<f64> = (d["placed"]["xyz_mm"].as_array().unwrap().iter())
        .map(|v| v.as_f64().unwrap())
        .collect();
    let base = dir.join("base.csv");
    std::fs::write(&base, path_in_part_frame([xyz[0], xyz[1], xyz[2]])).unwrap();
    let c = json(&stiffid(&[
        "compensate",
        "--setup",
        &setup,
        "--stiffness",
        &stiffness,
        "--path",
        &base.display().to_string(),
        "--out",
        &dir.join("compensated.csv").display().to_string(),
        "--json",
    ]));
    let peak = c["summary"]["budget"]["max_bound_mm"].as_f64().unwrap();
    let placed = d["placed"]["peak_bound_mm"].as_f64().unwrap();
    assert!((peak - placed).abs() < 1e-6 * placed, "{peak} vs {placed}");
    // With the part at its own placement, the path is the example's own: the own bound is
    // compensate's on the example's file.
    let own = json(&stiffid(&[
        "compensate",
        "--setup",
        &setup,
        "--stiffness",
        &stiffness,
        "--path",
        &example("path.csv"),
        "--out",
        &dir.join("own.csv").display().to_string(),
        "--json",
    ]));
    let own_peak = own["summary"]["budget"]["max_bound_mm"].as_f64().unwrap();
    let stated = d["own"]["peak_bound_mm"].as_f64().unwrap();
    assert!(
        (own_peak - stated).abs() < 1e-6 * stated,
        "{own_peak} vs {stated}"
    );
}

#[test]
fn robot_programs_and_built_in_setups_without_a_tool_are_refused_naming_why() {
    let dir = temp_dir("place-refused");
    let out = dir.join("placed.toml").display().to_string();
    let stiffness = example("stiffness.json");
    let (krl, process) = (example("pocket.src"), example("aluminium.toml"));
    let rest = [
        "--stiffness",
        &stiffness,
        "--program",
        &krl,
        "--process",
        &process,
        "--region-mm",
        "500,2000,-1500,500",
    ];
    let setup = example("fanuc-milling.toml");
    let refused = stiffid(&args(&setup, &out, &rest));
    assert_usage_error(
        &refused,
        // The example's KRL program states a tool without the setup's TCP: its Cartesian
        // targets are read, and refused for that tool, naming the file and the line.
        &[
            &format!("{krl}: line 17: the program's tool"),
            "is not the setup's",
        ],
    );
    // Before any placement is tried, and the error compensate gives for that program.
    let errors = |o: &std::process::Output| -> Vec<String> {
        (String::from_utf8_lossy(&o.stderr).lines())
            .filter(|l| l.starts_with("error"))
            .map(String::from)
            .collect()
    };
    let written = dir.join("pocket.src").display().to_string();
    let compensated = stiffid(&[
        "compensate",
        "--setup",
        &setup,
        "--stiffness",
        &stiffness,
        "--program",
        &krl,
        "--process",
        &process,
        "--out",
        &written,
    ]);
    assert_eq!(errors(&refused), errors(&compensated));
    assert!(!errors(&refused)[0].contains("--region-mm"));
    // A built-in setup is read (not "no such file") and refused for what it lacks.
    let mut gcode = rest.to_vec();
    let pocket = example("pocket.nc");
    gcode[3] = &pocket;
    assert_usage_error(
        &stiffid(&args("fanuc-r2000ic-165f", &out, &gcode)),
        &["tool.tcp_mm", "missing in setup fanuc-r2000ic-165f"],
    );
    // A path file on a cell with external axes: refused for the cell, before its e columns are
    // read (not "the cell has no external axes").
    let track = format!("{}/../../examples/track", env!("CARGO_MANIFEST_DIR"));
    let (cell, table) = (
        format!("{track}/track-cell.toml"),
        format!("{track}/table.csv"),
    );
    let kuka = example("kuka-stiffness.json");
    let path = [
        "--stiffness",
        &kuka,
        "--path",
        &table,
        "--region-mm",
        "500,2000,-1500,500",
    ];
    assert_usage_error(
        &stiffid(&args(&cell, &out, &path)),
        &[
            "--path",
            "has external axes",
            "a path file is placed on a robot without them",
        ],
    );
    assert!(!std::path::Path::new(&out).exists());
}

#[test]
fn the_height_and_tilt_are_free_in_the_grammar_of_compensate_and_the_old_spelling_says_the_new() {
    let dir = temp_dir("place-free");
    let part = dir.join("part.csv");
    std::fs::write(&part, path_in_part_frame([0.0; 3])).unwrap();
    let (part, out) = (
        part.display().to_string(),
        dir.join("placed.toml").display().to_string(),
    );
    let (setup, stiffness) = (example("fanuc-milling.toml"), example("stiffness.json"));
    let rest = [
        "--stiffness",
        &stiffness,
        "--path",
        &part,
        "--region-mm",
        "500,2000,-1500,500",
        "--rotation-deg",
        "0,0",
        "--grid",
        "3",
        "--samples",
        "8",
        "--starts",
        "1",
    ];
    // The height within -30..60 mm of its own (400 mm), the tilt within +-4 deg.
    let free = ["--free", "z=-30..60", "--free", "tilt=-4..4"];
    let d = json(&stiffid(&args(&setup, &out, &[&rest[..], &free].concat())));
    let z = d["placed"]["xyz_mm"][2].as_f64().unwrap();
    assert!((370.0 - 1e-9..=460.0 + 1e-9).contains(&z), "{d}");
    let rpy: Vec<f64> = (d["placed"]["rpy_deg"].as_array().unwrap().iter())
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert!(
        rpy[0].abs() <= 4.0 + 1e-6 && rpy[1].abs() <= 4.0 + 1e-6,
        "{d}"
    );
    // The height alone: no tilt, whatever the search finds.
    let d = json(&stiffid(&args(
        &setup,
        &out,
        &[&rest[..], &["--free", "z"]].concat(),
    )));
    let rpy = &d["placed"]["rpy_deg"];
    assert!(rpy[0].as_f64().unwrap().abs() < 1e-9 && rpy[1].as_f64().unwrap().abs() < 1e-9);
    let z = d["placed"]["xyz_mm"][2].as_f64().unwrap();
    assert!((300.0 - 1e-9..=500.0 + 1e-9).contains(&z), "{d}");
    // Bad texts are refused naming --free and the text; the old spelling names the new.
    for (given, said) in [
        (
            &["--free", "x=-5..5"][..],
            &["--free", "x=-5..5", "expected z"][..],
        ),
        (
            &["--free", "tilt=-2..5"],
            &["--free", "tilt=-2..5", "-T..T"],
        ),
        (&["--free", "tilt=-50..50"], &["--free", "0 < T <= 45"]),
        (&["--free", "z=/10"], &["--free", "z=/10", "no step"]),
        (
            &["--free", "z", "--free", "z=-5..5"],
            &["--free", "given twice"],
        ),
        (
            &["--free"],
            &["--free: expected a variable", "--free z", "--free tilt"],
        ),
        (&["--z-mm", "0,10"], &["--z-mm: removed", "--free z=LO..HI"]),
        (
            &["--tilt-deg", "5"],
            &["--tilt-deg: removed", "--free tilt=-T..T"],
        ),
    ] {
        let refused = stiffid(&args(&setup, &out, &[&rest[..], given].concat()));
        assert_usage_error(&refused, said);
    }
}
