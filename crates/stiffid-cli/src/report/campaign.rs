//! The plan of a calibration campaign, `stiffid select --for calibration|check --report DIR`:
//! `plan.html` (what to read where: the stations, the table angles and the reflectors of every
//! posture), `plan.csv` (one row per posture, the postures file `--out` writes) and `plan.json`
//! (the select document).
//! A calibration reads the unloaded robot: no load test.

use super::html;
use super::tables::{num, Table};
use crate::output::{json, ReportDir};
use anyhow::Result;
use nalgebra::Vector3;
use stiffid::app::select::document::Document;
use stiffid::app::select::Report;
use stiffid::Setup;

/// The generator mark of `plan.html`, as the stiffness plan's (one plan directory either way).
const GENERATOR: &str = "stiffid select";

/// Writes `plan.html`, `plan.csv` (`csv`: the postures file `--out` writes, the table of the
/// page) and `plan.json` of the campaign `report` chosen on `setup` by `command` into `dir`, each
/// file whole.
pub fn write(
    dir: ReportDir,
    setup: &Setup,
    report: &Report,
    csv: &str,
    command: &str,
) -> Result<()> {
    let doc = &report.document();
    let table = postures_table(doc);
    let n = doc.postures.len();
    let title = format!("Calibration campaign: {n} postures on {}", setup.name());
    let page = html::page(&title, GENERATOR, |w| {
        w.heading(1, &title);
        w.paragraph(&summary(setup, doc, command));
        w.heading(2, "What to read");
        w.list(&reflectors(setup));
        w.heading(2, "Steps, for each posture");
        w.list(&steps(setup, doc));
        w.table(&table);
        w.paragraph("Files: plan.csv (the table above, as the postures file: machine-readable), plan.json (the select document this page renders).");
    });
    let files = vec![
        ("plan.html".to_string(), page.into_bytes()),
        ("plan.csv".into(), csv.as_bytes().to_vec()),
        ("plan.json".into(), json(report)?.into_bytes()),
    ];
    dir.write_all(&files)?;
    dir.finish()
}

/// The robot, the calibration designed for and how the group was chosen.
fn summary(setup: &Setup, doc: &Document, command: &str) -> String {
    let designed = match &doc.calibration {
        Some(c) => format!(
            "Designed for the calibration `calibrate` fits (geometry `{}`, gravity `{}`, {} parameters) by the criterion `{}`; predicted RMS position error after it at the test postures: {} mm.",
            c.geometry,
            c.gravity,
            c.parameters,
            c.criterion,
            c.predicted_rms_mm.map_or("not separated".into(), num)
        ),
        None => String::new(),
    };
    format!(
        "Robot {}, read unloaded by the tracker. {designed} Chosen by `{command}` (seed {}).",
        setup.robot().name(),
        doc.seed
    )
}

/// The reflectors to read at every posture: the tool's, numbered as the readings' points, and
/// the table's, `T1`, `T2`, ... as the readings name them.
fn reflectors(setup: &Setup) -> Vec<String> {
    let at = |p: &Vector3<f64>| {
        format!(
            "({}, {}, {}) mm",
            num(p.x * 1e3),
            num(p.y * 1e3),
            num(p.z * 1e3)
        )
    };
    let tool = &setup.tool().measuring_points;
    let mut out: Vec<String> = (tool.iter().enumerate())
        .map(|(i, p)| {
            format!(
                "Tool reflector {} (point {} of the readings) at {}, flange frame.",
                i + 1,
                i + 1,
                at(p)
            )
        })
        .collect();
    let table = setup.table_reflectors();
    out.extend((table.iter().enumerate()).map(|(i, p)| match positioner(setup) {
        true => format!("Table reflector T{} (point T{} of the readings) at {}, cell frame with every axis at 0: read it at the posture's table angles.", i + 1, i + 1, at(p)),
        false => format!("Part reflector T{} (point T{} of the readings) at {}, cell frame: a fixed point of the cell, read it once (or at a few postures) in the same tracker session.", i + 1, i + 1, at(p)),
    }));
    out
}

/// Whether the cell has a positioner (its table's reflectors turn with it).
fn positioner(setup: &Setup) -> bool {
    (setup.robot().external()).is_some_and(|a| a.len() > a.carrier_len())
}

/// What to do at each posture: the external axes first, then the arm, then the readings.
fn steps(setup: &Setup, doc: &Document) -> Vec<String> {
    let mut out = Vec::new();
    let external = !doc.posture_stations.is_empty() || doc.station.is_some();
    if external {
        out.push("Move the external axes to the posture's values (the e columns: the track's station in mm, the positioner's table angles in deg).".to_string());
    }
    out.push("Move the arm to the posture's axis angles (the controller's, degrees).".into());
    let points = setup.tool().measuring_points.len();
    out.push(format!(
        "Read {} with the tracker, and write each reading as a row of the readings CSV (posture, point, x_mm, y_mm, z_mm{}; docs/reference.md, Readings CSV).",
        match (points, setup.table_reflectors().len()) {
            (p, 0) => format!("the tool's {p} reflector(s)"),
            (p, t) if positioner(setup) => format!("the tool's {p} reflector(s) and the table's {t}"),
            (p, t) => format!("the tool's {p} reflector(s) (and the part's {t} where the list says)"),
        },
        if external { " and the e columns" } else { "" }
    ));
    out
}

/// One row per posture: its label, its external axes' values and its axis angles.
fn postures_table(doc: &Document) -> Table {
    let at = |i: usize| doc.posture_stations.get(i).or(doc.station.as_ref());
    let columns: Vec<String> = at(0)
        .map(|s| s.keys().cloned().collect())
        .unwrap_or_default();
    let mut header = vec!["posture".to_string()];
    header.extend((1..=6).map(|j| format!("q{j}_deg")));
    header.extend(columns.iter().cloned());
    let rows = (doc.postures.iter().enumerate())
        .map(|(i, q)| {
            let mut row = vec![(i + 1).to_string()];
            let e = |c: &String| at(i).and_then(|s| s.get(c)).copied().unwrap_or(f64::NAN);
            row.extend(q.iter().map(|v| format!("{:.6}", v.to_degrees())));
            row.extend(columns.iter().map(|c| format!("{:.6}", e(c))));
            row
        })
        .collect();
    Table { header, rows }
}
