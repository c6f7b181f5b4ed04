//! What the reports drawn from a job's document share (`calibrate --report`, `identify
//! --report`): the directory, recognised as an earlier report by its page's generator mark; the
//! shared figures ([`stiffid_figures`]) drawn into SVG and PNG; the page and the files written,
//! each whole, their syncs to the disk overlapping.

use super::figures::{self, Figure};
use super::html;
use crate::output::ReportDir;
use anyhow::Result;
use rayon::prelude::*;
use std::path::Path;

/// A report of a job's document: its page's generator mark (`<meta name="generator">`, by which
/// an earlier report is recognised) and its fixed files besides `figures/` (the page is
/// `report.html`).
pub struct Kind {
    /// The generator mark, `stiffid JOB`.
    pub generator: &'static str,
    /// The fixed files, `report.html` among them.
    pub files: &'static [&'static str],
}

/// The page every report of a job's document writes.
pub const PAGE: &str = "report.html";

impl Kind {
    /// Opens the report directory `dir` (`--report`) before the job runs: new, empty or holding
    /// an earlier report of this kind (its page); see [`ReportDir::prepare`].
    ///
    /// # Errors
    /// Those of [`ReportDir::prepare`].
    pub fn open(&self, dir: &Path) -> Result<ReportDir> {
        let holds = |rel: &Path| {
            self.files.iter().any(|f| rel == Path::new(f))
                || (rel.starts_with("figures") && super::figures::is_ours(dir, rel))
        };
        let mark = format!("content=\"{}\"", self.generator);
        ReportDir::prepare(dir, "--report", None, &holds, &|d| {
            stiffid::internal::io::input::open(&d.join(PAGE))
                .ok()
                .and_then(|f| stiffid::internal::io::read_text(PAGE, f).ok())
                .is_some_and(|t| t.contains(&mark))
        })
    }

    /// The page titled `title` whose body `body` writes, marked with this kind's generator.
    pub fn page(&self, title: &str, body: impl FnOnce(&mut dyn html::Writer)) -> String {
        html::page(title, self.generator, body)
    }
}

/// The shared figures `shared` drawn into SVG, in parallel.
///
/// # Errors
/// A figure that cannot be drawn.
pub fn draw(shared: &[stiffid_figures::Figure]) -> Result<Vec<Figure>> {
    shared.par_iter().map(figures::shared).collect()
}

/// The figure named `name`.
pub fn find<'a>(figures: &'a [Figure], name: &str) -> Option<&'a Figure> {
    figures.iter().find(|f| f.name == name)
}

/// Writes `files` (each a path relative to `dir` and its bytes) and every figure's SVG into
/// `figures/`, then ends the report ([`ReportDir::finish`]).
///
/// # Errors
/// A file that cannot be written.
pub fn write(dir: ReportDir, files: Vec<(String, Vec<u8>)>, figures: Vec<Figure>) -> Result<()> {
    dir.write_all(&files)?;
    dir.write_all(&figures::files(&figures))?;
    dir.finish()
}
