//! `stiffid plot`: side and top views of every posture of a postures file, SVG and PNG.

use crate::load;
use crate::output::{self, ReportDir};
use crate::progress::Bars;
use crate::report::figures::{self, Png};
use anyhow::Result;
use std::path::{Path, PathBuf};
use stiffid::Progress;

/// Arguments of `stiffid plot`.
#[derive(clap::Args)]
pub struct Args {
    /// Setup: a built-in name (see `stiffid setups`) or a setup .toml file.
    #[arg(long)]
    setup: String,
    /// Postures file (posture,q1_deg,...,q6_deg).
    #[arg(long)]
    postures: PathBuf,
    /// Directory of the figures (created if missing; an existing one must be empty or hold only
    /// figures of `stiffid plot`, unless --force).
    #[arg(long)]
    out: PathBuf,
    /// Write into --out even if it holds other files (a file named as a figure is replaced; no
    /// file but an earlier figure of `stiffid plot` is removed).
    #[arg(long)]
    force: bool,
}

/// Whether every file in `dir` is a figure `stiffid plot` wrote.
fn only_our_figures(dir: &Path) -> bool {
    std::fs::read_dir(dir).is_ok_and(|entries| {
        entries
            .flatten()
            .all(|e| is_our_figure(dir, Path::new(&e.file_name())))
    })
}

/// Whether `rel` in `dir` is a figure `stiffid plot` wrote: named as one
/// (`postures`, `posture_NN`), and stiffid's ([`figures::is_ours`]).
fn is_our_figure(dir: &Path, rel: &Path) -> bool {
    let stem = rel
        .file_stem()
        .map(|s| s.to_string_lossy())
        .unwrap_or_default();
    let named = stem == "postures"
        || (stem.strip_prefix("posture_"))
            .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()));
    named && figures::is_ours(dir, rel)
}

/// Draws the postures and writes `postures.svg/.png` and `posture_NN.svg/.png`.
pub fn run(args: &Args) -> Result<()> {
    let setup = load::setup(&args.setup)?;
    setup.check_bodies()?;
    let group = load::postures(&args.postures, setup.robot(), None)?;
    let holds = |rel: &Path| is_our_figure(&args.out, rel);
    let dir = ReportDir::prepare(
        &args.out,
        "--out",
        Some(args.force),
        &holds,
        &only_our_figures,
    )?;
    // The figures are drawn at once: a spinner while they are drawn and written.
    let bars = Bars::new(false);
    bars.begin("figures", 0);
    let written = figures::all(&stiffid_figures::postures::each(&setup, &group), Png::Also)
        .and_then(|figures| {
            for f in &figures {
                dir.write(&format!("{}.svg", f.name), f.svg.as_bytes())?;
                if let Some(png) = &f.png {
                    dir.write(&format!("{}.png", f.name), png)?;
                }
            }
            Ok(figures)
        });
    bars.end();
    let figures = written?;
    dir.finish()?;
    output::print(&format!(
        "{} figures (SVG and PNG) of {} postures written to {}\n",
        figures.len(),
        group.len(),
        args.out.display()
    ))
}
