//! The cell in the CLI: `evaluate` reports each posture's feasibility, `select` returns feasible
//! postures beside the unconstrained optimum, impossible constraints exit 2 naming the check.

use crate::common;

use common::{assert_usage_error, json, numbers, stiffid, temp_dir, write_file};
use std::path::PathBuf;

/// The paper setup (as `stiffid setups show` prints it) with `extra` appended, written to `dir`.
fn setup_file(dir: &std::path::Path, extra: &str) -> PathBuf {
    let out = stiffid(&["setups", "show", "zhang2021-comau-nj165"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap() + extra;
    write_file(dir, "cell.toml", &text)
}

const CELL: &str = "
[cell]
floor_z_mm = 0.0
clearance_mm = 50.0
[tracker]
position_mm = [3000.0, -2000.0, 1500.0]
";

#[test]
fn evaluate_reports_each_postures_feasibility() {
    let d = temp_dir("cell-evaluate");
    let setup = setup_file(&d, "\n[cell]\nfloor_z_mm = 0.0\nclearance_mm = 50.0\n");
    let postures = write_file(
        &d,
        "p.csv",
        "posture,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg\n1,0,40,-170,0,0,0\n2,0,0,-90,0,45,0\n3,0,-50,-170,0,0,0\n",
    );
    let args = ["evaluate", "--setup", setup.to_str().unwrap(), "--postures"];
    let doc = json(&stiffid(
        &[&args[..], &[postures.to_str().unwrap(), "--json"]].concat(),
    ));
    let f = doc["feasibility"].as_array().unwrap();
    assert_eq!(f.len(), 3);
    assert_eq!(f[0]["posture"], 1);
    assert_eq!(f[0]["feasible"], false);
    let checks = |p: &serde_json::Value| -> Vec<String> {
        let v = p["violations"].as_array().unwrap();
        v.iter()
            .map(|v| v["check"].as_str().unwrap().to_string())
            .collect()
    };
    assert!(checks(&f[0]).contains(&"floor".to_string()), "{f:?}");
    let floor = &f[0]["violations"][0];
    assert!(floor["margin_mm"].as_f64().unwrap() < 0.0);
    assert_eq!(floor["between"][1], "floor");
    assert_eq!(f[1]["feasible"], true);
    assert!(f[1]["min_clearance_mm"].as_f64().unwrap() >= 50.0);
    assert!(f[1]["violations"].as_array().unwrap().is_empty());
    assert!(
        checks(&f[2]).contains(&"self-collision".to_string()),
        "{f:?}"
    );
    // The text says the same.
    let out = stiffid(&[&args[..], &[postures.to_str().unwrap()]].concat());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("posture 1: INFEASIBLE: floor ("), "{text}");
    assert!(
        text.contains("posture 2: feasible, smallest clearance"),
        "{text}"
    );
    // Its figures are the document's: the checks made, the clearance and the failing margin.
    let made: Vec<&str> = (f[0]["checks"].as_array().unwrap().iter())
        .map(|c| c.as_str().unwrap())
        .collect();
    assert_eq!(made, ["bounds", "floor", "self-collision", "rope"]);
    assert!(f.iter().all(|p| p["checks"] == f[0]["checks"]));
    let shown = [
        format!("feasibility in the cell (checks: {})\n", made.join(", ")),
        format!(
            "posture 2: feasible, smallest clearance {:.1} mm",
            f[1]["min_clearance_mm"].as_f64().unwrap()
        ),
        format!(
            "posture 1: INFEASIBLE: floor ({} - floor, margin {:.1} mm)",
            floor["between"][0].as_str().unwrap(),
            floor["margin_mm"].as_f64().unwrap()
        ),
    ];
    for line in shown {
        assert!(text.contains(&line), "{line} not in\n{text}");
    }
}

#[test]
fn select_in_a_cell_is_feasible_and_shows_the_unconstrained_optimum() {
    let d = temp_dir("cell-select");
    let setup = setup_file(&d, CELL);
    let out = d.join("best.csv");
    let doc = json(&stiffid(&[
        "select",
        "--setup",
        setup.to_str().unwrap(),
        "--criterion",
        "relative-a",
        "--start-random",
        "--max-evals",
        "700",
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]));
    let free = &doc["unconstrained"];
    assert!(free["value"].as_f64().unwrap() > 0.0);
    assert_eq!(free["postures_deg"].as_array().unwrap().len(), 6);
    assert!(free["criteria"]["relative_a"].as_f64().unwrap() > 0.0);
    // What the checks cost, in %: the feasible value over the unconstrained one, and the mean
    // of each group's predicted deviation rates (levels x joints) over the other's.
    let value = |d: &serde_json::Value| d["value"].as_f64().unwrap();
    let cost = free["cost_pct"].as_f64().unwrap();
    assert!((cost - 100.0 * (value(&doc) / value(free) - 1.0)).abs() < 1e-9);
    let mean = |c: &serde_json::Value| {
        let rows = c["predicted_deviation_pct"].as_array().unwrap();
        let all: Vec<f64> = rows.iter().flat_map(numbers).collect();
        all.iter().sum::<f64>() / all.len() as f64
    };
    let pct = |key: &str| free[key].as_f64().unwrap();
    let (feasible, unconstrained) = (mean(&doc["criteria"]), mean(&free["criteria"]));
    assert!((pct("feasible_predicted_average_pct") - feasible).abs() < 1e-12 * feasible);
    assert!((pct("predicted_average_pct") - unconstrained).abs() < 1e-12 * unconstrained);
    let change = 100.0 * (feasible / unconstrained - 1.0);
    assert!((pct("predicted_average_change_pct") - change).abs() < 1e-9);
    let eval = json(&stiffid(&[
        "evaluate",
        "--setup",
        setup.to_str().unwrap(),
        "--postures",
        out.to_str().unwrap(),
        "--json",
    ]));
    for p in eval["feasibility"].as_array().unwrap() {
        assert_eq!(p["feasible"], true, "{p}");
    }
    // Without a cell there is nothing to compare with.
    let plain = json(&stiffid(&[
        "select",
        "--setup",
        "zhang2021-comau-nj165",
        "--criterion",
        "relative-a",
        "--start-random",
        "--max-evals",
        "100",
        "--out",
        d.join("plain.csv").to_str().unwrap(),
        "--json",
    ]));
    assert!(plain["unconstrained"].is_null());
}

#[test]
fn impossible_constraints_exit_2_naming_the_check() {
    let d = temp_dir("cell-impossible");
    let setup = setup_file(&d, "\n[constraints]\nloading_point_min_z_mm = 1e5\n");
    let out = d.join("never.csv");
    let e = stiffid(&[
        "select",
        "--setup",
        setup.to_str().unwrap(),
        "--criterion",
        "relative-a",
        "--global",
        "--starts",
        "2",
        "--max-evals",
        "100",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_usage_error(&e, &["no feasible group", "loading-point-min-z"]);
    assert!(!out.exists());
}

#[test]
fn the_readme_cell_example_group_is_feasible_in_its_cell() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/cell");
    let setup = root.join("zhang2021-tracker.toml");
    let postures = root.join("feasible-relative-a.csv");
    let out = stiffid(&[
        "evaluate",
        "--setup",
        setup.to_str().unwrap(),
        "--postures",
        postures.to_str().unwrap(),
        "--json",
    ]);
    let doc = json(&out);
    let f = doc["feasibility"].as_array().unwrap();
    assert_eq!(f.len(), 6);
    for p in f {
        assert_eq!(p["feasible"], true, "{p}");
        assert!(p["min_clearance_mm"].as_f64().unwrap() >= 50.0, "{p}");
    }
}

/// A search that ends on its active constraints keeps its result: there the margins meet the
/// search's slack to rounding (`1e-4 - 2e-15` m), which once counted as a violation and let the
/// start, exactly outside every constraint, win. 36 postures in the tracker cell, one start:
/// the calibration's D-optimality improved 1.000x before, 1.4x now, feasible.
#[test]
fn a_search_ending_on_its_constraints_keeps_its_result() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/cell");
    let dir = temp_dir("active-constraints");
    let out = dir.join("group.csv");
    let doc = json(&stiffid(&[
        "select",
        "--setup",
        root.join("zhang2021-tracker.toml").to_str().unwrap(),
        "--for",
        "calibration",
        "--calibration-criterion",
        "d-optimality",
        "--global",
        "--count",
        "36",
        "--starts",
        "1",
        "--screen-steps",
        "0",
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]));
    let [start, value] = ["start_value", "value"].map(|k| doc[k].as_f64().unwrap());
    assert!(value < 0.8 * start, "{start} -> {value}");
    // Most postures end on a constraint, at the search's 0.1 mm slack to rounding.
    let margins = numbers(&doc["min_margin_mm"]);
    assert_eq!(margins.len(), 36);
    assert!(margins.iter().all(|m| *m > 0.0999), "{margins:?}");
    assert!(
        margins.iter().filter(|m| **m < 0.1001).count() >= 6,
        "{margins:?}"
    );
}
