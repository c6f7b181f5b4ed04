//! The figures of `stiffid compensate --report`: the TCP deflection along the path before and
//! after compensation with its uncertainty band, and the path drawn over the robot.

use crate::axes::{line_chart, whole, Axes};
use crate::postures::{draw_stick, projection, stick};
use crate::{colour, failed, Drawing, Plot};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use stiffid_core::Setup;
use stiffid_machining::compensate::Compensated;

struct Deflection<'a>(&'a [Compensated]);

/// The figure `deflection`.
pub fn deflection(results: &[Compensated]) -> Drawing<'_> {
    Drawing::new(
        "deflection",
        "TCP translation deflection |d| along the path, mm. Black: before compensation (the robot \
         at the nominal axis angles under the path's wrench), with its band +-2 standard deviations \
         from the compliance covariance where the stiffness file has one. Blue: after compensation, \
         the error predicted to remain, 2 standard deviations of the predicted deflection (the \
         compensation removes the predicted deflection, not the stiffness's uncertainty); without \
         a covariance it cannot be predicted and is not drawn. The compensated axis angles \
         reproduce the model itself to below 0.1 um (the summary gives the largest residual). \
         Orange dashed (--free tool-rotation): before the tool-axis optimisation.",
        Deflection(results),
    )
}

impl Plot for Deflection<'_> {
    fn size(&self) -> (u32, u32) {
        (1100, 520)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let r = self.0;
        let norm = |d: &nalgebra::Vector6<f64>| d.fixed_rows::<3>(0).norm() * 1e3;
        let sd = |c: &Compensated| c.translation_norm_std.map_or(0.0, |s| 2.0 * s * 1e3);
        let hi = r
            .iter()
            .map(|c| {
                let before = c.deflection_before.as_ref().map_or(0.0, norm);
                (norm(&c.deflection) + sd(c)).max(before)
            })
            .fold(0.0, f64::max)
            * 1.1;
        let n = r.len() as f64;
        let axes = Axes {
            caption: "TCP deflection along the path",
            x: 0.5..n + 0.5,
            y: 0.0..hi.max(1e-6),
            x_desc: "path point",
            y_desc: "|d|, mm",
            x_label: &whole,
        };
        let mut chart = line_chart(root, &axes)?;
        let x = |i: usize| i as f64 + 1.0;
        let band = |lo: &dyn Fn(&Compensated) -> f64, hi: &dyn Fn(&Compensated) -> f64| {
            let mut outline: Vec<(f64, f64)> =
                r.iter().enumerate().map(|(i, c)| (x(i), hi(c))).collect();
            outline.extend(r.iter().enumerate().rev().map(|(i, c)| (x(i), lo(c))));
            outline
        };
        if r.iter().any(|c| c.translation_norm_std.is_some()) {
            let before = band(&|c| (norm(&c.deflection) - sd(c)).max(0.0), &|c| {
                norm(&c.deflection) + sd(c)
            });
            chart
                .draw_series([Polygon::new(before, BLACK.mix(0.15).filled())])
                .map_err(failed)?;
        }
        let line = |f: &dyn Fn(&Compensated) -> f64| -> Vec<(f64, f64)> {
            r.iter().enumerate().map(|(i, c)| (x(i), f(c))).collect()
        };
        if r[0].deflection_before.is_some() {
            chart
                .draw_series(DashedLineSeries::new(
                    line(&|c| c.deflection_before.as_ref().map_or(0.0, norm)),
                    6,
                    4,
                    ShapeStyle::from(colour(1)).stroke_width(2),
                ))
                .map_err(failed)?;
        }
        chart
            .draw_series(LineSeries::new(
                line(&|c| norm(&c.deflection)),
                ShapeStyle::from(BLACK).stroke_width(2),
            ))
            .map_err(failed)?;
        if r.iter().any(|c| c.translation_norm_std.is_some()) {
            chart
                .draw_series(LineSeries::new(
                    line(&sd),
                    ShapeStyle::from(colour(2)).stroke_width(2),
                ))
                .map_err(failed)?;
        }
        Ok(())
    }
}

struct PathOverRobot<'a> {
    setup: &'a Setup,
    results: &'a [Compensated],
}

/// The figure `path`.
pub fn path<'a>(setup: &'a Setup, results: &'a [Compensated]) -> Drawing<'a> {
    Drawing::new(
        "path",
        "The path (red) drawn over the robot at its first, middle and last point (stick figures: \
         base, joint origins, flange, tool centre point), side view (x-z) and top view (x-y), base \
         frame, m.",
        PathOverRobot { setup, results },
    )
}

impl PathOverRobot<'_> {
    fn shown(&self) -> Vec<usize> {
        let n = self.results.len();
        let mut v = vec![0, n / 2, n - 1];
        v.dedup();
        v
    }

    fn view<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        name: &str,
        v: usize,
    ) -> Result<()> {
        let sticks: Vec<_> = self
            .shown()
            .iter()
            .map(|&i| stick(self.setup, &self.results[i].q))
            .collect();
        let tcp: Vec<(f64, f64)> = self
            .results
            .iter()
            .map(|c| (c.pose.translation.vector.x, c.pose.translation.vector[v]))
            .collect();
        let all = sticks
            .iter()
            .flat_map(|s| s.chain.iter().map(|p| (p.x, p[v])))
            .chain(tcp.iter().copied());
        let (mut xr, mut yr) = ((f64::MAX, f64::MIN), (f64::MAX, f64::MIN));
        for (a, b) in all {
            (xr, yr) = ((xr.0.min(a), xr.1.max(a)), (yr.0.min(b), yr.1.max(b)));
        }
        let (mut chart, _) = projection(
            area,
            name,
            v,
            (xr.0 - 0.2, xr.1 + 0.2),
            (yr.0 - 0.2, yr.1 + 0.2),
        )?;
        for (k, s) in sticks.iter().enumerate() {
            draw_stick(&mut chart, s, v, colour(k + 2))?;
        }
        chart
            .draw_series(LineSeries::new(tcp, ShapeStyle::from(RED).stroke_width(2)))
            .map_err(failed)?;
        Ok(())
    }
}

impl Plot for PathOverRobot<'_> {
    fn size(&self) -> (u32, u32) {
        (1200, 560)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let root = root
            .titled("The path over the robot", ("sans-serif", 22))
            .map_err(failed)?;
        let (side, top) = root.split_horizontally(600);
        self.view(&side, "side view", 2)?;
        self.view(&top, "top view", 1)
    }
}
