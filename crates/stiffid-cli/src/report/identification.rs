//! The report of `stiffid identify --report DIR`: `report.html` (self-contained, figures inline as
//! SVG, the 3D scene of the load tests), `identify.json` (the identify job's document, any of its
//! forms, which the other files render), `identify.glb` (the scene as glTF binary; not for the
//! model comparison) and `figures/` (SVG and PNG): the measured against the predicted displacements, the
//! parameters' 95% intervals, the residuals' QQ plot against the noise, the stability
//! of the cross-validation's folds, the prediction intervals' held-out scores, the compared
//! models' held-out shares with their standard errors ([`stiffid_figures::identify`]).

use super::document::{self as report, Kind, PAGE};
use super::figures::Figure;
use super::html::Writer;
use super::tables::{num, Table};
use crate::output::ReportDir;
use anyhow::Result;
use serde_json::Value;
use std::path::Path;
use stiffid::internal::view::stance::Postures;
use stiffid::internal::view::{glb, Scene};
use stiffid::Setup;

/// The identification's report: `report.html`, `identify.json`, `identify.glb`.
const KIND: Kind = Kind {
    generator: "stiffid identify",
    files: &[PAGE, "identify.json", "identify.glb"],
};

/// Opens the report directory `dir` (`--report`) before the identification: new, empty or
/// holding an identification report of ours (its `report.html`); see [`Kind::open`].
pub fn open(dir: &Path) -> Result<ReportDir> {
    KIND.open(dir)
}

/// Writes every file of the report of the identify document `json` (its text) into `dir`, with
/// the 3D scene of the load tests in `postures` (axis angles, rad, in the order the document's
/// residuals first name them, and their external axes' values, SI; `None` for the model
/// comparison, which has no scene).
pub fn write(dir: ReportDir, json: &str, setup: &Setup, postures: Option<Postures>) -> Result<()> {
    let doc: Value = serde_json::from_str(json)?;
    let figures = report::draw(&stiffid_figures::identify::figures(&doc)?)?;
    let scene = postures
        .map(|(p, e)| stiffid::app::identify::document::scene::scene(setup, &p, &e, json))
        .transpose()?;
    let name = doc["setup"].as_str().unwrap_or_default();
    let html = KIND.page(&format!("stiffid identification: {name}"), |w| {
        compose(w, &doc, &figures, scene.as_ref())
    });
    let mut files = vec![
        (PAGE.into(), html.into_bytes()),
        (KIND.files[1].into(), json.as_bytes().to_vec()),
    ];
    if let Some(s) = &scene {
        files.push((KIND.files[2].into(), glb::glb(s)));
    }
    report::write(dir, files, figures)
}

fn text(v: &Value) -> String {
    match v {
        Value::Null => "-".into(),
        Value::Number(n) if n.is_f64() => n.as_f64().map_or("-".into(), num),
        Value::Number(n) => n.to_string(),
        Value::String(s) => s.clone(),
        Value::Bool(b) => if *b { "yes" } else { "no" }.into(),
        other => other.to_string(),
    }
}

fn compose(w: &mut dyn Writer, doc: &Value, figures: &[Figure], scene: Option<&Scene>) {
    w.heading(
        1,
        &format!("Stiffness identification: {}", text(&doc["setup"])),
    );
    w.paragraph(&format!("Measurements `{}`.", text(&doc["data"])));
    if let Some(c) = doc["conclusion"].as_str() {
        w.paragraph(c);
    }
    for warning in doc["warnings"].as_array().into_iter().flatten() {
        w.paragraph(&format!("Warning: {}", text(&warning["message"])));
    }
    if doc["kind"] == "identify-comparison" {
        w.heading(2, "The compared models");
        w.table(&models_table(doc));
    }
    if let Some(p) = doc["parameters"]
        .as_array()
        .or(doc["fit"]["parameters"].as_array())
    {
        w.heading(2, "The stiffness");
        w.table(&parameters_table(doc, p));
    }
    if doc.get("residual_rms_mm").is_some() {
        w.paragraph(&format!(
            "Residual RMS {} mm; the residuals' spread is {} times the tracker's noise on a displacement coordinate ({} mm).",
            text(&doc["residual_rms_mm"]),
            text(&doc["noise_ratio"]),
            text(&doc["noise_std_mm"])
        ));
    }
    let cv = &doc["cross_validation"];
    if cv.is_object() {
        w.paragraph(&format!(
            "Cross-validation over {} folds: held out, the model explains {} % ± {} % of the measured displacement (RMS prediction error {} mm).",
            text(&cv["folds"]),
            text(&cv["explained_pct"]),
            text(&cv["explained_std_error_pct"]),
            text(&cv["rms_delta_b_mm"])
        ));
    }
    if let Some(q) = doc["prediction"]["score_q95_pct"].as_f64() {
        w.paragraph(&format!(
            "Prediction intervals ({}): 95% of the held-out errors are within {} % of the predicted displacement plus {} mm; `predict --stiffness` gives them for any posture.",
            text(&doc["prediction"]["method"]),
            num(q),
            text(&doc["prediction"]["noise_floor_mm"])
        ));
    }
    for f in figures {
        w.figure(f);
    }
    if let Some(s) = scene {
        w.heading(2, "The load tests in 3D");
        w.paragraph("The robot at each load-test posture with the rope, each measuring point's measured displacement and the one the fit predicts (its longest reading's, under the full load of load steps), and the identified compliance's ellipsoid at the TCP under the setup's load, magnified (the factor in the legend).");
        w.scene(s, KIND.files[2]);
    }
    w.paragraph(
        "Files: identify.json (the identify document this page renders), identify.glb (the 3D scene, except for a model comparison), figures/ (SVG and PNG).",
    );
}

/// Each parameter's stiffness with its 95% interval and, for the drives, its standard error.
fn parameters_table(doc: &Value, parameters: &[Value]) -> Table {
    let se = doc["std_error_pct"].as_array();
    let drives = doc["ci95_nm_per_rad"].as_array();
    let header = [
        "parameter",
        "unit",
        "stiffness",
        "95% interval",
        "standard error, %",
    ]
    .map(String::from)
    .to_vec();
    let rows = (parameters.iter().enumerate())
        .map(|(j, p)| {
            let ci = match &p["ci95"] {
                Value::Array(c) => Some(c),
                _ => drives.and_then(|d| d.get(j)).and_then(Value::as_array),
            };
            vec![
                text(&p["name"]),
                text(&p["unit"]),
                text(&p["stiffness"]),
                ci.map_or("-".into(), |c| {
                    let ends: Vec<Option<f64>> = c.iter().map(Value::as_f64).collect();
                    match ends[..] {
                        // Both ends with the digits that tell them apart.
                        [Some(a), Some(b)] => {
                            let ends = stiffid::internal::common::words::apart(&[a, b], 4);
                            format!("{} to {}", ends[0], ends[1])
                        }
                        _ => {
                            let end = |i: usize| c.get(i).map_or("-".into(), text);
                            format!("{} to {}", end(0), end(1))
                        }
                    }
                }),
                se.and_then(|s| s.get(j)).map_or("-".into(), text),
            ]
        })
        .collect();
    Table { header, rows }
}

/// The compared models: parameters, in-sample and held-out shares with standard errors.
fn models_table(doc: &Value) -> Table {
    let header = [
        "model",
        "parameters",
        "explained in sample, %",
        "held out, %",
        "standard error, %",
        "recommended",
    ]
    .map(String::from)
    .to_vec();
    let pct = |v: &Value| v.as_f64().map_or("-".into(), |x| num(100.0 * x));
    let rows = (doc["models"].as_array().into_iter().flatten())
        .map(|m| {
            let springs: Vec<String> = m["springs"]
                .as_array()
                .into_iter()
                .flatten()
                .map(text)
                .collect();
            vec![
                match springs.is_empty() {
                    true => "drives".into(),
                    false => springs.join(", "),
                },
                text(&m["parameters"]),
                pct(&m["in_sample_explained"]),
                pct(&m["held_out_explained"]),
                pct(&m["held_out_explained_std_error"]),
                text(&m["recommended"]),
            ]
        })
        .collect();
    Table { header, rows }
}
