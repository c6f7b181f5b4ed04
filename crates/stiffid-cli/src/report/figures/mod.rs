//! The report's figures ([`stiffid_figures`]), each drawn into SVG (inline in the HTML) and PNG.

pub mod map;

use anyhow::{Context, Result};
use rayon::prelude::*;
use stiffid_figures::Drawing;

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

/// Draws `drawing` into SVG and PNG.
pub fn render(drawing: &Drawing) -> Result<Figure> {
    let name = &drawing.name;
    Ok(Figure {
        name: name.clone(),
        caption: drawing.caption.clone(),
        svg: drawing.plot.svg()?,
        png: drawing.plot.png().with_context(|| format!("figure {name}"))?,
    })
}

/// Every drawing of `drawings` rendered, in order; drawn in parallel.
pub fn all(drawings: &[Drawing]) -> Result<Vec<Figure>> {
    drawings.par_iter().map(render).collect()
}

/// A shared figure ([`stiffid_figures`]) drawn into SVG and PNG.
pub fn shared(f: &stiffid_figures::Figure) -> Result<Figure> {
    render(&Drawing::new(&f.name, &f.caption, &f.chart))
}
