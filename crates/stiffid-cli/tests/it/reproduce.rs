//! `stiffid reproduce`: every file of the report, figures inside the HTML, the same summary for the
//! same seed, the paper's index lowered by Group 3, and foreign directories left alone.

use serde_json::Value;
use std::path::Path;
use std::process::Output;

use crate::common;

use common::{
    assert_criteria_positive, assert_success, assert_usage_error, fresh_dir, stiffid, temp_dir,
};

/// A small but complete study: 20 runs, 2 starts per global search, 2 start groups checked.
fn reproduce(out: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "reproduce",
        "--out",
        out.to_str().unwrap(),
        "--runs",
        "20",
        "--starts",
        "2",
        "--trials",
        "2",
        "--seed",
        "5",
    ];
    args.extend_from_slice(extra);
    stiffid(&args)
}

fn summary(dir: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

/// Every file of the report is there and not empty, each figure inline in the HTML (nothing
/// fetched from elsewhere) and linked from the Markdown; `names`: the groups'.
fn assert_files(dir: &Path, names: &[&str]) {
    let mut files = vec![
        "report.html".to_string(),
        "report.md".into(),
        "summary.json".into(),
        "deviation_rates.csv".into(),
    ];
    files.extend(names.iter().map(|n| format!("{n}.csv")));
    let mut figures = vec![
        "deviation_vs_noise".to_string(),
        "table4_level2".into(),
        "criteria_vs_deviation".into(),
    ];
    figures.extend(names.iter().map(|n| format!("postures_{n}")));
    for f in &figures {
        files.push(format!("figures/{f}.svg"));
        files.push(format!("figures/{f}.png"));
    }
    for f in &files {
        let bytes = std::fs::read(dir.join(f)).unwrap_or_else(|_| panic!("missing {f}"));
        assert!(!bytes.is_empty(), "{f} is empty");
    }
    assert!(std::fs::read(dir.join("figures/deviation_vs_noise.png"))
        .unwrap()
        .starts_with(b"\x89PNG"));

    // Figures inline, nothing fetched from elsewhere.
    let html = std::fs::read_to_string(dir.join("report.html")).unwrap();
    assert_eq!(html.matches("<svg").count(), figures.len());
    for f in &figures {
        assert!(
            html.contains(&format!("<figure id=\"{f}\">")),
            "{f} not in the HTML"
        );
    }
    assert!(!html.contains("src=\"http") && !html.contains("href=\"http"));
    let md = std::fs::read_to_string(dir.join("report.md")).unwrap();
    assert!(md.contains("![deviation_vs_noise](figures/deviation_vs_noise.png)"));
}

/// The summary's shape, and the paper's index lowered by the local search.
fn assert_summary(summary: &Value) {
    // The summary's shape and the paper's index lowered by the local search.
    assert_eq!(summary["runs"], 20);
    assert_eq!(summary["levels"].as_array().unwrap().len(), 6);
    assert_eq!(summary["setup"]["characteristic_length_mm"], 1200.0);
    let groups = summary["groups"].as_array().unwrap();
    for g in groups {
        assert_eq!(g["postures_deg"].as_array().unwrap().len(), 6);
        for key in [
            "mean_deviation_pct",
            "std_deviation_pct",
            "predicted_deviation_pct",
        ] {
            let rows = g[key].as_array().unwrap();
            assert_eq!(rows.len(), 6, "{key}");
            assert!(rows.iter().all(|r| r.as_array().unwrap().len() == 6));
        }
        assert_criteria_positive(g);
    }
    let zhang = |g: usize| groups[g]["zhang2021"].as_f64().unwrap();
    assert!(
        zhang(2) < zhang(0),
        "Group 3 {} not below Group 1 {}",
        zhang(2),
        zhang(0)
    );
}

/// The start groups' check: its first group is Group 1, searched the same way, with the same
/// predictions.
fn assert_start_trials(summary: &Value) {
    let groups = summary["groups"].as_array().unwrap();
    let trials = summary["start_trials"].as_array().unwrap();
    assert_eq!(trials.len(), 2);
    assert_eq!(trials[0]["seed"], 5);
    // The first start group of the check is Group 1, searched the same way: same predictions.
    let predicted_avg = |g: &Value| {
        let rows = g["predicted_deviation_pct"].as_array().unwrap();
        let sum: f64 = rows
            .iter()
            .flat_map(|r| r.as_array().unwrap())
            .map(|v| v.as_f64().unwrap())
            .sum();
        sum / 36.0
    };
    let t0 = &trials[0];
    assert!(
        (t0["start_predicted_average_pct"].as_f64().unwrap() / predicted_avg(&groups[0]) - 1.0)
            .abs()
            < 1e-12
    );
    assert!(
        (t0["zhang2021_predicted_average_pct"].as_f64().unwrap() / predicted_avg(&groups[2]) - 1.0)
            .abs()
            < 1e-12
    );
}

#[test]
fn the_report_is_complete_self_contained_and_reproducible() {
    let dir = fresh_dir("report");
    let out = reproduce(&dir, &[]);
    assert_success(&out);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("report.html") && stdout.contains("Groups 1 and 2"),
        "{stdout}"
    );

    let first = summary(&dir);
    let groups = first["groups"].as_array().unwrap();
    let names: Vec<&str> = groups.iter().map(|g| g["name"].as_str().unwrap()).collect();
    assert_eq!(
        names,
        [
            "group1-start",
            "group2-classical",
            "group3-zhang2021",
            "group4-relative-a",
            "group5-d-optimal"
        ]
    );
    assert_files(&dir, &names);
    assert_summary(&first);
    assert_start_trials(&first);
    let csv = std::fs::read_to_string(dir.join("deviation_rates.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 5 * 6 * 6);

    // Its own directory is rewritten without --force, identically apart from the time.
    assert_success(&reproduce(&dir, &[]));
    let mut second = summary(&dir);
    let mut first = first;
    assert!(second["elapsed_s"].as_f64().unwrap() > 0.0);
    first["elapsed_s"] = Value::Null;
    second["elapsed_s"] = Value::Null;
    assert_eq!(first, second);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_foreign_non_empty_directory_is_refused_without_force() {
    let dir = temp_dir("foreign");
    std::fs::write(dir.join("notes.txt"), "mine").unwrap();
    assert_usage_error(&reproduce(&dir, &[]), &["--force", "not a previous report"]);
    let entries: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert_eq!(entries.len(), 1, "wrote into a foreign directory");
    assert_eq!(
        std::fs::read_to_string(dir.join("notes.txt")).unwrap(),
        "mine"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
