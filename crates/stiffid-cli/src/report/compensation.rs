//! The report of `stiffid compensate --report DIR`: `report.html` (self-contained, figures inline
//! as SVG), `summary.json` (what `--json` prints), `compensation.csv` (what `--out` holds) and
//! `figures/` (SVG and PNG).

use super::figures::{self, Figure};
use super::html::{page, Writer};
use super::tables::{num, Table};
use crate::output::{Part, ReportDir};
use anyhow::Result;
use serde_json::Value;
use std::path::Path;
use stiffid::compensate::Compensated;
use stiffid::Setup;

/// The value of the `generator` key of `summary.json` that marks a compensation report.
pub const GENERATOR: &str = "stiffid compensate";

/// The fixed files of the report (besides `figures/`).
const FILES: [&str; 3] = ["summary.json", "compensation.csv", "report.html"];

/// Whether the report writes the file `rel` (relative to its directory).
pub fn holds(rel: &Path) -> bool {
    FILES.iter().any(|f| rel == Path::new(f)) || rel.starts_with("figures")
}

/// What the report shows of a streamed compensation: a sample of the points (index, result) for
/// the figures, the ten largest deflections, the number of points, the CSV written (`--out`),
/// the parts of the JSON document (`--json`) and the document without its points.
pub struct View<'a> {
    /// Every k-th point.
    pub sample: &'a [(usize, Compensated)],
    /// The ten largest deflections, largest first.
    pub largest: &'a [(usize, Compensated)],
    /// Points of the path.
    pub points: usize,
    /// The CSV of every point.
    pub csv: &'a Path,
    /// The parts of `summary.json`.
    pub summary: &'a [Part<'a>],
    /// The document without its points.
    pub document: &'a Value,
}

/// Writes every file of the report into `dir`, each whole; `summary.json` first, so the
/// directory is recognisably ours from then on.
pub fn write(dir: ReportDir, setup: &Setup, view: &View) -> Result<()> {
    let sample: Vec<Compensated> = view.sample.iter().map(|(_, c)| c.clone()).collect();
    let figures = [
        figures::path::deflection(&sample)?,
        figures::path::path(setup, &sample)?,
    ];
    dir.write_parts(FILES[0], view.summary)?;
    dir.write_parts(FILES[1], &[Part::File(view.csv)])?;
    for f in &figures {
        dir.write(&format!("figures/{}.svg", f.name), f.svg.as_bytes())?;
        dir.write(&format!("figures/{}.png", f.name), &f.png)?;
    }
    let html = page(
        &format!("stiffid compensation: {}", setup.name()),
        GENERATOR,
        |w| compose(w, setup, view, &figures),
    );
    dir.write(FILES[2], html.as_bytes())?;
    dir.finish()
}

fn compose(w: &mut dyn Writer, setup: &Setup, view: &View, figures: &[Figure]) {
    let document = view.document;
    let s = &document["summary"];
    let f = |key: &str| s[key].as_f64().unwrap_or(f64::NAN);
    w.heading(1, "Deflection compensation of a machining path");
    w.paragraph(&format!(
        "Path `{}` ({} points) on the setup `{}` ({}), joint stiffness from `{}`. Each point's TCP deflection under its wrench (Zhang et al. 2021, Eq. 4-6) and the compensated axis angles that put the loaded TCP where the unloaded robot puts it at the nominal posture.",
        document["path"].as_str().unwrap_or(""),
        view.points,
        setup.name(),
        setup.robot().name,
        document["stiffness"].as_str().unwrap_or(""),
    ));
    let mut items = vec![
        format!(
            "Largest TCP deflection {} mm (line {}), mean {} mm; largest tool rotation {} mrad.",
            num(f("max_deflection_mm")),
            s["max_deflection_line"],
            num(f("mean_deflection_mm")),
            num(f("max_rotation_mrad"))
        ),
        format!(
            "After compensation: residual at most {:.2e} um and {:.2e} urad (required 0.1 um and 1 urad), at most {} Newton steps per point.",
            f("max_residual_um"),
            f("max_residual_urad"),
            s["max_iterations"]
        ),
    ];
    if let Some(free) = s["free_tool_axis"].as_object() {
        let g = |k: &str| free[k].as_f64().unwrap_or(f64::NAN);
        items.push(format!(
            "Free tool axis: sum of the TCP deflections {} mm before, {} mm after the optimisation of the rotation about tool z.",
            num(g("sum_deflection_before_mm")),
            num(g("sum_deflection_after_mm"))
        ));
    }
    if document["has_covariance"] != true {
        items.push("The stiffness file has no compliance covariance: no uncertainty band (run `stiffid identify --out` to get one).".into());
    }
    w.list(&items);
    for fig in figures {
        w.figure(fig);
    }
    w.heading(2, "The ten largest deflections");
    if view.sample.len() < view.points {
        w.paragraph(&format!(
            "The figures show every {}th of the {} points.",
            view.sample.get(1).map_or(1, |s| s.0),
            view.points
        ));
    }
    w.table(&largest(view.largest));
    w.paragraph("Every point, every column: `compensation.csv` (the same as `--out`) and `summary.json` (the same as `--json`).");
}

fn largest(largest: &[(usize, Compensated)]) -> Table {
    let norm = |c: &Compensated| c.deflection.fixed_rows::<3>(0).norm() * 1e3;
    Table {
        header: [
            "point",
            "|d| mm",
            "std of |d| mm",
            "rotation mrad",
            "residual um",
            "q_c - q, deg (axes 1-6)",
        ]
        .map(String::from)
        .to_vec(),
        rows: largest
            .iter()
            .map(|(i, c)| {
                let dq = (c.q_compensated - c.q).map(f64::to_degrees);
                vec![
                    (i + 1).to_string(),
                    num(norm(c)),
                    c.translation_norm_std.map_or("-".into(), |s| num(s * 1e3)),
                    num(c.deflection.fixed_rows::<3>(3).norm() * 1e3),
                    format!("{:.2e}", c.residual_position * 1e6),
                    dq.iter()
                        .map(|v| format!("{v:.4}"))
                        .collect::<Vec<_>>()
                        .join(", "),
                ]
            })
            .collect(),
    }
}
