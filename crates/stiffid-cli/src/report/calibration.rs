//! The report of `stiffid calibrate --report DIR`: `report.html` (self-contained: figures inline
//! as SVG, the 3D scene), `calibration.json` (the calibrate job's document, which the other files
//! render), `errors.glb` (the scene as glTF binary) and `figures/` (SVG and PNG). The figures are
//! the shared ones ([`stiffid_figures::calibrate`]) drawn from the document.

use super::document::{self as report, find, Kind, PAGE};
use super::figures::Figure;
use super::html::Writer;
use super::tables::{num, Table};
use crate::output::{json, ReportDir};
use anyhow::Result;
use std::path::Path;
use stiffid::app::calibrate::document::Document;
use stiffid::app::document::mm;
use stiffid::internal::common::words::apart;
use stiffid::internal::view::{glb, Scene};
use stiffid::Setup;

/// The calibration's report: `report.html`, `calibration.json`, `errors.glb`.
const KIND: Kind = Kind {
    generator: "stiffid calibrate",
    files: &[PAGE, "calibration.json", "errors.glb"],
};

/// Opens the report directory `dir` (`--report`) before the calibration: new, empty or holding a
/// calibration report of ours (its `report.html`); see [`Kind::open`].
pub fn open(dir: &Path) -> Result<ReportDir> {
    KIND.open(dir)
}

/// Writes every file of the report of the calibration whose document is `doc` into `dir`, each
/// whole.
pub fn write(dir: ReportDir, setup: &Setup, doc: &Document) -> Result<()> {
    let figures = report::draw(&stiffid_figures::calibrate::figures(
        &serde_json::to_value(doc)?,
    )?)?;
    let text = json(doc)?;
    let scene = stiffid::app::calibrate::scene::scene(setup, &text)?;
    let html = KIND.page(&format!("stiffid calibration: {}", doc.setup), |w| {
        compose(w, doc, &figures, &scene)
    });
    let files = vec![
        (PAGE.into(), html.into_bytes()),
        (KIND.files[1].into(), text.into_bytes()),
        (KIND.files[2].into(), glb::glb(&scene)),
    ];
    report::write(dir, files, figures)
}

fn compose(w: &mut dyn Writer, doc: &Document, figures: &[Figure], scene: &Scene) {
    w.heading(1, &format!("Robot calibration: {}", doc.setup));
    w.paragraph(&format!(
        "Readings `{}` ({} fitted, in the {} frame); joint errors `{}`, gravity terms `{}`. The fit stopped: {} after {} iterations.",
        doc.data, doc.readings, doc.measured_in, doc.geometry, doc.gravity, doc.stop_reason, doc.iterations
    ));
    let mut summary = format!(
        "RMS error of the fitted readings: {} mm with the nominal robot ({}), {} mm calibrated; the noise estimated from the residuals is {} mm per coordinate",
        num(mm(doc.nominal_rms)),
        match doc.measured_in {
            "base" => "in the base frame, nothing registered",
            _ => "the tracker registered on them",
        },
        num(mm(doc.residual_rms)),
        num(mm(doc.noise_std))
    );
    if let Some(r) = doc.noise_ratio {
        summary += &format!(", {} times the setup's tracker noise", num(r));
    }
    summary.push('.');
    for v in [&doc.validation, &doc.cross_validation]
        .into_iter()
        .flatten()
    {
        summary += &format!(
            " Held out ({}): RMS {} mm (max {} mm), nominal {} mm.",
            v.data,
            num(mm(v.rms)),
            num(mm(v.max)),
            num(mm(v.nominal_rms))
        );
    }
    w.paragraph(&summary);
    for warning in doc.warnings {
        w.paragraph(&format!("Warning: {}", warning.message));
    }
    if let Some(l) = &doc.ladder {
        ladder_section(w, l);
    }
    w.heading(2, "Error per posture and measuring point, before and after");
    if let Some(f) = find(figures, "errors") {
        w.figure(f);
    }
    w.heading(2, "The errors in 3D");
    w.paragraph("The robot at each fitted posture with each measuring point's error before the calibration (the nominal robot) and after it, magnified (the factor in the legend).");
    w.scene(scene, KIND.files[2]);
    w.heading(2, "Residuals against the noise");
    if let Some(f) = find(figures, "residuals") {
        w.figure(f);
    }
    w.heading(2, "The parameters with their intervals");
    w.paragraph(&format!(
        "{} parameters identified (the rank of the identification Jacobian){}.",
        doc.rank,
        doc.condition
            .map_or(String::new(), |c| format!(", condition number {}", num(c)))
    ));
    for f in figures.iter().filter(|f| f.name.starts_with("parameters_")) {
        w.figure(f);
    }
    w.table(&parameters_table(doc));
    w.heading(2, "Merged parameters");
    match doc.merged.is_empty() {
        true => w.paragraph("None: the readings determine every parameter of the error model."),
        false => {
            w.paragraph("The readings do not separate these parameters from the identified ones: each is left at its nominal value and its effect is carried by the parameters named.");
            let items: Vec<String> = (doc.merged.iter())
                .map(|m| format!("`{}`: {}.", m.name, m.reason))
                .collect();
            w.list(&items);
        }
    }
    if !doc.correlations.is_empty() {
        let items: Vec<String> = (doc.correlations.iter())
            .map(|c| format!("`{}` and `{}`: correlation {:.3}", c.a, c.b, c.rho))
            .collect();
        w.paragraph("Identified parameters correlated above 0.9 (their sum or difference is better determined than each):");
        w.list(&items);
    }
    w.heading(2, "Every reading");
    w.table(&errors_table(doc));
    w.paragraph("Files: calibration.json (the calibrate document this page renders), errors.glb (the 3D scene), figures/ (SVG and PNG).");
}

/// The ladder of models: each rung's held-out figure and why it was skipped, the chosen one's
/// beside the geometry's, the region where the spread was judged.
fn ladder_section(w: &mut dyn Writer, l: &stiffid::app::calibrate::document::LadderDocument) {
    w.heading(2, "The model chosen");
    let geometry = l.rungs.first().and_then(|r| r.held_out_rms_mm);
    let chosen = l.rungs.get(l.chosen).and_then(|r| r.held_out_rms_mm);
    let text = match (l.folds, geometry, chosen) {
        (0, _, _) => "Too few postures to choose a model: the first rung is fitted.".to_string(),
        (k, Some(g), Some(c)) => format!(
            "Each model predicts {k} groups of postures from the others; the simplest within one standard error of the best held-out error, and below every simpler model's, is fitted (marked). The chosen model: {} mm RMS held out, against {} mm for the geometry alone (no gravity terms, no maps).",
            num(c),
            num(g)
        ),
        (k, _, _) => format!("Each model predicts {k} groups of postures from the others."),
    };
    w.paragraph(&text);
    let region: Vec<String> = (l.region_lower_deg.iter().zip(&l.region_upper_deg))
        .enumerate()
        .map(|(j, (a, b))| format!("joint {}: {} to {} deg", j + 1, num(*a), num(*b)))
        .collect();
    w.paragraph(&format!(
        "A gravity model's spread is judged where the robot is used (its postures, held-out and test postures, with a margin): {}.",
        region.join(", ")
    ));
    let header = [
        "",
        "gravity",
        "maps",
        "held out, mm",
        "spread, mm",
        "skipped",
    ]
    .map(String::from)
    .to_vec();
    let rows = (l.rungs.iter().enumerate())
        .map(|(i, r)| {
            vec![
                if i == l.chosen { "chosen" } else { "" }.into(),
                r.gravity.to_string(),
                if r.maps { "yes" } else { "no" }.into(),
                r.held_out_rms_mm.map_or("-".into(), num),
                r.workspace_sd_mm.map_or("-".into(), num),
                r.skipped.clone().unwrap_or_default(),
            ]
        })
        .collect();
    w.table(&Table { header, rows });
}

/// The before and after error of every reading.
fn errors_table(doc: &Document) -> Table {
    let header = ["set", "posture", "point", "before, mm", "after, mm"]
        .map(String::from)
        .to_vec();
    let rows = (doc.errors.iter())
        .map(|e| {
            vec![
                e.set.to_string(),
                e.posture.to_string(),
                e.point_name.clone(),
                format!("{:.4}", mm(e.before_norm)),
                format!("{:.4}", mm(e.after_norm)),
            ]
        })
        .collect();
    Table { header, rows }
}

/// Every parameter: nominal, fitted, standard deviation and 95% interval.
fn parameters_table(doc: &Document) -> Table {
    let header = [
        "parameter",
        "unit",
        "nominal",
        "fitted",
        "sd",
        "95% interval",
        "identified",
    ]
    .map(String::from)
    .to_vec();
    let rows = (doc.parameters.iter())
        .map(|p| {
            vec![
                p.name.clone(),
                p.unit.to_string(),
                num(p.nominal),
                num(p.value),
                match p.inseparable_from.is_empty() {
                    true => p.sd.map_or("-".into(), num),
                    false => format!("inseparable from {}", p.inseparable_from.join(", ")),
                },
                match (p.sd, p.inseparable_from.is_empty()) {
                    (Some(s), true) => {
                        let ends = apart(&[p.value - 1.96 * s, p.value + 1.96 * s], 4);
                        format!("{} to {}", ends[0], ends[1])
                    }
                    _ => "-".into(),
                },
                if p.identified { "yes" } else { "merged" }.into(),
            ]
        })
        .collect();
    Table { header, rows }
}
