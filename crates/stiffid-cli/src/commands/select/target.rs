//! `select --target-pct X`: the figure of the group sizes tried and their text.

use crate::output::OutFile;
use crate::report::figures::{render, Png};
use anyhow::Result;
use std::path::Path;
use stiffid::internal::design::target::TargetOutcome;

/// The figure files beside `--out` without `--report` (`OUT.target.svg`, `OUT.target.png`),
/// checked before the search.
pub fn files(out: &Path) -> Result<[OutFile; 2]> {
    let stem = out.with_extension("");
    Ok([
        OutFile::prepare(&stem.with_extension("target.svg"), "--out (target figure)")?,
        OutFile::prepare(&stem.with_extension("target.png"), "--out (target figure)")?,
    ])
}

/// Writes the figure of the group sizes tried into the [`files`].
pub fn write_figure(files: &[OutFile; 2], outcome: &TargetOutcome) -> Result<()> {
    let f = render(&stiffid_figures::target::figure(outcome), Png::Also)?;
    files[0].write(f.svg.as_bytes())?;
    files[1].write(f.png.as_deref().unwrap_or_default())
}

/// The group sizes tried and their worst joint, in words.
pub fn text(t: &TargetOutcome) -> String {
    let mut s = format!(
        "smallest group predicting at most {} % on every joint (noise level multiple 1):\n",
        t.target_pct
    );
    s += &format!(
        "{:>8}  {:>11}  {:>6}\n",
        "postures", "worst joint", "rate %"
    );
    for step in &t.steps {
        let (j, w) = step.worst_joint();
        s += &format!("{:>8}  {:>11}  {:>6.3}\n", step.postures.len(), j + 1, w);
    }
    s
}
