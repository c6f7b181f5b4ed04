//! Group size against the predicted worst-joint deviation rate (`select --target-pct`), with the
//! target as a dashed line.

use crate::axes::{line_chart, whole, Axes};
use crate::{colour, failed, Drawing, Plot};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use stiffid_design::target::TargetOutcome;

struct Target<'a>(&'a TargetOutcome);

/// The figure `target`.
pub fn figure(outcome: &TargetOutcome) -> Drawing<'_> {
    Drawing::new(
        "target",
        &format!(
            "Predicted mean deviation rate of the worst joint at noise level multiple 1 (first \
             order) of the best group of each size; dashed: the target, {} %.",
            outcome.target_pct
        ),
        Target(outcome),
    )
}

impl Target<'_> {
    /// (group size, worst-joint rate) of every step with a finite rate.
    fn points(&self) -> Vec<(f64, f64)> {
        self.0
            .steps
            .iter()
            .map(|s| (s.postures.len() as f64, s.worst_joint().1))
            .filter(|p| p.1.is_finite())
            .collect()
    }
}

impl Plot for Target<'_> {
    fn size(&self) -> (u32, u32) {
        (800, 500)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let points = self.points();
        let target = self.0.target_pct;
        let hi = points.iter().map(|p| p.1).fold(target, f64::max) * 1.1;
        let last = self.0.steps.last().map_or(2, |s| s.postures.len()) as f64;
        let axes = Axes {
            caption: "postures needed",
            x: 1.5..last + 0.5,
            y: 0.0..hi,
            x_desc: "postures in the group",
            y_desc: "worst joint's deviation rate, %",
            x_label: &whole,
        };
        let mut chart = line_chart(root, &axes)?;
        let c = colour(2);
        chart
            .draw_series(LineSeries::new(
                points.clone(),
                ShapeStyle::from(c).stroke_width(2),
            ))
            .map_err(failed)?;
        chart
            .draw_series(points.iter().map(|p| Circle::new(*p, 4, c.filled())))
            .map_err(failed)?;
        chart
            .draw_series(DashedLineSeries::new(
                [(1.5, target), (last + 0.5, target)],
                6,
                4,
                ShapeStyle::from(colour(5)).stroke_width(2),
            ))
            .map_err(failed)?;
        Ok(())
    }
}
