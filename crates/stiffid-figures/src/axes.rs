//! The chart every line figure of a report draws on: a caption, `x` and `y` ranges, the axes
//! named, the `y` labels in short numbers, no light grid lines.

use crate::{failed, short};
use anyhow::Result;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::ops::Range;

/// The axes of a line chart: what each says and how the `x` labels read.
pub struct Axes<'a> {
    /// The chart's caption.
    pub caption: &'a str,
    /// The `x` range.
    pub x: Range<f64>,
    /// The `y` range.
    pub y: Range<f64>,
    /// The `x` axis' name.
    pub x_desc: &'a str,
    /// The `y` axis' name.
    pub y_desc: &'a str,
    /// Each `x` label's text.
    pub x_label: &'a dyn Fn(&f64) -> String,
}

/// A chart on `root` with `axes` drawn.
pub fn line_chart<'a, DB: DrawingBackend>(
    root: &'a DrawingArea<DB, Shift>,
    axes: &Axes,
) -> Result<ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>> {
    let mut chart = ChartBuilder::on(root)
        .caption(axes.caption, ("sans-serif", 22))
        .margin(14)
        .x_label_area_size(40)
        .y_label_area_size(64)
        .build_cartesian_2d(axes.x.clone(), axes.y.clone())
        .map_err(failed)?;
    chart
        .configure_mesh()
        .x_desc(axes.x_desc)
        .y_desc(axes.y_desc)
        .y_label_formatter(&|y| short(*y))
        .x_label_formatter(axes.x_label)
        .label_style(("sans-serif", 14))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(failed)?;
    Ok(chart)
}

/// An `x` label of a whole number: `3`.
pub fn whole(x: &f64) -> String {
    format!("{x:.0}")
}
