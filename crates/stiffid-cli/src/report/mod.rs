//! The report of `stiffid reproduce`: `report.html` (self-contained, figures inline as SVG),
//! `report.md`, `summary.json`, `deviation_rates.csv`, one postures CSV per group and `figures/`
//! (SVG and PNG).

pub mod calibration;
pub mod campaign;
pub mod compensation;
mod content;
pub mod document;
pub mod figures;
pub mod html;
pub mod identification;
pub mod markdown;
pub mod plan;
pub mod summary;
pub mod tables;

use crate::output::ReportDir;
use anyhow::Result;
use figures::Figure;
use std::path::Path;
use stiffid::app::reproduce::Report;
use stiffid::app::simulate::document::deviation_csv;
use stiffid::internal::io::postures;

pub use stiffid_figures::reproduce::{criteria_values, CRITERIA};

/// Opens the report directory `dir` (given with `option`) before the computation (see
/// [`ReportDir::prepare`]): a non-empty directory only if it holds an earlier report of
/// `generator` (its `summary.json`), or with `force` (`None`: no `--force` option); `holds` names the files the report writes,
/// none of which may be an input.
pub fn open(
    dir: &Path,
    option: &str,
    force: Option<bool>,
    generator: &str,
    holds: &dyn Fn(&Path) -> bool,
) -> Result<ReportDir> {
    let ours =
        |rel: &Path| holds(rel) && (!rel.starts_with("figures") || figures::is_ours(dir, rel));
    ReportDir::prepare(dir, option, force, &ours, &|d| {
        summary::is_ours(&d.join("summary.json"), generator)
    })
}

/// Whether the study's report writes the file `rel` (relative to its directory).
pub fn holds(rel: &Path) -> bool {
    let name = rel.to_string_lossy();
    FILES.contains(&name.as_ref())
        || rel.starts_with("figures")
        || (name.starts_with("group") && name.ends_with(".csv"))
}

/// The fixed files of a report (besides one postures CSV per group and `figures/`).
const FILES: [&str; 4] = [
    "summary.json",
    "deviation_rates.csv",
    "report.md",
    "report.html",
];

/// Writes every file of the report into `dir`, each file whole; `summary.json` first, so the
/// directory is recognisably ours from then on.
pub fn write(dir: ReportDir, report: &Report, figures: &[Figure]) -> Result<()> {
    let study = &report.study;
    dir.write(FILES[0], summary::json(report)?.as_bytes())?;
    let names: Vec<String> = study.groups.iter().map(|g| g.name.clone()).collect();
    let sims: Vec<_> = study.groups.iter().map(|g| g.simulation.clone()).collect();
    let mut texts: Vec<(String, String)> = study
        .groups
        .iter()
        .map(|g| (format!("{}.csv", g.name), postures::to_csv(&g.postures)))
        .collect();
    texts.push((
        FILES[1].into(),
        deviation_csv(&names, &sims, &study.setup.noise().levels),
    ));
    texts.push((FILES[2].into(), markdown::report(report, figures)));
    texts.push((FILES[3].into(), html::report(report, figures)));
    let mut files = figures::files(figures);
    files.extend(
        texts
            .iter()
            .map(|(rel, text)| (rel.clone(), text.as_bytes())),
    );
    dir.write_all(&files)?;
    dir.finish()
}
