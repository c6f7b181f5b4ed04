//! The paper's Fig. 8: average deviation rate against noise level, one panel per joint, one line
//! per group; dashed, the first-order prediction.

use crate::{colour, failed, short, Drawing, Plot};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use stiffid_design::study::Study;

struct Deviation<'a>(&'a Study);

/// The figure `deviation_vs_noise`.
pub fn figure(study: &Study) -> Drawing<'_> {
    Drawing::new(
        "deviation_vs_noise",
        &format!(
            "Average deviation rate |k_id - k_true| / k_true of each joint against the noise level \
             (levels 1-{} are the variance multiples {} of sigma^2 = {:.3e} mm^2, the paper's \
             Table 3: one displacement coordinate), {} Monte Carlo runs per point; solid: simulated mean, dashed: first-order \
             prediction (the paper's Fig. 8).",
            study.setup.noise().levels.len(),
            study
                .setup
                .noise()
                .levels
                .iter()
                .map(|m| m.to_string())
                .collect::<Vec<_>>()
                .join(", "),
            study.setup.noise().displacement_variance() * 1e6,
            study.runs
        ),
        Deviation(study),
    )
}

impl Plot for Deviation<'_> {
    fn size(&self) -> (u32, u32) {
        (1200, 820)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let (legend, panels) = root.split_vertically(70);
        legend_row(&legend, self.0)?;
        for (j, panel) in panels.split_evenly((2, 3)).iter().enumerate() {
            joint_panel(panel, self.0, j)?;
        }
        Ok(())
    }
}

/// The group legend: a coloured line and title per group, in one or two rows.
pub fn legend_row<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, study: &Study) -> Result<()> {
    let per_row = 3;
    let width = area.dim_in_pixel().0 as i32 / per_row;
    for (g, group) in study.groups.iter().enumerate() {
        let x = 20 + width * (g as i32 % per_row);
        let y = 18 + 28 * (g as i32 / per_row);
        let style = ShapeStyle::from(colour(g)).stroke_width(3);
        area.draw(&PathElement::new(vec![(x, y), (x + 36, y)], style))
            .map_err(failed)?;
        area.draw(&Circle::new((x + 18, y), 4, colour(g).filled()))
            .map_err(failed)?;
        area.draw(&Text::new(
            group.title.clone(),
            (x + 44, y - 9),
            ("sans-serif", 18),
        ))
        .map_err(failed)?;
    }
    Ok(())
}

fn joint_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    study: &Study,
    j: usize,
) -> Result<()> {
    let levels = study.setup.noise().levels.len();
    let values = study.groups.iter().flat_map(|g| {
        let s = &g.simulation;
        s.mean_deviation_pct
            .iter()
            .chain(&s.predicted_deviation_pct)
            .map(move |r| r[j])
    });
    let hi = values.filter(|v| v.is_finite()).fold(0.0f64, f64::max);
    let hi = if hi > 0.0 { 1.1 * hi } else { 1.0 };
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!("({}) joint {}", (b'a' + j as u8) as char, j + 1),
            ("sans-serif", 20),
        )
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(0.7..levels as f64 + 0.3, 0.0..hi)
        .map_err(failed)?;
    chart
        .configure_mesh()
        .x_labels(levels)
        .x_label_formatter(&|x| format!("{x:.0}"))
        .y_label_formatter(&|y| short(*y))
        .x_desc("noise level")
        .y_desc("deviation rate, %")
        .label_style(("sans-serif", 14))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(failed)?;
    for (g, group) in study.groups.iter().enumerate() {
        let s = &group.simulation;
        let points = |rates: &[[f64; 6]]| -> Vec<(f64, f64)> {
            rates
                .iter()
                .enumerate()
                .map(|(l, r)| ((l + 1) as f64, r[j]))
                .collect()
        };
        let style = ShapeStyle::from(colour(g)).stroke_width(2);
        chart
            .draw_series(LineSeries::new(points(&s.mean_deviation_pct), style))
            .map_err(failed)?;
        chart
            .draw_series(
                points(&s.mean_deviation_pct)
                    .into_iter()
                    .map(|p| Circle::new(p, 3, colour(g).filled())),
            )
            .map_err(failed)?;
        chart
            .draw_series(DashedLineSeries::new(
                points(&s.predicted_deviation_pct),
                4,
                4,
                ShapeStyle::from(colour(g).mix(0.7)).stroke_width(1),
            ))
            .map_err(failed)?;
    }
    Ok(())
}
