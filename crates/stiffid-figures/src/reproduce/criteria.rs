//! Does the criterion predict accuracy? Every design criterion of every group against the group's
//! measured average deviation rate, one panel per criterion, with Spearman's rank correlation.

use super::{criteria_values, CRITERIA};
use crate::{colour, failed, short, Drawing, Plot};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use stiffid_design::study::{spearman, Study};

struct CriteriaPlot<'a>(&'a Study);

/// The figure `criteria_vs_deviation`.
pub fn figure(study: &Study) -> Drawing<'_> {
    Drawing::new(
        "criteria_vs_deviation",
        "Each design criterion of each group (x, log scale) against the group's measured average \
         deviation rate (y: mean over joints and noise levels, %). rho: Spearman's rank \
         correlation over the groups; a criterion that predicts accuracy has rho near +1.",
        CriteriaPlot(study),
    )
}

impl Plot for CriteriaPlot<'_> {
    fn size(&self) -> (u32, u32) {
        (1200, 900)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let (legend, panels) = root.split_vertically(70);
        super::deviation::legend_row(&legend, self.0)?;
        for (c, panel) in panels
            .split_evenly((3, 3))
            .iter()
            .take(CRITERIA.len())
            .enumerate()
        {
            criterion_panel(panel, self.0, c)?;
        }
        Ok(())
    }
}

/// The range of `log10` of the positive finite values, padded.
fn log_range(values: &[f64]) -> (f64, f64) {
    let logs = values
        .iter()
        .filter(|v| v.is_finite() && **v > 0.0)
        .map(|v| v.log10());
    let (lo, hi) = logs.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    match lo <= hi {
        true => {
            let pad = 0.12 * (hi - lo).max(0.2);
            (lo - pad, hi + pad)
        }
        false => (-1.0, 1.0),
    }
}

fn criterion_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    study: &Study,
    c: usize,
) -> Result<()> {
    let xs: Vec<f64> = study
        .groups
        .iter()
        .map(|g| criteria_values(&g.evaluation)[c].1)
        .collect();
    let ys: Vec<f64> = study
        .groups
        .iter()
        .map(|g| g.average_deviation_pct())
        .collect();
    let (key, _) = CRITERIA[c];
    let rho = spearman(&xs, &ys);
    let (x0, x1) = log_range(&xs);
    let y1 = 1.15
        * ys.iter()
            .copied()
            .filter(|y| y.is_finite())
            .fold(0.0, f64::max);
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!(
                "{key}   rho = {}",
                rho.map_or("n/a".into(), |r| format!("{r:+.2}"))
            ),
            ("sans-serif", 18),
        )
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(50)
        .build_cartesian_2d(x0..x1, 0.0..y1.max(1e-9))
        .map_err(failed)?;
    chart
        .configure_mesh()
        .x_labels(5)
        .y_labels(5)
        .x_label_formatter(&|x| short(10f64.powf(*x)))
        .y_label_formatter(&|y| short(*y))
        .y_desc("avg deviation, %")
        .label_style(("sans-serif", 12))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(failed)?;
    for (g, (x, y)) in xs
        .iter()
        .zip(&ys)
        .enumerate()
        .filter(|(_, (x, _))| x.is_finite() && **x > 0.0)
    {
        chart
            .draw_series([EmptyElement::at((x.log10(), *y))
                + Circle::new((0, 0), 6, colour(g).filled())
                + Text::new(format!("{}", g + 1), (7, -16), ("sans-serif", 15))])
            .map_err(failed)?;
    }
    Ok(())
}
