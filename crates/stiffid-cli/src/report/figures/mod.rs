//! The report's figures ([`stiffid_figures`]), each drawn into SVG (inline in the HTML page and
//! in `figures/`) and, where a Markdown file or a figure command needs one, PNG.

pub mod map;

use anyhow::{Context, Result};
use rayon::prelude::*;
use std::path::Path;
use stiffid_figures::Drawing;

/// A rendered figure.
pub struct Figure {
    /// File stem in `figures/` (`<name>.svg`, `<name>.png`).
    pub name: String,
    /// Caption.
    pub caption: String,
    /// The SVG document.
    pub svg: String,
    /// The PNG image, when asked for ([`Png::Also`]).
    pub png: Option<Vec<u8>>,
}

/// Whether a figure is also drawn as PNG: for the reproduce report's Markdown and the figure
/// commands (`plot`, `select --target-pct` without `--report`), never only for a page that shows
/// its SVG inline (the bitmap and its encoding were a quarter of a report's time).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Png {
    /// SVG only.
    No,
    /// SVG and PNG.
    Also,
}

/// Draws `drawing` into SVG and, if `png` says so, PNG.
pub fn render(drawing: &Drawing, png: Png) -> Result<Figure> {
    let name = &drawing.name;
    let png = match png {
        Png::Also => Some(
            drawing
                .plot
                .png()
                .with_context(|| format!("figure {name}"))?,
        ),
        Png::No => None,
    };
    Ok(Figure {
        name: name.clone(),
        caption: drawing.caption.clone(),
        svg: drawing.plot.svg()?,
        png,
    })
}

/// Every drawing of `drawings` rendered ([`render`]), in order; drawn in parallel.
pub fn all(drawings: &[Drawing], png: Png) -> Result<Vec<Figure>> {
    drawings.par_iter().map(|d| render(d, png)).collect()
}

/// A shared figure ([`stiffid_figures`]) drawn into SVG only (a report page's).
pub fn shared(f: &stiffid_figures::Figure) -> Result<Figure> {
    render(&Drawing::new(&f.name, &f.caption, &f.chart), Png::No)
}

/// The files of `figures` in `figures/`: each SVG and each PNG drawn, paths relative to the
/// report's directory.
pub fn files(figures: &[Figure]) -> Vec<(String, &[u8])> {
    let mut out: Vec<(String, &[u8])> = Vec::new();
    for f in figures {
        out.push((format!("figures/{}.svg", f.name), f.svg.as_bytes()));
        if let Some(png) = &f.png {
            out.push((format!("figures/{}.png", f.name), png));
        }
    }
    out
}

/// Whether `rel` (a path in the report directory `dir`) is a figure stiffid wrote: an SVG that
/// carries [`stiffid_figures::MARK`], or a PNG beside such an SVG of the same stem. A user's file
/// of a figure's name is not: it is never removed, and replaced only with `--force`.
pub fn is_ours(dir: &Path, rel: &Path) -> bool {
    let svg = match rel.extension().and_then(|e| e.to_str()) {
        Some("svg") => rel.to_path_buf(),
        Some("png") => rel.with_extension("svg"),
        _ => return false,
    };
    let mut head = [0u8; 256];
    stiffid::internal::io::input::open(&dir.join(svg))
        .and_then(|mut f| std::io::Read::read(&mut f, &mut head))
        .is_ok_and(|n| String::from_utf8_lossy(&head[..n]).contains(stiffid_figures::MARK))
}
