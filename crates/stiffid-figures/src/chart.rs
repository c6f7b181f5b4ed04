//! One chart of marks on two linear axes (a logarithmic `y` on request): points, lines, bars and
//! error bars, a legend, the axes named with their units. Every figure of [`crate::calibrate`] and
//! [`crate::identify`] is one, so a figure is its data.

use crate::{failed, short, Plot};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;

/// A chart: its title, axes and marks.
pub struct Chart {
    /// The title.
    pub title: String,
    /// The `x` axis' name with its unit.
    pub x_desc: String,
    /// The `y` axis' name with its unit.
    pub y_desc: String,
    /// Whether `y` is drawn on a logarithmic scale (its values must then be > 0; others are left
    /// out).
    pub log_y: bool,
    /// Text labels of the whole `x` values 0, 1, ... (categories) instead of numbers.
    pub x_names: Vec<String>,
    /// What is drawn, in order.
    pub marks: Vec<Mark>,
}

/// What a chart draws; each with its legend entry (empty: none) and colour.
pub enum Mark {
    /// Points at `(x, y)`.
    Points {
        /// The legend's text.
        label: String,
        /// The colour.
        colour: RGBColor,
        /// The points.
        xy: Vec<(f64, f64)>,
    },
    /// A polyline through `(x, y)`, dashed or not.
    Line {
        /// The legend's text.
        label: String,
        /// The colour.
        colour: RGBColor,
        /// The vertices.
        xy: Vec<(f64, f64)>,
    },
    /// Bars from `y = 0` (or the bottom of a logarithmic axis): `(x_left, x_right, y)`.
    Bars {
        /// The legend's text.
        label: String,
        /// The colour.
        colour: RGBColor,
        /// The bars.
        bars: Vec<(f64, f64, f64)>,
    },
    /// A value with its interval: `(x, y, low, high)`.
    Intervals {
        /// The legend's text.
        label: String,
        /// The colour.
        colour: RGBColor,
        /// The values.
        values: Vec<(f64, f64, f64, f64)>,
    },
}

impl Mark {
    fn xy(&self) -> Vec<(f64, f64)> {
        match self {
            Mark::Points { xy, .. } | Mark::Line { xy, .. } => xy.clone(),
            Mark::Bars { bars, .. } => bars
                .iter()
                .flat_map(|&(a, b, y)| [(a, y), (b, y)])
                .collect(),
            Mark::Intervals { values, .. } => values
                .iter()
                .flat_map(|&(x, y, lo, hi)| [(x, y), (x, lo), (x, hi)])
                .collect(),
        }
    }
}

impl Chart {
    /// The `x` and `y` ranges of every finite value (`y` > 0 on a logarithmic axis), a little
    /// wider; `y` from 0 for bars on a linear axis.
    fn ranges(&self) -> ((f64, f64), (f64, f64)) {
        let all: Vec<(f64, f64)> = (self.marks.iter())
            .flat_map(Mark::xy)
            .filter(|(x, y)| x.is_finite() && y.is_finite() && (!self.log_y || *y > 0.0))
            .collect();
        let span = |v: &mut dyn Iterator<Item = f64>| {
            v.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                (a.min(x), b.max(x))
            })
        };
        let (mut x0, mut x1) = span(&mut all.iter().map(|p| p.0));
        let (mut y0, mut y1) = span(&mut all.iter().map(|p| p.1));
        if !x0.is_finite() {
            (x0, x1, y0, y1) = (0.0, 1.0, 0.1, 1.0);
        }
        if self.marks.iter().any(|m| matches!(m, Mark::Bars { .. })) && !self.log_y {
            y0 = y0.min(0.0);
        }
        let pad = |a: f64, b: f64, log: bool| match log {
            true => (a / 1.5, b * 1.5),
            false if b > a => (a - 0.04 * (b - a), b + 0.04 * (b - a)),
            false => (a - 0.5 * a.abs().max(1.0), b + 0.5 * b.abs().max(1.0)),
        };
        (pad(x0, x1, false), pad(y0, y1, self.log_y))
    }
}

impl Chart {
    /// Whether the category names are written upright (many categories).
    fn rotated(&self) -> bool {
        self.x_names.len() > 8
    }
}

/// `v` as an axis label on an axis spanning `span`: round-off beside 0 written as 0.
fn label(v: f64, span: f64) -> String {
    match v.abs() < 1e-9 * span.abs() {
        true => "0".into(),
        false => short(v),
    }
}

impl Plot for Chart {
    fn size(&self) -> (u32, u32) {
        match self.rotated() {
            true => (760, 540),
            false => (760, 440),
        }
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let ((x0, x1), (y0, y1)) = self.ranges();
        let names = |x: &f64| {
            let k = x.round();
            match ((x - k).abs() < 1e-9 && k >= 0.0).then(|| self.x_names.get(k as usize)) {
                Some(Some(n)) => n.clone(),
                _ if self.x_names.is_empty() => label(*x, x1 - x0),
                _ => String::new(),
            }
        };
        let mut builder = ChartBuilder::on(root);
        builder
            .caption(&self.title, ("sans-serif", 20))
            .margin(14)
            .x_label_area_size(if self.rotated() { 150 } else { 44 })
            .y_label_area_size(70);
        let ticks = match self.x_names.is_empty() {
            true => 10,
            false => self.x_names.len() * 2 + 1,
        };
        macro_rules! draw {
            ($chart:expr, $y:expr) => {{
                let mut chart = $chart;
                chart
                    .configure_mesh()
                    .x_desc(self.x_desc.as_str())
                    .y_desc(self.y_desc.as_str())
                    .x_labels(ticks)
                    .x_label_formatter(&names)
                    .y_label_formatter(&|y| label(*y, y1 - y0))
                    .label_style(("sans-serif", 13))
                    .x_label_style(match self.rotated() {
                        true => ("sans-serif", 12).into_font().transform(FontTransform::Rotate90),
                        false => ("sans-serif", 13).into_font(),
                    })
                    .light_line_style(WHITE.mix(0.0))
                    .draw()
                    .map_err(failed)?;
                let bottom = $y;
                let keep = |y: f64| y.is_finite() && (!self.log_y || y > 0.0);
                for mark in &self.marks {
                    let drawn = match mark {
                        Mark::Points { colour, xy, .. } => chart.draw_series(
                            (xy.iter().filter(|p| keep(p.1)))
                                .map(|&p| Circle::new(p, 3, colour.mix(0.75).filled())),
                        ),
                        Mark::Line { colour, xy, .. } => chart.draw_series(LineSeries::new(
                            xy.iter().copied().filter(|p| keep(p.1)),
                            colour.stroke_width(2),
                        )),
                        Mark::Bars { colour, bars, .. } => chart.draw_series(
                            (bars.iter().filter(|b| keep(b.2))).map(|&(a, b, y)| {
                                Rectangle::new([(a, bottom), (b, y)], colour.mix(0.6).filled())
                            }),
                        ),
                        Mark::Intervals { colour, values, .. } => chart.draw_series(
                            (values.iter().filter(|v| keep(v.2) && keep(v.3))).map(
                                |&(x, y, lo, hi)| {
                                    ErrorBar::new_vertical(x, lo, y, hi, colour.filled(), 10)
                                },
                            ),
                        ),
                    }
                    .map_err(failed)?;
                    let (label, colour) = match mark {
                        Mark::Points { label, colour, .. }
                        | Mark::Line { label, colour, .. }
                        | Mark::Bars { label, colour, .. }
                        | Mark::Intervals { label, colour, .. } => (label, *colour),
                    };
                    if !label.is_empty() {
                        drawn.label(label.as_str()).legend(move |(x, y)| {
                            Rectangle::new([(x, y - 5), (x + 14, y + 5)], colour.filled())
                        });
                    }
                }
                if self.marks.iter().any(|m| !matches!(m, Mark::Points { label, .. } | Mark::Line { label, .. } | Mark::Bars { label, .. } | Mark::Intervals { label, .. } if label.is_empty())) {
                    chart
                        .configure_series_labels()
                        .background_style(WHITE.mix(0.85))
                        .border_style(BLACK.mix(0.3))
                        .label_font(("sans-serif", 13))
                        .position(SeriesLabelPosition::UpperLeft)
                        .draw()
                        .map_err(failed)?;
                }
            }};
        }
        match self.log_y {
            false => draw!(
                builder.build_cartesian_2d(x0..x1, y0..y1).map_err(failed)?,
                y0.max(0.0).min(y1)
            ),
            true => draw!(
                builder
                    .build_cartesian_2d(x0..x1, (y0..y1).log_scale())
                    .map_err(failed)?,
                y0
            ),
        }
        Ok(())
    }
}
