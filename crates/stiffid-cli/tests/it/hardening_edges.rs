//! The outputs a command writes are the ones it names, the options it takes mean something in
//! the mode given, and every documented range holds at its edges: each refusal exit 2, one
//! `error: ` line naming the option, file or field, and nothing written.

use crate::common::{assert_success, example, refused, stiffid, temp_dir, write_file};

/// `compensate` of the example pocket (G-code) into `out` with `extra` options.
fn pocket(out: &str, extra: &[&str]) -> Vec<String> {
    let mut args: Vec<String> = [
        "compensate",
        "--setup",
        &example("milling/fanuc-milling.toml"),
        "--stiffness",
        &example("milling/stiffness.json"),
        "--program",
        &example("milling/pocket.nc"),
        "--process",
        &example("milling/aluminium.toml"),
        "--out",
        out,
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    args.extend(extra.iter().map(|s| s.to_string()));
    args
}

fn refs(args: &[String]) -> Vec<&str> {
    args.iter().map(String::as_str).collect()
}

/// A split program's sub-programs go beside it: a file there named as one of them that an
/// earlier run of the same program did not write is refused before anything is computed, and
/// an earlier run's are replaced.
#[test]
fn a_split_program_never_replaces_a_file_it_did_not_write() {
    let dir = temp_dir("edges-split");
    write_file(
        &dir,
        "WALL_01.ls",
        "/PROG  WALL_01\n! the user's own program\n",
    );
    let args = pocket("{dir}/wall.ls", &["--moves-per-file", "100"]);
    let line = refused(&dir, &refs(&args), &["--out", "WALL_01.ls", "sub-programs"]);
    assert!(
        line.contains("move it away or choose another --out"),
        "{line}"
    );
    std::fs::remove_file(dir.join("WALL_01.ls")).unwrap();
    let d = dir.to_str().unwrap();
    let args: Vec<String> = args.iter().map(|a| a.replace("{dir}", d)).collect();
    for run in 0..2 {
        assert_success(&stiffid(&refs(&args)));
        let sub = std::fs::read_to_string(dir.join("WALL_01.ls")).unwrap();
        assert!(sub.starts_with("/PROG  WALL_01\n"), "run {run}: {sub}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The settings of a robot program generated from G-code (targets, name length, moves per file,
/// the largest TCP speed) are refused where none is generated: written back as G-code, or a
/// robot program read back.
#[test]
fn program_settings_without_a_generated_program_are_refused() {
    let dir = temp_dir("edges-settings");
    let gcode_out = [
        (["--targets", "joint"], "--targets"),
        (["--name-length", "12"], "--name-length"),
        (["--moves-per-file", "100"], "--moves-per-file"),
        (["--max-tcp-speed-mm-s", "100"], "--max-tcp-speed-mm-s"),
    ];
    for (extra, flag) in gcode_out {
        let args = pocket("{dir}/out.nc", &extra);
        refused(
            &dir,
            &refs(&args),
            &[flag, "only for a G-code program written as a robot program"],
        );
    }
    let ls = example("milling/pocket.ls");
    for (extra, flag) in [
        (["--targets", "joint"], "--targets"),
        (["--moves-per-file", "100"], "--moves-per-file"),
        (["--max-tcp-speed-mm-s", "100"], "--max-tcp-speed-mm-s"),
    ] {
        let mut args = pocket("{dir}/back.ls", &extra);
        args[6] = ls.clone();
        let line = refused(
            &dir,
            &refs(&args),
            &[flag, "written back with its own targets"],
        );
        assert!(line.starts_with(&format!("error: {flag}: ")), "{line}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--frame` names the frame of a path CSV's wrenches: with a program (whose wrench is its
/// process file's) a frame other than the default is refused by `compensate` and `place`
/// alike, where it was ignored; the default passes.
#[test]
fn a_wrench_frame_with_a_program_is_refused() {
    let dir = temp_dir("edges-frame");
    let expected = ["--frame", "only with --path", "process file's"];
    let compensate = pocket("{dir}/out.nc", &["--frame", "tool"]);
    let line = refused(&dir, &refs(&compensate), &expected);
    assert!(line.starts_with("error: --frame: "), "{line}");
    let place = [
        "place",
        "--setup",
        &example("milling/fanuc-milling.toml"),
        "--stiffness",
        &example("milling/stiffness.json"),
        "--program",
        &example("milling/pocket.nc"),
        "--process",
        &example("milling/aluminium.toml"),
        "--region-mm",
        "500,2000,-1500,500",
        "--out",
        "{dir}/placed.toml",
        "--frame",
        "tool",
    ];
    let line = refused(&dir, &place, &expected);
    assert!(line.starts_with("error: --frame: "), "{line}");
    let d = dir.to_str().unwrap();
    let by_default = pocket(&format!("{d}/out.nc"), &["--frame", "base"]);
    assert_success(&stiffid(&refs(&by_default)));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The limits a user gives `compensate` are said as given, in a number a person can read: 1e308
/// is `1e308`, not 309 digits.
#[test]
fn the_limits_given_are_printed_as_given() {
    let dir = temp_dir("edges-limits");
    let d = dir.to_str().unwrap();
    let out = format!("{d}/out.ls");
    let limits = [
        "--free",
        "tool-rotation=-10..10/10",
        "--max-condition",
        "1e308",
        "--max-error-mm",
        "1e308",
    ];
    let o = stiffid(&refs(&pocket(&out, &limits)));
    assert_success(&o);
    let text = String::from_utf8(o.stdout).unwrap();
    for said in [
        "condition number at most 1e308,",
        "meets 1e308 mm at 95%: yes",
    ] {
        assert!(text.contains(said), "{said}: {text}");
    }
    assert!(!text.contains("00000000"), "{text}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `select --margin-mm` is a distance of 0 to 1000 mm: a negative, infinite or NaN one is
/// refused naming the option, the edges themselves taken.
#[test]
fn the_select_margin_is_refused_outside_its_range() {
    let dir = temp_dir("edges-margin");
    let setup = example("cell/zhang2021-tracker.toml");
    let args = |margin: &str| {
        let margin = format!("--margin-mm={margin}");
        [
            "select",
            "--setup",
            &setup,
            "--start-random",
            "--max-evals",
            "5",
            "--out",
            "{dir}/g.csv",
            &margin,
        ]
        .iter()
        .map(|s| s.to_string())
        .collect::<Vec<_>>()
    };
    for bad in ["-1", "nan", "inf", "1000.001"] {
        let line = refused(
            &dir,
            &refs(&args(bad)),
            &["--margin-mm", "outside [0, 1000] mm"],
        );
        assert!(line.starts_with("error: --margin-mm: "), "{line}");
    }
    let d = dir.to_str().unwrap();
    for edge in ["0", "1000"] {
        let args: Vec<String> = args(edge).iter().map(|a| a.replace("{dir}", d)).collect();
        let out = stiffid(&refs(&args));
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!stderr.contains("error: --margin-mm"), "{edge}: {stderr}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `kinematics --setup` takes the setup's characteristic length (1200 mm for the paper's setup),
/// as the given one; `--characteristic-length-mm` still overrides it.
#[test]
fn kinematics_takes_the_setups_characteristic_length() {
    let args = [
        "kinematics",
        "--setup",
        "zhang2021-comau-nj165",
        "--q-deg",
        "10,20,-90,30,20,10",
        "--json",
    ];
    let doc = crate::common::json(&stiffid(&args));
    let length = doc["characteristic_length_mm"].as_f64().unwrap();
    assert!((length - 1200.0).abs() < 1e-9, "{length}");
    assert_eq!(doc["characteristic_length_source"], "given");
    let given = [&args[..], &["--characteristic-length-mm", "900"]].concat();
    let doc = crate::common::json(&stiffid(&given));
    let length = doc["characteristic_length_mm"].as_f64().unwrap();
    assert!((length - 900.0).abs() < 1e-9, "{length}");
}

/// A calibration campaign over the track's stations deals its postures over them: a station
/// with too few says so as the station's share of the postures asked for, not as the group.
#[test]
fn a_campaigns_station_with_too_few_postures_says_it_per_station() {
    let dir = temp_dir("edges-campaign");
    let setup = example("track/track-cell.toml");
    let args = [
        "select",
        "--setup",
        &setup,
        "--for",
        "calibration",
        "--start-random",
        "--count",
        "6",
        "--station",
        "500,0,0",
        "--station",
        "3000,0,0",
        "--station",
        "5500,0,0",
        "--out",
        "{dir}/campaign.csv",
    ];
    let line = refused(&dir, &args, &["station 1: 2 postures per station"]);
    assert!(
        line.contains("the campaign deals its 6 postures over its stations"),
        "{line}"
    );
    assert!(!line.contains("2 given"), "{line}");
    std::fs::remove_dir_all(&dir).unwrap();
}
