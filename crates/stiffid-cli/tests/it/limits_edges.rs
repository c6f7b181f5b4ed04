//! The documented limits at their edges, options that keep their meaning in every mode, outputs
//! that are never left behind: one test per cause, each over several variants.

use crate::common;

use common::{assert_success, identify_fanuc, json, refused, stiffid, temp_dir, write_file, GROUP};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const CELL: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../examples/cell/zhang2021-tracker.toml"
);
const MILLING: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/milling");

/// The example cell's TOML with `from` replaced by `to` (which must occur), written as `name`.
fn cell_with(dir: &Path, name: &str, from: &str, to: &str) -> PathBuf {
    let text = std::fs::read_to_string(CELL).unwrap();
    assert!(text.contains(from), "{from}");
    write_file(dir, name, &text.replacen(from, to, 1))
}

/// `sh -c script` with `$0` the stiffid binary.
fn shell(script: &str) -> Output {
    Command::new("sh")
        .args(["-c", script, env!("CARGO_BIN_EXE_stiffid")])
        .output()
        .unwrap()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn bodies_as_large_as_the_robot_never_panic() {
    let dir = temp_dir("edge-radii");
    write_file(&dir, "g.csv", GROUP);
    for radius in ["10000", "5000", "2500"] {
        let radii = format!("[robot_geometry]\nlink_radius_mm = [{radius}, {radius}, {radius}, {radius}, {radius}, {radius}, {radius}]\n\n[cell]");
        let setup = cell_with(&dir, "big.toml", "[cell]", &radii);
        let s = setup.to_str().unwrap();
        let g = dir.join("g.csv");
        let out = stiffid(&["evaluate", "--setup", s, "--postures", g.to_str().unwrap()]);
        assert_success(&out);
        for method in [&["--start-random"][..], &["--global", "--starts", "2"]] {
            let args = [
                &[
                    "select",
                    "--setup",
                    s,
                    "--max-evals",
                    "50",
                    "--out",
                    "{dir}/o.csv",
                ][..],
                method,
            ]
            .concat();
            let line = refused(&dir, &args, &["no feasible group"]);
            assert!(!line.contains("panicked"), "{line}");
        }
    }
}

#[test]
fn a_tiny_tool_axis_step_is_refused_naming_the_option() {
    let dir = temp_dir("edge-step");
    for step in ["1e-300", "1e-9", "1e-4"] {
        refused(
            &dir,
            &[
                "compensate",
                "--setup",
                &format!("{MILLING}/fanuc-milling.toml"),
                "--stiffness",
                &format!("{MILLING}/stiffness.json"),
                "--path",
                &format!("{MILLING}/path.csv"),
                "--out",
                "{dir}/o.csv",
                "--free",
                &format!("tool-rotation=-90..90/{step}"),
            ],
            &["--free tool-rotation step", "cells", "at most"],
        );
    }
}

#[test]
fn cell_positions_and_array_lengths_are_range_checked() {
    let dir = temp_dir("edge-cell");
    let cases = [
        ("floor_z_mm = 0.0", "floor_z_mm = 1e308", "cell.floor_z_mm"),
        ("floor_z_mm = 0.0", "floor_z_mm = -2e5", "cell.floor_z_mm"),
        ("position_mm = [3000.0, -2000.0, 1500.0]", "position_mm = [1e308, -2000.0, 1500.0]", "tracker.position_mm"),
        ("position_mm = [3000.0, -2000.0, 1500.0]", "position_mm = [3000.0, -2000.0, 1500.0, 4.0]", "invalid length 4"),
        ("position_mm = [3000.0, -2000.0, 1500.0]", "base_from_tracker = { xyz_mm = [3000.0, -2000.0, 1500.0], rpy_deg = [0, 0, 1e308] }", "rpy_deg"),
        ("anchor_mm = [2000.0, 1500.0, 0.0]", "anchor_mm = [2000.0, 1500.0, 0.0, 7.0]", "invalid length 4"),
        ("[cell]", "[robot_geometry]\nlink_radius_mm = [350, 260, 195, 175, 130, 110, 90, 80]\n\n[cell]", "invalid length 8"),
        ("clearance_mm = 50.0", "clearance_mm = 50.0\n[[cell.obstacle]]\nname = \"t\"\nmin_mm = [-1e308, 0, 0]\nmax_mm = [1, 1, 1]", "min_mm"),
    ];
    write_file(&dir, "g.csv", GROUP);
    for (from, to, named) in cases {
        let setup = cell_with(&dir, "c.toml", from, to);
        let (s, g) = (setup.to_str().unwrap(), dir.join("g.csv"));
        refused(
            &dir,
            &["evaluate", "--setup", s, "--postures", g.to_str().unwrap()],
            &[named],
        );
    }
}

#[test]
fn every_fold_is_fitted_as_the_full_fit() {
    for (method, folds) in [
        (&["--nonnegative"][..], "5"),
        (&["--robust", "tukey"], "5"),
        (&["--robust", "huber"], "3"),
    ] {
        let doc = json(&identify_fanuc(&[method, &["--folds", folds]].concat()));
        let plain = json(&identify_fanuc(&["--folds", folds]));
        let cv = &doc["cross_validation"];
        let folds_k: Vec<Vec<f64>> = cv["per_fold"]
            .as_array()
            .unwrap()
            .iter()
            .map(|f| {
                f["stiffness_nm_per_rad"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|k| k.as_f64().unwrap_or(f64::INFINITY))
                    .collect()
            })
            .collect();
        if method[0] == "--nonnegative" {
            assert!(folds_k.iter().flatten().all(|k| *k > 0.0), "{folds_k:?}");
        }
        // The folds differ from the least-squares folds: the option reached them.
        assert_ne!(
            cv["per_fold"], plain["cross_validation"]["per_fold"],
            "{method:?}"
        );
    }
}

#[test]
fn thread_counts_beyond_the_limit_are_refused_naming_the_setting() {
    for bad in ["5000", "257", "many", "-1"] {
        let out = Command::new(env!("CARGO_BIN_EXE_stiffid"))
            .arg("robots")
            .env("RAYON_NUM_THREADS", bad)
            .output()
            .unwrap();
        let line =
            common::assert_usage_error(&out, &["RAYON_NUM_THREADS", "0 (one per core) to 256"]);
        assert!(line.contains(bad), "{line}");
    }
    let out = Command::new(env!("CARGO_BIN_EXE_stiffid"))
        .arg("robots")
        .env("RAYON_NUM_THREADS", "3")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
}

#[test]
fn stdout_that_cannot_be_written_is_an_error_and_leaves_no_file() {
    let dir = temp_dir("edge-stdout");
    let closed = shell("\"$0\" robots >&-");
    assert_eq!(closed.status.code(), Some(2), "{}", stderr(&closed));
    assert!(stderr(&closed).contains("stdout is closed"));
    // Open read-write on /dev/null (Python's subprocess.DEVNULL, a daemon's stdout) is open.
    let devnull = shell("\"$0\" robots 1<>/dev/null");
    assert_eq!(devnull.status.code(), Some(0), "{}", stderr(&devnull));
    let out = dir.join("k.json");
    let data = common::fanuc_csv();
    let script = format!(
        "\"$0\" identify --setup fanuc-r2000ic-165f --data {} --out {} --json > /dev/full",
        data.display(),
        out.display()
    );
    let full = shell(&script);
    assert_eq!(full.status.code(), Some(2), "{}", stderr(&full));
    assert!(!out.exists(), "--out left behind after stdout failed");
    let script = format!(
        "\"$0\" plot --setup zhang2021-comau-nj165 --postures {} --out {} > /dev/full",
        write_file(&dir, "g.csv", GROUP).display(),
        dir.join("figs").display()
    );
    assert_eq!(shell(&script).status.code(), Some(2));
    assert!(!dir.join("figs").exists(), "plot left its directory behind");
}

/// A disk that fills during a run, as a file-size limit (`ulimit -f`, with `SIGXFSZ` ignored so
/// that a write beyond it fails with `EFBIG` as on a full disk): the small CSV fits, the report or
/// the figure does not; the run fails and leaves none of its files.
#[test]
fn a_disk_that_fills_during_the_run_leaves_no_file() {
    let dir = temp_dir("edge-full-disk");
    let (out, report) = (dir.join("x.csv"), dir.join("rep"));
    let search = "select --setup zhang2021-comau-nj165 --criterion classical";
    for (args, fails) in [
        (
            format!(
                "--start-random --max-evals 20 --report {}",
                report.display()
            ),
            "plan.html",
        ),
        (
            "--global --starts 2 --max-evals 200 --target-pct 10".to_string(),
            "x.target.png",
        ),
    ] {
        let script = format!(
            "trap '' XFSZ; ulimit -f 40; \"$0\" {search} {args} --out {}",
            out.display()
        );
        let run = shell(&script);
        assert_eq!(run.status.code(), Some(2), "{}", stderr(&run));
        assert!(
            stderr(&run).contains(fails) && stderr(&run).contains("File too large"),
            "{}",
            stderr(&run)
        );
        let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
        assert!(left.is_empty(), "{args}: left behind {left:?}");
    }
}

#[test]
fn one_path_for_two_outputs_is_refused_before_computing() {
    let dir = temp_dir("edge-same");
    for (out, report) in [("{dir}/x", "{dir}/x"), ("{dir}/r/summary.json", "{dir}/r")] {
        if out.contains("/r/") {
            std::fs::create_dir_all(dir.join("r")).unwrap();
        }
        refused(
            &dir,
            &[
                "compensate",
                "--setup",
                "zhang2021-comau-nj165",
                "--stiffness",
                &format!("{MILLING}/stiffness.json"),
                "--path",
                &format!("{MILLING}/path.csv"),
                "--out",
                out,
                "--report",
                report,
            ],
            &["--report", "same place as --out"],
        );
        let _ = std::fs::remove_dir_all(dir.join("r"));
    }
}

#[test]
fn an_earlier_larger_group_leaves_no_stale_figures() {
    let dir = temp_dir("edge-stale");
    let six = write_file(&dir, "six.csv", GROUP);
    let three: String = GROUP.lines().take(4).map(|l| format!("{l}\n")).collect();
    let three = write_file(&dir, "three.csv", &three);
    let figs = dir.join("figs");
    for postures in [&six, &three] {
        assert_success(&stiffid(&[
            "plot",
            "--setup",
            "zhang2021-comau-nj165",
            "--postures",
            postures.to_str().unwrap(),
            "--out",
            figs.to_str().unwrap(),
        ]));
    }
    let names: Vec<String> = std::fs::read_dir(&figs)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(names.iter().any(|n| n.contains("03")), "{names:?}");
    assert!(
        !names.iter().any(|n| n.contains("04") || n.contains("06")),
        "{names:?}"
    );
}

#[test]
fn concurrent_setups_new_to_one_file_leave_exactly_one_winner() {
    let dir = temp_dir("edge-race");
    let target = dir.join("cell.toml");
    for _ in 0..3 {
        let _ = std::fs::remove_file(&target);
        let children: Vec<_> = (0..4)
            .map(|_| {
                Command::new(env!("CARGO_BIN_EXE_stiffid"))
                    .args(["setups", "new", "--robot", "fanuc-r2000ic-165f", "--out"])
                    .arg(&target)
                    .output()
            })
            .collect();
        let wins = children
            .into_iter()
            .filter(|c| c.as_ref().unwrap().status.success())
            .count();
        assert!(wins >= 1 && target.exists());
        assert_eq!(
            wins,
            1,
            "several runs claimed to have created {}",
            target.display()
        );
    }
}

#[test]
fn usage_errors_are_whole_and_negative_values_reach_their_option() {
    let out = stiffid(&[
        "select",
        "--setup",
        "zhang2021-comau-nj165",
        "--target-pct",
        "1",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let text = stderr(&out);
    assert!(
        text.starts_with("error: ") && text.contains("--out"),
        "{text}"
    );
    for value in ["-inf", "-1", "-0.5"] {
        let out = stiffid(&[
            "select",
            "--setup",
            "zhang2021-comau-nj165",
            "--target-pct",
            value,
            "--out",
            "x.csv",
        ]);
        assert_eq!(out.status.code(), Some(2));
        let text = stderr(&out);
        assert!(text.contains("target"), "{value}: {text}");
        assert!(!text.contains("unexpected argument"), "{value}: {text}");
    }
    let dir = temp_dir("edge-q0");
    refused(
        &dir,
        &[
            "compensate",
            "--setup",
            "zhang2021-comau-nj165",
            "--stiffness",
            &format!("{MILLING}/stiffness.json"),
            "--path",
            &format!("{MILLING}/path.csv"),
            "--out",
            "{dir}/o.csv",
            "--q0-deg=nan,0,-90,0,0,0",
        ],
        &["--q0-deg[1]"],
    );
}

#[test]
fn a_null_stiffness_is_named_with_what_to_do() {
    let dir = temp_dir("edge-null");
    let k = write_file(
        &dir,
        "k.json",
        r#"{"stiffness_nm_per_rad": [9.5e5, 3e6, null, 2.5e5, 2e5, 1.5e5]}"#,
    );
    refused(
        &dir,
        &[
            "predict",
            "--setup",
            "zhang2021-comau-nj165",
            "--stiffness",
            k.to_str().unwrap(),
            "--q-deg",
            "0,0,-90,0,0,0",
            "--wrench",
            "0,0,-500,0,0,0",
        ],
        &["stiffness_nm_per_rad[3] is null", "finite stiffness"],
    );
}

#[test]
fn test_pose_without_test_postures_is_not_computed() {
    let dir = temp_dir("edge-testpose");
    let text = std::fs::read_to_string(CELL).unwrap();
    let start = text.find("[test]").unwrap();
    let end = start + text[start..].find("\n]\n").unwrap() + 3;
    let setup = write_file(
        &dir,
        "c.toml",
        &format!("{}{}", &text[..start], &text[end..]),
    );
    let g = write_file(&dir, "g.csv", GROUP);
    let args = [
        "evaluate",
        "--setup",
        setup.to_str().unwrap(),
        "--postures",
        g.to_str().unwrap(),
    ];
    let doc = json(&stiffid(&[&args[..], &["--json"]].concat()));
    assert!(doc["test_pose_mm"].is_null(), "{}", doc["test_pose_mm"]);
    let text = String::from_utf8(stiffid(&args).stdout).unwrap();
    assert!(text.contains("test-pose    not computed"), "{text}");
}

/// The joint error maps' choice has a bound on its work (readings x map coefficients^2): fixed
/// maps beyond it are refused naming `--maps` before they are chosen, `--maps auto` beyond it
/// fits no map and says why; within it the maps are chosen.
#[test]
fn joint_error_maps_beyond_their_work_bound_are_refused_or_skipped() {
    use crate::calibrate_cli::{model, postures, readings, truth, SETUP};
    let d = temp_dir("maps-work");
    let model = model();
    let x = truth(&model);
    let tracker = crate::calibrate_cli::tracker();
    // 250 postures of 4 points: 1000 readings x 768^2 coefficients = 5.9e8 > 5e8.
    let data = write_file(
        &d,
        "fit.csv",
        &readings(&model, &x, &tracker, &postures(250, 3)),
    );
    let data = data.to_str().unwrap();
    let all64 = "J1:64,J2:64,J3:64,J4:64,J5:64,J6:64";
    let args = [
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        data,
        "--maps",
        all64,
    ];
    let line = refused(
        &d,
        &args,
        &["--maps", all64, "1000 readings x 768^2", "5e8"],
    );
    assert!(line.contains("fewer joints or harmonics"), "{line}");
    // The same readings with fewer harmonics (1000 x 32^2) are fitted.
    let args = ["calibrate", "--setup", SETUP, "--data", data, "--json"];
    let maps = ["--maps", "J2:8,J3:8", "--gravity", "none"];
    let v = json(&stiffid(&[&args[..], &maps].concat()));
    assert_eq!(v["maps"]["asked"], "J2:8,J3:8");
    assert!(v["maps"]["skipped"].is_null() && v["maps"]["nested"].is_object());
    // The text shows a map's coefficients in one line, the largest with its value.
    let out = stiffid(&[&args[..5], &maps].concat());
    assert_success(&out);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        !text.contains(".map.cos") && !text.contains(".map.sin"),
        "{text}"
    );
    for j in ["joint2", "joint3"] {
        let prefix = format!("{j}.map.");
        let largest = (v["parameters"].as_array().unwrap().iter())
            .filter(|p| p["name"].as_str().unwrap().starts_with(&prefix))
            .map(|p| p["value"].as_f64().unwrap())
            .max_by(|a, b| a.abs().total_cmp(&b.abs()))
            .unwrap();
        let line = (text.lines())
            .find(|l| l.starts_with(&format!("{j}.map ")))
            .unwrap();
        assert!(
            line.contains(&format!("8 harmonics, largest {largest:.6}")),
            "{line}"
        );
    }
    // 900 postures: 3600 readings x 384^2 = 5.3e8: auto fits none, and says why.
    let many = write_file(
        &d,
        "many.csv",
        &readings(&model, &x, &tracker, &postures(900, 4)),
    );
    let args = [
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        many.to_str().unwrap(),
        "--gravity",
        "none",
        "--json",
    ];
    let v = json(&stiffid(&args));
    assert_eq!(v["maps"]["chosen"], "none");
    let why = v["maps"]["skipped"].as_str().unwrap();
    assert!(
        why.starts_with("3600 readings x 384^2 map coefficients = 5.308e8"),
        "{why}"
    );
}

/// A simulation's identifications (groups x noise levels x runs) are bounded: 2e8 is refused
/// naming `--runs` before any run.
#[test]
fn a_simulation_beyond_its_identifications_bound_is_refused() {
    let d = temp_dir("simulation-work");
    let text = std::str::from_utf8(&stiffid(&["setups", "show", "zhang2021-comau-nj165"]).stdout)
        .unwrap()
        .to_string();
    let levels = (1..=20)
        .map(|l| format!("{}", l as f64 * 0.25))
        .collect::<Vec<_>>();
    let from = "level_multiples = [0.5, 1.0, 1.5, 2.0, 2.5, 3.0]";
    assert!(text.contains(from));
    let setup = text.replace(from, &format!("level_multiples = [{}]", levels.join(", ")));
    let setup = write_file(&d, "setup.toml", &setup);
    let group = write_file(&d, "group.csv", GROUP);
    let group = group.to_str().unwrap();
    let mut args = vec![
        "simulate",
        "--setup",
        setup.to_str().unwrap(),
        "--runs",
        "100000",
    ];
    args.push("--postures");
    args.extend([group; 100]);
    refused(
        &d,
        &args,
        &[
            "runs",
            "100000 runs x 20 noise levels x 100 groups = 200000000",
            "1e8",
        ],
    );
}
