//! `stiffid select --pool / --target-pct / --report` and `stiffid plot`: what is chosen, files
//! written (figures that decode), one-line errors (exit 2).

use crate::common;

use common::{assert_usage_error, json, stiffid, temp_dir, write_file, GROUP};
use std::path::Path;

/// 13 postures: `GROUP`, six more, and posture 13 outside the paper setup's bounds (q3 = -20).
fn pool_text() -> String {
    GROUP.to_string()
        + "7,45,-30,-60,60,-50,-90
8,-60,20,-150,-120,10,45
9,75,-10,-110,20,-80,170
10,-25,35,-45,170,55,-120
11,5,-50,-170,-60,-15,100
12,-85,-5,-80,90,75,-10
13,0,0,-20,0,0,0
"
}

fn select(args: &[&str]) -> std::process::Output {
    let mut all = vec!["select", "--setup", "zhang2021-comau-nj165"];
    all.extend_from_slice(args);
    stiffid(&all)
}

fn png_size(path: &Path) -> (u32, u32) {
    let decoder = png::Decoder::new(std::fs::File::open(path).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert!(buf.iter().any(|&b| b < 128), "{}: blank", path.display());
    (info.width, info.height)
}

fn assert_svg(path: &Path, size: (u32, u32)) {
    let svg = std::fs::read_to_string(path).unwrap();
    assert!(svg.contains("<svg"), "{}", path.display());
    assert!(
        svg.contains(&format!("width=\"{}\" height=\"{}\"", size.0, size.1)),
        "{}",
        path.display()
    );
    assert!(svg.trim_end().ends_with("</svg>"), "{}", path.display());
    assert!(svg.matches("<polyline").count() + svg.matches("<path").count() > 3);
}

#[test]
fn pool_choice_is_the_enumerated_optimum_and_skips_postures_outside_the_bounds() {
    let d = temp_dir("pool");
    let pool = write_file(&d, "pool.csv", &pool_text());
    let out = d.join("best.csv");
    let doc = json(&select(&[
        "--pool",
        pool.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]));
    assert_eq!(doc["criterion"], "relative-a", "the default criterion");
    assert_eq!(doc["search"], "pool");
    assert!(doc["start_value"].is_null());
    let p = &doc["pool"];
    assert_eq!(p["postures"], 13);
    assert_eq!(p["usable"], 12);
    assert_eq!(p["skipped"][0]["posture"], 13);
    assert_eq!(p["skipped"][0]["checks"][0], "bounds");
    assert!(p["skipped"][0]["reason"]
        .as_str()
        .unwrap()
        .contains("axis 3"));
    assert_eq!(p["method"], "enumeration", "C(12, 6) = 924 groups");
    let chosen: Vec<u64> = p["chosen"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_u64().unwrap())
        .collect();
    assert_eq!(chosen.len(), 6);
    assert!(!chosen.contains(&13));
    // The criterion's JSON key is accepted as its name.
    let exchange = json(&select(&[
        "--criterion",
        "relative_a",
        "--pool",
        pool.to_str().unwrap(),
        "--out",
        d.join("x.csv").to_str().unwrap(),
        "--json",
    ]));
    assert_eq!(exchange["pool"]["chosen"], p["chosen"]);
    // The file written is the chosen group, and evaluates to the reported value.
    let eval = json(&stiffid(&[
        "evaluate",
        "--setup",
        "zhang2021-comau-nj165",
        "--postures",
        out.to_str().unwrap(),
        "--json",
    ]));
    let (v, e) = (
        doc["value"].as_f64().unwrap(),
        eval["relative_a"].as_f64().unwrap(),
    );
    assert!((v - e).abs() < 1e-6 * v, "{v} vs {e}");

    let refused = select(&[
        "--pool",
        pool.to_str().unwrap(),
        "--out",
        pool.to_str().unwrap(),
    ]);
    assert_usage_error(&refused, &["refusing to write over the input file"]);
    let too_many = select(&[
        "--pool",
        pool.to_str().unwrap(),
        "--count",
        "13",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_usage_error(&too_many, &["pool.csv", "only 12 of the 13", "bounds 1"]);
    let unknown = select(&[
        "--criterion",
        "relative",
        "--pool",
        "x.csv",
        "--out",
        "y.csv",
    ]);
    assert_eq!(unknown.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&unknown.stderr).contains("unknown criterion 'relative'"));
}

#[test]
fn pool_postures_that_fail_the_cells_checks_are_skipped() {
    let d = temp_dir("pool-cell");
    let paper = stiffid(&["setups", "show", "zhang2021-comau-nj165"]);
    let setup = String::from_utf8(paper.stdout).unwrap()
        + "\n[cell]\nfloor_z_mm = 0.0\nclearance_mm = 50.0\n";
    let setup = write_file(&d, "cell.toml", &setup);
    // Posture 14: upper arm 40 deg forward, forearm 100 deg down: the tool is in the floor.
    let pool = write_file(&d, "pool.csv", &(pool_text() + "14,0,40,-170,0,0,0\n"));
    let run = |n: &str| {
        stiffid(&[
            "select",
            "--setup",
            setup.to_str().unwrap(),
            "--pool",
            pool.to_str().unwrap(),
            "--count",
            n,
            "--out",
            d.join("best.csv").to_str().unwrap(),
            "--json",
        ])
    };
    let doc = json(&run("3"));
    let p = &doc["pool"];
    let skipped = p["skipped"].as_array().unwrap();
    let floor = skipped.iter().find(|s| s["posture"] == 14).unwrap();
    assert!(floor["checks"]
        .as_array()
        .unwrap()
        .contains(&"floor".into()));
    assert!(floor["reason"].as_str().unwrap().contains("floor"));
    assert_eq!(
        p["usable"].as_u64().unwrap() as usize + skipped.len(),
        14,
        "every posture is usable or skipped"
    );
    for c in p["chosen"].as_array().unwrap() {
        assert!(
            skipped.iter().all(|s| s["posture"] != *c),
            "{c} was skipped"
        );
    }
    let e = run("14");
    assert_usage_error(
        &e,
        &["pass the cell's checks", "failed most often: ", "floor"],
    );

    // The plot draws the floor, the obstacles and the tracker of the cell.
    let cell = std::fs::read_to_string(&setup).unwrap()
        + "[[cell.obstacle]]\nname = \"table\"\nmin_mm = [1200, -400, 0]\nmax_mm = [1800, 400, 750]\n\
           [tracker]\nposition_mm = [3000, -2000, 1500]\n";
    let cell = write_file(&d, "cell-tracker.toml", &cell);
    let figs = d.join("figs");
    let out = stiffid(&[
        "plot",
        "--setup",
        cell.to_str().unwrap(),
        "--postures",
        d.join("best.csv").to_str().unwrap(),
        "--out",
        figs.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let svg = std::fs::read_to_string(figs.join("posture_01.svg")).unwrap();
    for label in [">\nfloor\n<", ">\ntable\n<", ">\ntracker\n<"] {
        assert!(svg.contains(label), "{label}");
    }
    assert_eq!(png_size(&figs.join("posture_01.png")), (1200, 560));
}

#[test]
fn target_pct_gives_the_smallest_group_and_fails_when_out_of_reach() {
    let d = temp_dir("pool-target");
    let pool = write_file(&d, "pool.csv", &pool_text());
    let run = |pct: &str| {
        let out = d.join(format!("t{pct}.csv"));
        let doc = json(&select(&[
            "--pool",
            pool.to_str().unwrap(),
            "--target-pct",
            pct,
            "--out",
            out.to_str().unwrap(),
            "--json",
        ]));
        let t = &doc["target"];
        let steps = t["steps"].as_array().unwrap();
        let n = t["postures"].as_u64().unwrap();
        assert_eq!(doc["postures_deg"].as_array().unwrap().len() as u64, n);
        assert_eq!(steps[0]["postures"], 2);
        let last = steps.last().unwrap()["worst_joint_pct"].as_f64().unwrap();
        assert!(last <= pct.parse::<f64>().unwrap(), "{last}");
        for s in &steps[..steps.len() - 1] {
            assert!(s["worst_joint_pct"].as_f64().is_none_or(|w| w > last));
        }
        assert_eq!(png_size(&d.join(format!("t{pct}.target.png"))), (800, 500));
        n
    };
    let (loose, tight) = (run("6"), run("4"));
    assert!(tight > loose && loose >= 2, "{tight} vs {loose}");

    let out = d.join("never.csv");
    let e = select(&[
        "--pool",
        pool.to_str().unwrap(),
        "--target-pct",
        "0.1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_usage_error(
        &e,
        &[
            "--target-pct: 0.1 % is not reachable",
            "best reachable with the pool's 12 usable postures",
            "stopped after 2 group sizes",
        ],
    );
    assert!(!out.exists());
    let e = select(&["--target-pct", "2", "--start-random", "--out", "y.csv"]);
    assert_eq!(e.status.code(), Some(2));
    let e = select(&["--target-pct", "2", "--out", out.to_str().unwrap()]);
    assert_usage_error(&e, &["--pool", "--global"]);
}

#[test]
fn report_and_plot_write_figures_that_decode() {
    let d = temp_dir("pool-plan");
    let pool = write_file(&d, "pool.csv", &pool_text());
    let plan = d.join("plan");
    json(&select(&[
        "--pool",
        pool.to_str().unwrap(),
        "--count",
        "4",
        "--out",
        d.join("best.csv").to_str().unwrap(),
        "--report",
        plan.to_str().unwrap(),
        "--json",
    ]));
    let html = std::fs::read_to_string(plan.join("plan.html")).unwrap();
    assert!(html.contains("<figure id=\"posture_04\">"));
    // Written again with three postures: its fourth posture's figure goes, a user's file stays.
    let mine = write_file(&plan.join("figures"), "my-photo.svg", "<svg>mine</svg>");
    let (pool_path, plan_path) = (pool.to_str().unwrap(), plan.to_str().unwrap());
    let again = [
        "--pool", pool_path, "--count", "3", "--report", plan_path, "--json",
    ];
    json(&select(
        &[
            &again[..],
            &["--out", d.join("three.csv").to_str().unwrap()],
        ]
        .concat(),
    ));
    assert!(!plan.join("figures/posture_04.svg").exists());
    assert_eq!(std::fs::read_to_string(&mine).unwrap(), "<svg>mine</svg>");
    json(&select(&[
        "--pool",
        pool.to_str().unwrap(),
        "--count",
        "4",
        "--out",
        d.join("best.csv").to_str().unwrap(),
        "--report",
        plan.to_str().unwrap(),
        "--json",
    ]));
    let html = std::fs::read_to_string(plan.join("plan.html")).unwrap();
    assert!(!html.contains("src=\"http") && !html.contains("zhang2021-comau-nj165.toml"));
    let csv = std::fs::read_to_string(plan.join("plan.csv")).unwrap();
    let header = csv.lines().next().unwrap();
    assert!(header.contains("rope_length_mm") && header.contains("point4_dz_mm"));
    assert_eq!(csv.lines().count(), 5);
    for name in ["postures", "posture_01", "posture_04"] {
        assert_svg(
            &plan.join("figures").join(format!("{name}.svg")),
            (1200, 560),
        );
        assert!(!plan.join("figures").join(format!("{name}.png")).exists());
    }
}

/// `plot` writes a figure per posture and the group's, decodable, and writes again into its own
/// directory; a directory with other files needs --force, and a user's file is never lost.
#[test]
fn plot_writes_figures_and_keeps_a_users_files() {
    let d = temp_dir("plot");
    let best = write_file(
        &d,
        "best.csv",
        &GROUP.lines().take(5).collect::<Vec<_>>().join("\n"),
    );
    let pool = write_file(&d, "pool.csv", &pool_text());
    let figs = d.join("figs");
    let out = stiffid(&[
        "plot",
        "--setup",
        "zhang2021-comau-nj165",
        "--postures",
        best.to_str().unwrap(),
        "--out",
        figs.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    assert_eq!(std::fs::read_dir(&figs).unwrap().count(), 10, "5 figures");
    assert_eq!(png_size(&figs.join("posture_02.png")), (1200, 560));
    assert_svg(&figs.join("postures.svg"), (1200, 560));
    // A directory with other files is not written into without --force.
    let e = stiffid(&[
        "plot",
        "--setup",
        "zhang2021-comau-nj165",
        "--postures",
        pool.to_str().unwrap(),
        "--out",
        d.to_str().unwrap(),
    ]);
    assert_usage_error(&e, &["--force"]);
    // Figures are known by their contents: a user's file named as one is neither removed nor
    // replaced; with --force a file named as a figure the run writes is replaced, and no other
    // is removed. The plot's own directory is written again without --force.
    let plot = |out: &Path, postures: &Path, force: bool| {
        let (setup, postures) = ("zhang2021-comau-nj165", postures.to_str().unwrap());
        let mut args = vec!["plot", "--setup", setup, "--postures", postures];
        args.extend(["--out", out.to_str().unwrap()]);
        args.extend(force.then_some("--force"));
        stiffid(&args)
    };
    let two = write_file(
        &d,
        "two.csv",
        &GROUP.lines().take(3).collect::<Vec<_>>().join("\n"),
    );
    assert!(plot(&figs, &two, false).status.success());
    assert_eq!(
        std::fs::read_dir(&figs).unwrap().count(),
        6,
        "the earlier figures removed"
    );
    let mine = write_file(&figs, "posture_05.svg", "my thesis figure");
    assert_usage_error(&plot(&figs, &two, false), &["--force"]);
    assert_eq!(std::fs::read_to_string(&mine).unwrap(), "my thesis figure");
    assert!(plot(&figs, &two, true).status.success());
    assert_eq!(std::fs::read_to_string(&mine).unwrap(), "my thesis figure");
}

#[test]
fn a_plan_with_load_steps_lists_them_and_predicts_with_them() {
    let d = temp_dir("pool-steps");
    let pool = write_file(&d, "pool.csv", &pool_text());
    let text = String::from_utf8(stiffid(&["setups", "show", "zhang2021-comau-nj165"]).stdout)
        .unwrap()
        .replace(
            "[loading]\n",
            "[loading]\nsteps_n = [100, 200, 300, 400, 500]\n",
        );
    let setup = write_file(&d, "steps.toml", &text);
    let plan = d.join("plan");
    let run = |setup: &str, report: Option<&Path>| {
        let mut args = vec![
            "select",
            "--setup",
            setup,
            "--pool",
            pool.to_str().unwrap(),
            "--count",
            "4",
            "--json",
        ];
        let out = d.join(format!("best-{}.csv", report.is_some()));
        args.extend(["--out", out.to_str().unwrap()]);
        if let Some(r) = report {
            args.extend(["--report", r.to_str().unwrap()]);
        }
        json(&stiffid(&args))
    };
    let stepped = run(setup.to_str().unwrap(), Some(&plan));
    let plain = run("zhang2021-comau-nj165", None);
    assert_eq!(
        stepped["postures_deg"], plain["postures_deg"],
        "the same group"
    );
    // F^2 (S2 + S1^2) / S2^2 with S1 = 1500 N, S2 = 550 000 N^2, over the 2 of one loaded minus
    // one unloaded reading.
    let factor: f64 = 250_000.0 * (550_000.0 + 2_250_000.0) / 550_000.0f64.powi(2) / 2.0;
    let rates = |doc: &serde_json::Value| -> Vec<f64> {
        crate::common::numbers(&doc["criteria"]["predicted_deviation_pct"][1])
    };
    for (s, p) in rates(&stepped).iter().zip(rates(&plain)) {
        assert!((s / p - factor.sqrt()).abs() < 1e-9, "{s} {p}");
    }
    let html = std::fs::read_to_string(plan.join("plan.html")).unwrap();
    assert!(
        html.contains("at each load step, rising: 100, 200, 300, 400, 500 N (5 steps"),
        "{}",
        &html[..html.len().min(3000)]
    );
}
