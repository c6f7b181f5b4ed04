//! The figures of `stiffid compensate --program --report`: the process force along the path and
//! each program segment's deflection before and after compensation.

use crate::axes::{line_chart, whole, Axes};
use crate::{colour, failed, Drawing, Plot};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use stiffid::app::compensate::Segment;
use stiffid::app::document::mm;
use stiffid_machining::compensate::Compensated;

struct Force<'a>(&'a [(usize, Compensated)]);

/// The figure `force`: the process force on the tool at the points of `sample` (0-based index,
/// result).
pub fn force(sample: &[(usize, Compensated)]) -> Drawing<'_> {
    Drawing::new(
        "force",
        "The process force on the tool along the path, base frame, N: its length (black) and its \
         x, y, z components (colours), from the process file's operations turned along the path's \
         own feed direction. Zero where nothing cuts (rapid moves, plunges, blocks no operation \
         covers).",
        Force(sample),
    )
}

impl Plot for Force<'_> {
    fn size(&self) -> (u32, u32) {
        (1100, 460)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let r = self.0;
        let f = |c: &Compensated| c.wrench.fixed_rows::<3>(0).into_owned();
        let hi = r
            .iter()
            .map(|(_, c)| f(c).norm())
            .fold(0.0, f64::max)
            .max(1.0)
            * 1.1;
        let n = r.last().map_or(1, |(i, _)| i + 1) as f64;
        let axes = Axes {
            caption: "Process force along the path",
            x: 0.5..n + 0.5,
            y: -hi..hi,
            x_desc: "path point",
            y_desc: "force, N",
            x_label: &whole,
        };
        let mut chart = line_chart(root, &axes)?;
        let line = |g: &dyn Fn(&Compensated) -> f64| -> Vec<(f64, f64)> {
            r.iter().map(|(i, c)| (*i as f64 + 1.0, g(c))).collect()
        };
        for (k, name) in ["fx", "fy", "fz"].iter().enumerate() {
            let style = ShapeStyle::from(colour(k + 1)).stroke_width(1);
            chart
                .draw_series(LineSeries::new(line(&|c| f(c)[k]), style))
                .map_err(failed)?
                .label(*name)
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], style));
        }
        let style = ShapeStyle::from(BLACK).stroke_width(2);
        chart
            .draw_series(LineSeries::new(line(&|c| f(c).norm()), style))
            .map_err(failed)?
            .label("|f|")
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], style));
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(failed)?;
        Ok(())
    }
}

struct Segments<'a>(&'a [Segment]);

/// A value drawn per segment, mm.
type Value = dyn Fn(&Segment) -> f64;

/// The figure `segments`: each program segment's largest deflection before and after
/// compensation.
pub fn segments(segments: &[Segment]) -> Drawing<'_> {
    Drawing::new(
        "segments",
        "The largest TCP deflection of each program segment (a program line: a G-code block with \
         its arc points, a robot program's target), mm. Black: before compensation, under the \
         process force. Blue: after compensation, the error predicted to remain, 2 standard \
         deviations of the deflection from the compliance covariance (what the stiffness's \
         uncertainty leaves), where the stiffness file has one; the compensated targets \
         reproduce the model itself to below 0.1 um (the table's residual).",
        Segments(segments),
    )
}

impl Plot for Segments<'_> {
    fn size(&self) -> (u32, u32) {
        (1100, 460)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let s = self.0;
        let std = |g: &Segment| g.deflection_std.map_or(0.0, |v| 2.0 * mm(v));
        let hi = s
            .iter()
            .map(|g| mm(g.deflection_before).max(std(g)))
            .fold(0.0, f64::max)
            .max(1e-6)
            * 1.1;
        let n = s.len() as f64;
        let lines: Vec<u64> = s.iter().map(|g| g.line).collect();
        let line_of = |x: &f64| {
            let k = x.round() as usize;
            lines
                .get(k.wrapping_sub(1))
                .map_or(String::new(), u64::to_string)
        };
        let axes = Axes {
            caption: "Deflection per program segment",
            x: 0.5..n + 0.5,
            y: 0.0..hi,
            x_desc: "segment (program line)",
            y_desc: "largest |d|, mm",
            x_label: &line_of,
        };
        let mut chart = line_chart(root, &axes)?;
        let points = |g: &dyn Fn(&Segment) -> f64| -> Vec<(f64, f64)> {
            s.iter()
                .enumerate()
                .map(|(k, v)| (k as f64 + 1.0, g(v)))
                .collect()
        };
        let mut drawn: Vec<(&Value, RGBColor)> =
            vec![(&|v: &Segment| mm(v.deflection_before), BLACK)];
        if s.iter().any(|g| g.deflection_std.is_some()) {
            drawn.push((&std, colour(2)));
        }
        for (g, c) in drawn {
            let style = ShapeStyle::from(c).stroke_width(2);
            chart
                .draw_series(LineSeries::new(points(g), style))
                .map_err(failed)?;
            chart
                .draw_series(
                    points(g)
                        .into_iter()
                        .map(|p| Circle::new(p, 3, style.filled())),
                )
                .map_err(failed)?;
        }
        Ok(())
    }
}
