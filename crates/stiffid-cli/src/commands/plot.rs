//! `stiffid plot`: side and top views of every posture of a postures file, SVG and PNG.

use crate::output::write_atomic;
use crate::report::{check_dir, figures};
use crate::{load, postures};
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};

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
    /// Write into --out even if it holds other files.
    #[arg(long)]
    force: bool,
}

/// Whether every file in `dir` is a figure `stiffid plot` writes.
fn only_our_figures(dir: &Path) -> bool {
    std::fs::read_dir(dir).is_ok_and(|entries| {
        entries.flatten().all(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            let stem = name
                .strip_suffix(".svg")
                .or_else(|| name.strip_suffix(".png"))
                .unwrap_or("");
            stem == "postures"
                || stem
                    .strip_prefix("posture_")
                    .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
        })
    })
}

/// Draws the postures and writes `postures.svg/.png` and `posture_NN.svg/.png`.
pub fn run(args: &Args) -> Result<()> {
    let setup = load::setup(&args.setup)?;
    let group = postures::read(&args.postures, &setup.robot)?;
    check_dir(
        &args.out,
        args.force,
        "a directory of stiffid plot figures; choose another directory or pass --force",
        only_our_figures,
    )?;
    let figures = figures::postures::each(&setup, &group)?;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("{}: cannot create", args.out.display()))?;
    for f in &figures {
        let stem = args.out.join(&f.name);
        write_atomic(&stem.with_extension("svg"), f.svg.as_bytes())?;
        write_atomic(&stem.with_extension("png"), &f.png)?;
    }
    println!(
        "{} figures (SVG and PNG) of {} postures written to {}",
        figures.len(),
        group.len(),
        args.out.display()
    );
    Ok(())
}
