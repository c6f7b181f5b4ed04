//! The report of `stiffid compensate --report DIR`: `report.html` (self-contained, figures inline
//! as SVG), `summary.json` (what `--json` prints), `compensation.csv` (the CSV of every point) and
//! `figures/` (SVG and PNG). It reads the job's document ([`Document`]) and, for the figures, the
//! sample of points the job kept ([`Report::summary`]).

use super::figures::{self, Figure, Png};
use super::html::{page, Writer};
use super::tables::{num, Table};
use crate::output::{Fill, ReportDir};
use anyhow::Result;
use std::path::Path;
use stiffid::app::compensate::document::GENERATOR;
use stiffid::app::compensate::document::{Document, SummaryDocument};
use stiffid::app::compensate::{Report, Segment};
use stiffid::app::document::mm;
use stiffid::internal::common::words::count;
use stiffid::internal::machining::compensate::Compensated;
use stiffid::internal::view::{glb, Scene};
use stiffid::Setup;

/// The fixed files of the report (besides `figures/`).
const FILES: [&str; 4] = [
    "summary.json",
    "compensation.csv",
    "report.html",
    "path.glb",
];

/// The map's CSV (with `--map`).
const MAP_CSV: &str = "map.csv";

/// Whether the report writes the file `rel` (relative to its directory).
pub fn holds(rel: &Path) -> bool {
    FILES.iter().any(|f| rel == Path::new(f))
        || rel == Path::new(MAP_CSV)
        || rel.starts_with("figures")
}

/// What the report shows of a streamed compensation: the job's report (its sample of the points
/// for the figures, the ten largest deflections), the CSV written, what writes the JSON document
/// (`--json`) and the document without its points.
pub struct View<'a> {
    /// The job's report.
    pub report: &'a Report,
    /// The CSV of every point.
    pub csv: &'a Path,
    /// What writes `summary.json`.
    pub summary: Fill<'a>,
    /// The document without its points.
    pub document: &'a Document<'a>,
}

/// Writes every file of the report into `dir`, each whole; `summary.json` first, so the
/// directory is recognisably ours from then on.
pub fn write(dir: ReportDir, setup: &Setup, view: &View) -> Result<()> {
    let sample = stiffid_figures::compensate::sample(view.report);
    let drawings = stiffid_figures::compensate::figures(setup, &sample, view.report);
    let figures = figures::all(&drawings, Png::No)?;
    if let Some(map) = &view.report.map {
        dir.write(MAP_CSV, figures::map::csv(map).as_bytes())?;
    }
    dir.write_with(FILES[0], view.summary)?;
    let csv = |w: &mut dyn std::io::Write| {
        std::io::copy(&mut std::fs::File::open(view.csv)?, w).map(drop)
    };
    dir.write_with(FILES[1], &csv)?;
    dir.write_all(&figures::files(&figures))?;
    let scene = stiffid::app::compensate::scene::scene(setup, &view.document.summary.scene)?;
    let html = page(
        &format!("stiffid compensation: {}", setup.name()),
        GENERATOR,
        |w| compose(w, setup, view, &figures, scene.as_ref()),
    );
    dir.write(FILES[2], html.as_bytes())?;
    if let Some(s) = &scene {
        dir.write(FILES[3], &glb::glb(s))?;
    }
    dir.finish()
}

/// What the error that remains after compensation is made of, in mm.
fn remains(s: &SummaryDocument) -> String {
    let b = &s.budget;
    let parts: Vec<String> = (b.made_of.iter())
        .map(|p| match p.max_mm {
            Some(m) => format!(
                "{} at most {} mm (mean {} mm)",
                p.part.replace('_', " "),
                num(m),
                num(p.mean_mm.unwrap_or(m))
            ),
            None => format!("{} {}", p.part.replace('_', " "), b.no_value(p)),
        })
        .collect();
    let mut text = format!(
        "After compensation the error that remains at {}% is made of: {} (left: the compensation's residual; compensation: the predicted deflection's error; calibration: the calibrated robot's held-out error; force: the process force model's tolerance; model form: the spread over the models the data support). The compensated axis angles reproduce the model itself to {:.2e} um and {:.2e} urad, {} Newton steps per point at most.",
        b.level * 100.0,
        parts.join("; "),
        s.max_residual_position * 1e6,
        s.max_residual_rotation * 1e6,
        s.max_iterations
    );
    if let Some(m) = &b.meets {
        text += &format!(
            " Meets {} mm at {}%: {}.",
            num(m.max_error_mm),
            m.level * 100.0,
            if m.meets { "yes" } else { "no" }
        );
    }
    text
}

fn compose(
    w: &mut dyn Writer,
    setup: &Setup,
    view: &View,
    figures: &[Figure],
    scene: Option<&Scene>,
) {
    let document = view.document;
    let s = &document.summary;
    let points = view.report.summary.points;
    w.heading(1, "Deflection compensation of a machining path");
    w.paragraph(&format!(
        "Path `{}` ({} points) on the setup `{}` ({}), joint stiffness from `{}`. Each point's TCP deflection under its wrench (Zhang et al. 2021, Eq. 4-6) and the compensated axis angles that put the loaded TCP where the unloaded robot puts it at the nominal posture.",
        document.path,
        points,
        setup.name(),
        setup.robot().name(),
        document.stiffness,
    ));
    let mut items = vec![
        format!(
            "Largest TCP deflection {} mm (line {}), mean {} mm; largest tool rotation {} mrad.",
            num(mm(s.max_deflection)),
            s.max_deflection_line,
            num(mm(s.mean_deflection)),
            num(s.max_rotation * 1e3)
        ),
        remains(s),
    ];
    // The summary's sums are any free variable's; the rotation is named only where it was free.
    let rotation = document.free.iter().any(|f| f.variable == "tool-rotation");
    if let (Some(free), true) = (&s.free_tool_axis, rotation) {
        items.push(format!(
            "Free tool axis: sum of the TCP deflections {} mm before, {} mm after the optimisation of the rotation about tool z.",
            num(mm(free.sum_deflection_before)),
            num(mm(free.sum_deflection_after))
        ));
    }
    if let Some(p) = &document.program {
        items.push(format!(
            "Program in {} with the process `{}`: {}; compensated program `{}`.",
            p.language,
            p.process,
            count(p.segments.len(), "segment"),
            p.out
        ));
    }
    let b = &s.budget;
    items.push(match b.max_bound_mm {
        Some(m) => format!(
            "Error bound at {}%: at most {} mm (line {}), mean {} mm{}{}.",
            b.level * 100.0,
            num(m),
            b.max_bound_line.unwrap_or(0),
            b.mean_bound_mm.map_or("-".into(), num),
            b.worst.first().map_or(String::new(), |w| format!(
                ", dominated there by {}",
                w.dominant.replace('_', " ")
            )),
            match b.absent.is_empty() {
                true => String::new(),
                false => format!(" (absent, counted as 0: {})", b.absent.join(", ")),
            }
        ),
        None => format!(
            "Error bound at {}%: infinite (a finite bound needs at least {} held-out calibration errors).",
            b.level * 100.0,
            stiffid::internal::model::prediction::held_out_needed(b.level)
        ),
    });
    if !document.has_covariance {
        items.push("The stiffness file has no compliance covariance: no uncertainty band (run `stiffid identify --out` to get one).".into());
    }
    items.extend(
        document
            .warnings
            .iter()
            .map(|w| format!("Warning: {}", w.message)),
    );
    w.list(&items);
    if let Some(scene) = scene {
        w.heading(2, "The path in the cell");
        w.paragraph("The path coloured by the error predicted to remain after compensation (without a covariance, by the deflection compensated), with the robot at the path's first point and at its largest deflection.");
        w.scene(scene, FILES[3]);
    }
    for fig in figures {
        w.figure(fig);
    }
    if let Some(p) = &document.program {
        w.heading(2, "Force and deflection per segment");
        w.table(&segments(p.segments));
    }
    w.heading(2, "The ten largest deflections");
    let sample = &view.report.summary.sample;
    if sample.len() < points {
        w.paragraph(&format!(
            "The figures show every {}th of the {} points.",
            sample.get(1).map_or(1, |s| s.0),
            points
        ));
    }
    w.table(&largest(&view.report.summary.largest));
    w.paragraph(
        "Every point, every column: `compensation.csv` and `summary.json` (the same as `--json`).",
    );
}

/// The segments' table (at most the first 200 rows; the JSON has them all).
fn segments(segments: &[Segment]) -> Table {
    Table {
        header: [
            "line",
            "operation",
            "points",
            "force N",
            "|d| before mm",
            "remaining after, 2 sd of |d| mm",
            "model residual mm",
        ]
        .map(String::from)
        .to_vec(),
        rows: segments
            .iter()
            .take(200)
            .map(|s| {
                vec![
                    s.line.to_string(),
                    s.operation.clone().unwrap_or_else(|| "-".into()),
                    s.points.to_string(),
                    num(s.force),
                    num(mm(s.deflection_before)),
                    s.deflection_std.map_or("-".into(), |v| num(2.0 * mm(v))),
                    format!("{:.2e}", mm(s.deflection_after)),
                ]
            })
            .collect(),
    }
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
