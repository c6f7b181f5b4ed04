//! `stiffid select --for calibration` on the example track cell with reflectors on its table:
//! `--out` and the document give every posture its positioner angles for the table's readings,
//! within the travel, at the station asked for; the campaign's plan (`--report`) writes them
//! with what to read.

use crate::common;

use common::{json, refused, stiffid, temp_dir};
use std::path::Path;

#[test]
fn select_gives_each_posture_the_positioners_angles() {
    let dir = temp_dir("table-angles");
    let example =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/track/track-cell.toml");
    // `[workpiece]` is the example's last table: the reflectors join it.
    let text = std::fs::read_to_string(example).unwrap()
        + "reflectors_mm = [[300, 0, 40], [-200, 250, 40], [-100, -300, 60]]\n";
    let setup = dir.join("cell.toml");
    std::fs::write(&setup, text).unwrap();
    let out = dir.join("campaign.csv");
    let doc = json(&stiffid(&[
        "select",
        "--setup",
        setup.to_str().unwrap(),
        "--for",
        "calibration",
        "--start-random",
        "--count",
        "12",
        "--station",
        "3000,0,0",
        "--seed",
        "1",
        "--max-evals",
        "100",
        "--out",
        out.to_str().unwrap(),
        "--report",
        dir.join("plan").to_str().unwrap(),
        "--json",
    ]));
    let stations = doc["posture_stations"].as_array().unwrap();
    assert_eq!(stations.len(), 12);
    let csv = std::fs::read_to_string(&out).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(&header[7..], ["e1_mm", "e2_deg", "e3_deg"]);
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').skip(7).map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 12);
    for (row, station) in rows.iter().zip(stations) {
        assert_eq!(row[0], 3000.0);
        assert!(row[1].abs() < 95.0 && row[2].abs() < 360.0, "{row:?}");
        assert!((station["e2_deg"].as_f64().unwrap() - row[1]).abs() < 1e-5);
        assert!((station["e3_deg"].as_f64().unwrap() - row[2]).abs() < 1e-5);
    }
    assert!(rows
        .iter()
        .any(|r| r[1] != rows[0][1] || r[2] != rows[0][2]));
    // The plan is the campaign's: the postures file as its table, what to read (the tool's
    // reflectors and the table's T1-T3) and where, no load test.
    let plan = std::fs::read_to_string(dir.join("plan/plan.csv")).unwrap();
    assert_eq!(plan, csv);
    let page = std::fs::read_to_string(dir.join("plan/plan.html")).unwrap();
    assert!(page.contains("Calibration campaign: 12 postures"), "{page}");
    for reflector in ["T1", "T2", "T3", "Tool reflector 1"] {
        assert!(page.contains(reflector), "{reflector}");
    }
    for column in ["e1_mm", "e2_deg", "e3_deg", "q6_deg"] {
        assert!(page.contains(column), "{column}");
    }
    for load_test in ["rope_length_mm", "a load of", "relative-a", "the rope"] {
        assert!(
            !page.contains(load_test),
            "{load_test} in the campaign's plan"
        );
    }
    let text = std::fs::read_to_string(dir.join("plan/plan.json")).unwrap();
    let planned: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(planned["posture_stations"], doc["posture_stations"]);
    // The value minimised is the group's predicted error with the table read at its angles.
    let predicted = doc["calibration"]["predicted_rms_mm"].as_f64().unwrap();
    let value = doc["value"].as_f64().unwrap() * 1e3;
    assert!(
        (predicted - value).abs() <= 1e-6 * predicted,
        "{predicted} {value}"
    );
}

/// A wall between the tracker and the positioner hides the table's reflectors at every angle of
/// the positioner: the design is refused for that, naming the table and what to move, before any
/// search (the search would first meet the wall in the tool's own lines of sight), nothing written.
#[test]
fn reflectors_hidden_at_every_table_angle_are_refused_before_the_search() {
    let dir = temp_dir("table-hidden");
    let example =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/track/track-cell.toml");
    let text = std::fs::read_to_string(example).unwrap()
        + "reflectors_mm = [[300, 0, 40], [-200, 250, 40]]\n"
        + "[cell]\nclearance_mm = 20\n[tracker]\nposition_mm = [3000, 4500, 1500]\n"
        + "[[cell.obstacle]]\nname = \"wall\"\nmin_mm = [-2000, 3400, -500]\n"
        + "max_mm = [8000, 3500, 6000]\n";
    let setup = dir.join("cell.toml");
    std::fs::write(&setup, text).unwrap();
    let args = [
        "select",
        "--setup",
        setup.to_str().unwrap(),
        "--for",
        "calibration",
        "--start-random",
        "--count",
        "12",
        "--station",
        "3000,0,0",
        "--seed",
        "1",
        "--out",
        "{dir}/campaign.csv",
    ];
    let line = refused(
        &dir,
        &args,
        &[
            "table",
            "no angle of the positioner has clear lines of sight",
        ],
    );
    assert!(
        line.contains("move the tracker or the reflectors"),
        "{line}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
