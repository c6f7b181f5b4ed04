//! `stiffid plot`: side and top views of every posture of a postures file, SVG and PNG.

use crate::load;
use crate::output::{self, ReportDir};
use crate::progress::Bars;
use crate::report::figures::{self, Png};
use anyhow::Result;
use std::path::{Path, PathBuf};
use stiffid_core::Progress;

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

/// The comment every SVG figure of `stiffid plot` carries after its `<svg>` tag: what tells a
/// figure of ours from a user's file of the same name, which the command never replaces or
/// removes without `--force`, nor removes with it.
const MARK: &str = "<!-- drawn by stiffid plot -->";

/// Whether every file in `dir` is a figure `stiffid plot` wrote.
fn only_our_figures(dir: &Path) -> bool {
    std::fs::read_dir(dir).is_ok_and(|entries| {
        entries
            .flatten()
            .all(|e| is_our_figure(dir, Path::new(&e.file_name())))
    })
}

/// Whether `rel` in `dir` is a figure `stiffid plot` wrote: named as one, and an SVG that
/// carries [`MARK`], or a PNG beside such an SVG of the same name.
fn is_our_figure(dir: &Path, rel: &Path) -> bool {
    let name = rel.to_string_lossy();
    let named = |stem: &str| {
        stem == "postures"
            || stem
                .strip_prefix("posture_")
                .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
    };
    let carries_mark = |svg: &Path| {
        let mut head = [0u8; 256];
        stiffid_core::io::input::open(svg)
            .and_then(|mut f| std::io::Read::read(&mut f, &mut head))
            .is_ok_and(|n| String::from_utf8_lossy(&head[..n]).contains(MARK))
    };
    match (name.strip_suffix(".svg"), name.strip_suffix(".png")) {
        (Some(stem), _) => named(stem) && carries_mark(&dir.join(rel)),
        (_, Some(stem)) => named(stem) && carries_mark(&dir.join(format!("{stem}.svg"))),
        _ => false,
    }
}

/// `svg` with [`MARK`] after its `<svg ...>` tag.
fn marked(svg: &str) -> String {
    match svg.find(">\n") {
        Some(end) => format!("{}\n{MARK}{}", &svg[..=end], &svg[end + 1..]),
        None => format!("{MARK}\n{svg}"),
    }
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
                dir.write(&format!("{}.svg", f.name), marked(&f.svg).as_bytes())?;
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
