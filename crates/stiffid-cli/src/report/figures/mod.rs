//! The report's figures, each drawn once through plotters into SVG (inline in the HTML) and PNG.

pub mod chart;
pub mod criteria;
pub mod deviation;
pub mod machining;
pub mod path;
pub mod postures;
pub mod table;
pub mod target;

use anyhow::{anyhow, bail, Context, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};
use rayon::prelude::*;
use std::sync::OnceLock;
use stiffid::study::Study;

/// DejaVu Sans (Bitstream Vera license, `assets/DejaVuSans-LICENSE.txt`): the PNG text font.
const FONT: &[u8] = include_bytes!("../../../assets/DejaVuSans.ttf");

/// One colour per group, in group order (colour-blind-safe Okabe-Ito hues).
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

/// The colour of group `g`.
pub fn colour(g: usize) -> RGBColor {
    PALETTE[g % PALETTE.len()]
}

/// A rendered figure.
pub struct Figure {
    /// File stem in `figures/` (`<name>.svg`, `<name>.png`).
    pub name: String,
    /// Caption.
    pub caption: String,
    /// The SVG document.
    pub svg: String,
    /// The PNG image.
    pub png: Vec<u8>,
}

/// Something drawable on any plotters backend.
pub trait Plot {
    /// Width and height, pixels.
    fn size(&self) -> (u32, u32);
    /// Draws onto the whole area.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>;
}

/// Plotters errors as anyhow errors.
pub fn failed<E: std::fmt::Debug>(e: E) -> anyhow::Error {
    anyhow!("drawing a figure failed: {e:?}")
}

/// Draws `plot` into SVG and PNG.
pub fn render(name: &str, caption: &str, plot: &impl Plot) -> Result<Figure> {
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
    let (w, h) = plot.size();
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(failed)?;
        plot.draw(&root)?;
        root.present().map_err(failed)?;
    }
    let mut rgb = vec![255u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(failed)?;
        plot.draw(&root)?;
        root.present().map_err(failed)?;
    }
    Ok(Figure {
        name: name.to_string(),
        caption: caption.to_string(),
        svg,
        png: encode_png(&rgb, w, h).with_context(|| format!("figure {name}"))?,
    })
}

/// The PNG of an RGB image: fast compression with adaptive row filters. On the report's figures
/// that is 40x faster than `Best` (then a fifth of `stiffid reproduce`) for files 1.4x larger.
fn encode_png(rgb: &[u8], w: u32, h: u32) -> Result<Vec<u8>> {
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, w, h);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Fast);
    encoder.set_adaptive_filter(png::AdaptiveFilterType::Adaptive);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(rgb)?;
    writer.finish()?;
    Ok(out)
}

/// Every figure of the report, in report order; drawn in parallel.
pub fn all(study: &Study) -> Result<Vec<Figure>> {
    (0..3 + study.groups.len())
        .into_par_iter()
        .map(|i| match i {
            0 => deviation::figure(study),
            1 => table::figure(study),
            2 => criteria::figure(study),
            _ => postures::figure(study, i - 3),
        })
        .collect()
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
