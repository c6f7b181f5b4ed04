//! `stiffid select` and `stiffid evaluate`: files written, JSON keys, one-line errors (exit 2).

use crate::common;

use common::{
    assert_criteria_positive, assert_usage_error, json, stiffid, temp_dir, write_file, GROUP,
};

#[test]
fn select_from_a_start_file_improves_it_and_evaluate_agrees() {
    let d = temp_dir("select");
    let start = write_file(&d, "start.csv", GROUP);
    let out = d.join("best.csv");
    let setup = "zhang2021-comau-nj165";
    let doc = json(&stiffid(&[
        "select",
        "--setup",
        setup,
        "--criterion",
        "zhang2021",
        "--start",
        start.to_str().unwrap(),
        "--max-evals",
        "800",
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]));
    let (before, after) = (
        doc["start_value"].as_f64().unwrap(),
        doc["value"].as_f64().unwrap(),
    );
    assert!(after < before, "{after} vs {before}");
    assert!(doc["evaluations"].as_u64().unwrap() <= 800);
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.starts_with("posture,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg\n"));
    assert_eq!(text.lines().count(), 7);

    let eval = json(&stiffid(&[
        "evaluate",
        "--setup",
        setup,
        "--postures",
        out.to_str().unwrap(),
        "--json",
    ]));
    assert_criteria_positive(&eval);
    let z = eval["zhang2021"].as_f64().unwrap();
    assert!(
        (z - after).abs() < 1e-5 * after,
        "file round trip: {z} vs {after}"
    );
    let rates = eval["predicted_deviation_pct"].as_array().unwrap();
    assert_eq!(rates.len(), 6);
    assert!(rates.iter().all(|r| r.as_array().unwrap().len() == 6));

    // The start file is never the output.
    let refused = stiffid(&[
        "select",
        "--setup",
        setup,
        "--criterion",
        "d-optimal",
        "--start",
        start.to_str().unwrap(),
        "--out",
        start.to_str().unwrap(),
    ]);
    assert_usage_error(&refused, &["refusing to write over the input file"]);
    assert_eq!(std::fs::read_to_string(&start).unwrap(), GROUP);
}

#[test]
fn select_random_and_global_write_postures_within_bounds() {
    let d = temp_dir("select-global");
    for extra in [
        &["--start-random", "--count", "4"][..],
        &["--global", "--starts", "2", "--max-evals", "300"][..],
    ] {
        let out = d.join("g.csv");
        let mut args = vec![
            "select",
            "--setup",
            "zhang2021-comau-nj165",
            "--criterion",
            "relative-a",
            "--seed",
            "3",
        ];
        args.extend_from_slice(extra);
        args.extend_from_slice(&["--out", out.to_str().unwrap(), "--json"]);
        let doc = json(&stiffid(&args));
        let postures = doc["postures_deg"].as_array().unwrap();
        let (lower, upper) = (
            [-90.0, -60.0, -180.0, -180.0, -90.0, -180.0],
            [90.0, 40.0, -40.0, 180.0, 90.0, 180.0],
        );
        for q in postures {
            for (a, v) in q.as_array().unwrap().iter().enumerate() {
                let v = v.as_f64().unwrap();
                assert!(v >= lower[a] && v <= upper[a], "axis {}: {v}", a + 1);
            }
        }
        assert!(doc["value"].as_f64().unwrap() <= doc["start_value"].as_f64().unwrap());
        // Why the search stopped: one reason per local search (one, or one per global start),
        // every reason listed, the found group's among them.
        let counts = doc["terminations"].as_array().unwrap();
        assert_eq!(counts.len(), 6);
        let total: u64 = counts.iter().map(|c| c["searches"].as_u64().unwrap()).sum();
        let searches = if extra[0] == "--global" { 2 } else { 1 };
        assert_eq!(total, searches, "{counts:?}");
        let found = counts
            .iter()
            .find(|c| c["termination"] == doc["termination"]);
        assert!(found.unwrap()["searches"].as_u64().unwrap() >= 1);
    }
}

#[test]
fn select_gradient_exact_or_fd_from_the_same_start() {
    let d = temp_dir("select-gradient");
    let start = write_file(&d, "start.csv", GROUP);
    let run = |gradient: &str| {
        let out = d.join(format!("{gradient}.csv"));
        json(&stiffid(&[
            "select",
            "--setup",
            "zhang2021-comau-nj165",
            "--criterion",
            "d-optimal",
            "--start",
            start.to_str().unwrap(),
            "--gradient",
            gradient,
            "--out",
            out.to_str().unwrap(),
            "--json",
        ]))
    };
    let (exact, fd) = (run("exact"), run("fd"));
    assert_eq!(exact["gradient"], "exact");
    assert_eq!(fd["gradient"], "fd");
    let value = |doc: &serde_json::Value| doc["value"].as_f64().unwrap();
    assert!(
        value(&exact) <= value(&fd) * (1.0 + 1e-6),
        "{exact} vs {fd}"
    );
    assert!(value(&fd) < fd["start_value"].as_f64().unwrap());
    let evaluations = |doc: &serde_json::Value| doc["evaluations"].as_u64().unwrap();
    assert!(evaluations(&exact) * 10 < evaluations(&fd));

    let unknown = stiffid(&[
        "select",
        "--setup",
        "zhang2021-comau-nj165",
        "--criterion",
        "d-optimal",
        "--start-random",
        "--gradient",
        "numeric",
        "--out",
        d.join("never.csv").to_str().unwrap(),
    ]);
    assert_eq!(unknown.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&unknown.stderr).contains("exact, fd"));
}

/// Both SQPs from the same start on a smooth criterion: the document names the one that ran, ours
/// ends no worse than SLSQP (to 1e-6); the default `auto` runs ours there and SLSQP on
/// `zhang2021`, with the very result of the solver it names; an unknown name is refused with the
/// known ones.
#[test]
fn select_solver_auto_slsqp_or_active_set_from_the_same_start() {
    let d = temp_dir("select-solver");
    let start = write_file(&d, "start.csv", GROUP);
    let run = |criterion: &str, solver: Option<&str>| {
        let out = d.join(format!("{criterion}-{}.csv", solver.unwrap_or("default")));
        let mut args = vec![
            "select",
            "--setup",
            "zhang2021-comau-nj165",
            "--criterion",
            criterion,
            "--start",
            start.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--json",
        ];
        args.extend(solver.map(|s| ["--solver", s]).into_iter().flatten());
        stiffid(&args)
    };
    let doc = |criterion, solver| json(&run(criterion, solver));
    let (slsqp, ours) = (
        doc("d-optimal", Some("slsqp")),
        doc("d-optimal", Some("active-set")),
    );
    assert_eq!(slsqp["solver"], "slsqp");
    assert_eq!(ours["solver"], "active-set");
    let value = |doc: &serde_json::Value| doc["value"].as_f64().unwrap();
    assert!(
        value(&ours) <= value(&slsqp) * (1.0 + 1e-6),
        "{ours} vs {slsqp}"
    );
    assert!(value(&ours) < ours["start_value"].as_f64().unwrap());

    let the_search = |d: &serde_json::Value| (d["postures_deg"].clone(), d["value"].clone());
    for (criterion, ran) in [("d-optimal", "active-set"), ("zhang2021", "slsqp")] {
        let (default, auto) = (doc(criterion, None), doc(criterion, Some("auto")));
        let named = doc(criterion, Some(ran));
        assert_eq!(default["solver"], ran, "{criterion}");
        assert_eq!(auto["solver"], ran, "{criterion}");
        assert_eq!(the_search(&default), the_search(&named), "{criterion}");
        assert_eq!(the_search(&auto), the_search(&named), "{criterion}");
    }

    let unknown = run("d-optimal", Some("newton"));
    assert_eq!(unknown.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&unknown.stderr).contains("auto, slsqp, active-set"));
}

#[test]
fn bad_input_is_one_line_naming_the_place() {
    let d = temp_dir("select-bad");
    let out = d.join("never.csv");
    let outside = write_file(
        &d,
        "outside.csv",
        &GROUP.replace("3,60,-40,-130", "3,60,-40,-20"),
    );
    let e = stiffid(&[
        "select",
        "--setup",
        "zhang2021-comau-nj165",
        "--criterion",
        "relative-a",
        "--start",
        outside.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_usage_error(&e, &["outside.csv", "line 4", "q3_deg"]);
    assert!(!out.exists());

    let unknown = stiffid(&[
        "select",
        "--setup",
        "zhang2021-comau-nj165",
        "--criterion",
        "best",
        "--start-random",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(unknown.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&unknown.stderr).contains("relative-a"));

    let no_start = stiffid(&[
        "select",
        "--setup",
        "zhang2021-comau-nj165",
        "--criterion",
        "relative-a",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_usage_error(&no_start, &["--start-random"]);

    let broken = write_file(&d, "broken.csv", &GROUP.replace("2,-45,10", "2,-45,ten"));
    let e = stiffid(&[
        "evaluate",
        "--setup",
        "zhang2021-comau-nj165",
        "--postures",
        broken.to_str().unwrap(),
    ]);
    assert_usage_error(&e, &["broken.csv", "line 3", "q2_deg"]);
}

#[test]
fn select_force_without_report_replaces_the_postures_file() {
    let d = temp_dir("select-force");
    let out = write_file(&d, "g.csv", "old");
    let o = out.to_str().unwrap();
    let args = [
        "select",
        "--setup",
        "zhang2021-comau-nj165",
        "--start-random",
        "--max-evals",
        "20",
    ];
    let forced = stiffid(&[&args[..], &["--out", o, "--force"]].concat());
    common::assert_success(&forced);
    let written = std::fs::read_to_string(&out).unwrap();
    assert!(written.starts_with("posture,q1_deg"), "{written}");
    // The same postures as without --force: the option changed nothing else.
    let plain = d.join("plain.csv");
    common::assert_success(&stiffid(
        &[&args[..], &["--out", plain.to_str().unwrap()]].concat(),
    ));
    assert_eq!(std::fs::read_to_string(plain).unwrap(), written);
}

/// `select --for calibration` lowers the predicted calibration error of its start group, and
/// `evaluate --for calibration` of the group written reports the same value; `--for both`
/// minimises the weighted geometric mean and reports both designs' criteria.
#[test]
fn select_for_calibration_and_both_and_evaluate_agree() {
    let d = temp_dir("select-calibration");
    let setup = "zhang2021-comau-nj165";
    let out = d.join("cal.csv");
    let doc = json(&stiffid(&[
        "select",
        "--setup",
        setup,
        "--for",
        "calibration",
        "--start-random",
        "--count",
        "14",
        "--max-evals",
        "200",
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]));
    assert_eq!(doc["for"], "calibration");
    let (before, after) = (
        doc["start_value"].as_f64().unwrap(),
        doc["value"].as_f64().unwrap(),
    );
    assert!(after < 0.8 * before, "{after} vs {before}");
    let cal = &doc["calibration"];
    assert_eq!(cal["criterion"], "test-pose");
    let rms = cal["predicted_rms_mm"].as_f64().unwrap();
    assert!((rms - 1e3 * after).abs() < 1e-9 * rms, "{rms} vs {after}");
    let eval = json(&stiffid(&[
        "evaluate",
        "--setup",
        setup,
        "--postures",
        out.to_str().unwrap(),
        "--for",
        "calibration",
        "--json",
    ]));
    let again = eval["calibration"]["predicted_rms_mm"].as_f64().unwrap();
    assert!(
        (again - rms).abs() < 1e-6 * rms,
        "file round trip: {again} vs {rms}"
    );
    assert!(eval["calibration"]["o1_mm"].as_f64().unwrap() > 0.0);

    let both = json(&stiffid(&[
        "select",
        "--setup",
        setup,
        "--for",
        "both",
        "--start-random",
        "--count",
        "14",
        "--max-evals",
        "200",
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]));
    assert_eq!(both["calibration_weight"].as_f64(), Some(0.5));
    let (s, c) = (
        both["criteria"]["relative_a"].as_f64().unwrap(),
        both["calibration"]["predicted_rms_mm"].as_f64().unwrap() * 1e-3,
    );
    let v = both["value"].as_f64().unwrap();
    assert!((v - (s * c).sqrt()).abs() < 1e-6 * v, "{v} vs {s} and {c}");

    let bad = stiffid(&[
        "select",
        "--setup",
        setup,
        "--for",
        "both",
        "--weight",
        "1.5",
        "--start-random",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_usage_error(&bad, &["weight", "between 0 and 1"]);
}

/// A group too small to separate the calibration's parameters is refused, naming the count, and
/// no postures file is written; twelve postures are enough on the same setup.
#[test]
fn select_for_calibration_refuses_a_group_that_cannot_separate_it() {
    let d = temp_dir("select-calibration-small");
    for (n, ok) in [("3", false), ("12", true)] {
        let out = d.join(format!("group-{n}.csv"));
        let run = stiffid(&[
            "select",
            "--setup",
            "zhang2021-comau-nj165",
            "--for",
            "calibration",
            "--count",
            n,
            "--start-random",
            "--out",
            out.to_str().unwrap(),
        ]);
        match ok {
            true => assert!(run.status.success() && out.exists()),
            false => {
                assert_usage_error(&run, &["the 3 postures do not separate", "36 parameters"]);
                assert!(!out.exists());
            }
        }
    }
}

/// `select --for-candidates`: too few postures refused naming the count (nothing written), with
/// `--for calibration` refused, `--candidates` only with it; a design of 6 postures prints how
/// it identifies each candidate, and `evaluate --candidates` of that group agrees.
#[test]
fn select_for_candidates_refuses_and_reports() {
    let d = temp_dir("for-candidates");
    let out = d.join("group.csv");
    let out_s = out.to_str().unwrap();
    let setup = "zhang2021-comau-nj165";
    let base = [
        "select", "--setup", setup, "--global", "--starts", "2", "--out", out_s,
    ];
    let few = stiffid(&[&base[..], &["--for-candidates", "--count", "4"]].concat());
    assert_usage_error(&few, &["--for-candidates:", "at least 5 postures"]);
    assert!(!out.exists());
    let calibration = stiffid(&[&base[..], &["--for-candidates", "--for", "calibration"]].concat());
    assert_usage_error(&calibration, &["--for-candidates:", "stiffness"]);
    let names = stiffid(&[&base[..], &["--candidates", "tilt"]].concat());
    assert_eq!(names.status.code(), Some(2));
    let unknown = stiffid(&[&base[..], &["--for-candidates", "--candidates", "elbow"]].concat());
    assert_usage_error(&unknown, &["--candidates", "'elbow' is not a candidate"]);
    let doc = json(&stiffid(
        &[
            &base[..],
            &["--for-candidates", "--candidates", "tilt", "--json"],
        ]
        .concat(),
    ));
    let c = &doc["candidates"];
    assert_eq!(c["together"], true);
    let designed = c["designed"].as_array().unwrap();
    assert!(!designed.is_empty());
    let text = String::from_utf8(
        stiffid(&[
            "evaluate",
            "--setup",
            setup,
            "--postures",
            out_s,
            "--candidates",
            "tilt",
        ])
        .stdout,
    )
    .unwrap();
    assert!(text.contains("at once: identified"), "{text}");
    for name in designed {
        let line = (text.lines())
            .find(|l| {
                l.trim_start()
                    .starts_with(&format!("{} ", name.as_str().unwrap()))
            })
            .unwrap();
        assert!(line.contains(" identified "), "{line}");
    }
}
