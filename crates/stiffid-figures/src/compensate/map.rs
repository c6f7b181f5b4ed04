//! The figure `map` of `stiffid compensate --map --report`: the error bound of every path point
//! at every rotation about the spindle (or, with `--map track`, every track station), the value
//! chosen drawn on it.

use crate::axes::{line_chart, whole, Axes};
use crate::{failed, Drawing, Plot};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use stiffid_machining::compensate::{Map, MapVariable};

/// Columns drawn at most (every k-th point).
const COLUMNS: usize = 600;

struct Drawn<'a>(&'a Map);

/// The figure `map` of `map`.
pub fn figure(map: &Map) -> Drawing<'_> {
    Drawing::new(
        "map",
        "The error bound (bound_mm, at the budget's level) of every path point at every rotation \
         about the spindle (with --map track, every track station) from the path's own, light \
         (small) to dark (large), white where the moved pose is not reached or the station is \
         beyond the travel; the black line: the value chosen. Every value, with the deflection, \
         the Jacobian's condition number, the distance to the joint limits and to the cell's \
         floor and obstacles: map.csv.",
        Drawn(map),
    )
}

impl Plot for Drawn<'_> {
    fn size(&self) -> (u32, u32) {
        (1100, 520)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let m = self.0;
        let (n, g) = (m.bound.nrows(), m.bound.ncols());
        let (deg, scale, caption, y_desc) = axis(m);
        let half = match g {
            0 | 1 => 1.0,
            _ => (deg[1] - deg[0]) / 2.0,
        };
        let (lo, hi) = m
            .bound
            .iter()
            .filter(|v| v.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(*v), b.max(*v))
            });
        let axes = Axes {
            caption,
            x: 0.5..n as f64 + 0.5,
            y: deg.first().copied().unwrap_or(0.0) - half
                ..deg.last().copied().unwrap_or(0.0) + half,
            x_desc: "path point",
            y_desc,
            x_label: &whole,
        };
        let mut chart = line_chart(root, &axes)?;
        let stride = n.div_ceil(COLUMNS).max(1);
        let cells = (0..n)
            .step_by(stride)
            .flat_map(|i| (0..g).map(move |k| (i, k)));
        let shade = |v: f64| -> RGBColor {
            if !v.is_finite() {
                return WHITE;
            }
            let t = if hi > lo { (v - lo) / (hi - lo) } else { 0.0 };
            let c = (235.0 - 200.0 * t) as u8;
            RGBColor(c, c, (255.0 - 120.0 * t) as u8)
        };
        chart
            .draw_series(cells.map(|(i, k)| {
                let x = i as f64 + 1.0;
                Rectangle::new(
                    [
                        (x - 0.5, deg[k] - half),
                        (x - 0.5 + stride as f64, deg[k] + half),
                    ],
                    shade(m.bound[(i, k)]).filled(),
                )
            }))
            .map_err(failed)?;
        let line: Vec<(f64, f64)> = (m.chosen.iter().enumerate())
            .map(|(i, a)| (i as f64 + 1.0, a * scale))
            .collect();
        chart
            .draw_series(LineSeries::new(
                line,
                ShapeStyle::from(BLACK).stroke_width(2),
            ))
            .map_err(failed)?;
        Ok(())
    }
}

/// The values of the map's columns in the figure's unit (deg or mm), that unit's scale from SI,
/// the caption and the axis' description.
pub fn axis(m: &Map) -> (Vec<f64>, f64, &'static str, &'static str) {
    match m.variable {
        MapVariable::Rotation => (
            m.angles.iter().map(|a| a.to_degrees()).collect(),
            180.0 / std::f64::consts::PI,
            "Error bound over path point and tool rotation",
            "rotation about tool z, deg",
        ),
        MapVariable::Track => (
            m.stations.iter().map(|s| s * 1e3).collect(),
            1e3,
            "Error bound over path point and track station",
            "station from the path's own, mm",
        ),
    }
}
