//! The figures of stiffid's reports, drawn with plotters (pure Rust) onto any of its backends:
//! what the command writes into its reports (SVG inline in the HTML, PNG beside the reproduce
//! report's Markdown) and what the Python package returns as SVG strings. The calibration's and
//! the identification's figures are built from their jobs' JSON documents ([`calibrate`],
//! [`identify`]; the documents' schemas in `docs/schemas`); those of a plan ([`postures`],
//! [`target`]), a compensation ([`compensate`]) and the paper's study ([`reproduce`]) from the
//! library's objects the jobs return, as [`Drawing`]s drawn when a front end asks. Both front
//! ends draw the same figure from the same document or objects.
//!
//! Why a crate of its own: the library (`stiffid`) computes and owns the documents and draws
//! nothing; the command and the Python package both render, and one renderer serves both.

#![deny(missing_docs)]

pub mod axes;
pub mod calibrate;
pub mod chart;
pub mod compensate;
pub mod drawing;
pub mod identify;
pub mod postures;
pub mod reproduce;
pub mod target;

use anyhow::{anyhow, bail, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};
use std::sync::OnceLock;

pub use chart::{Chart, Mark};
pub use drawing::{png, Draw, Drawing};

/// DejaVu Sans (Bitstream Vera license, `assets/DejaVuSans-LICENSE.txt`): the font text is
/// measured and drawn with.
const FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");

/// One colour per series, in order (colour-blind-safe Okabe-Ito hues).
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(0, 0, 0),
    RGBColor(230, 159, 0),
    RGBColor(0, 114, 178),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(213, 94, 0),
    RGBColor(86, 180, 233),
    RGBColor(170, 170, 0),
];

/// The colour of series `g`.
pub fn colour(g: usize) -> RGBColor {
    PALETTE[g % PALETTE.len()]
}

/// Something drawable on any plotters backend.
pub trait Plot {
    /// Width and height, pixels.
    fn size(&self) -> (u32, u32);
    /// Draws onto the whole area.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>;
}

impl<P: Plot> Plot for &P {
    fn size(&self) -> (u32, u32) {
        (*self).size()
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        (*self).draw(root)
    }
}

/// A figure to draw: its file stem, caption and chart.
pub struct Figure {
    /// File stem (`<name>.svg`).
    pub name: String,
    /// Caption, one sentence or two.
    pub caption: String,
    /// What to draw.
    pub chart: Chart,
}

/// Plotters errors as anyhow errors.
pub fn failed<E: std::fmt::Debug>(e: E) -> anyhow::Error {
    anyhow!("drawing a figure failed: {e:?}")
}

/// Registers the bundled font as `sans-serif` (once per process), which every backend measures
/// text with.
///
/// # Errors
/// When the bundled font does not parse.
pub fn fonts() -> Result<()> {
    static FONTS: OnceLock<bool> = OnceLock::new();
    let registered = FONTS.get_or_init(|| {
        [
            FontStyle::Normal,
            FontStyle::Bold,
            FontStyle::Italic,
            FontStyle::Oblique,
        ]
        .into_iter()
        .all(|style| register_font("sans-serif", style, FONT).is_ok())
    });
    if !registered {
        bail!("the bundled font assets/DejaVuSans.ttf does not parse");
    }
    Ok(())
}

/// The comment every SVG figure carries on the line after its `<svg>` tag: what tells a figure
/// stiffid wrote from a user's file of the same name in a report's directory.
pub const MARK: &str = "<!-- drawn by stiffid -->";

/// `plot` as an SVG document, [`MARK`] after its `<svg>` tag.
///
/// # Errors
/// Those of [`fonts`] and of drawing.
pub fn svg(plot: &impl Plot) -> Result<String> {
    fonts()?;
    let (w, h) = plot.size();
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(failed)?;
        plot.draw(&root)?;
        root.present().map_err(failed)?;
    }
    let tag = svg.find('\n').map_or(svg.len(), |end| end + 1);
    svg.insert_str(tag, &format!("{MARK}\n"));
    Ok(svg)
}

/// `v` with 3 significant digits, no trailing zeros (axis labels).
pub fn short(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let decimals = (2 - v.abs().log10().floor() as i32).max(0) as usize;
    let s = format!("{v:.decimals$}");
    match s.contains('.') {
        true => s.trim_end_matches('0').trim_end_matches('.').to_string(),
        false => s,
    }
}
