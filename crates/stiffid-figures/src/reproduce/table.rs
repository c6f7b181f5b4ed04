//! The paper's Table 4 as a figure: mean deviation rate (and standard deviation) of every joint
//! and group at the level nearest multiple 1 (the paper's level 2), the best group of each joint
//! shaded.

use crate::{colour, failed, Drawing, Plot};
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use stiffid_design::study::Study;

struct Table<'a>(&'a Study);

/// The figure `table4_level2`.
pub fn figure(study: &Study) -> Drawing<'_> {
    let l = study.validation_level;
    Drawing::new(
        "table4_level2",
        &format!(
            "Mean deviation rate +- standard deviation, %, over {} runs at noise level {} \
             (variance multiple {}), per joint and group (the paper's Table 4 shows one run). \
             Shaded: the best group of each joint.",
            study.runs,
            l + 1,
            study.setup.noise().levels[l]
        ),
        Table(study),
    )
}

const ROW: i32 = 44;
const FIRST: i32 = 110;
const HEAD: i32 = 60;

impl Plot for Table<'_> {
    fn size(&self) -> (u32, u32) {
        let cols = self.0.groups.len() as u32;
        (FIRST as u32 + 190 * cols + 10, (HEAD + ROW * 6 + 10) as u32)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let study = self.0;
        let l = study.validation_level;
        let width = 190;
        let text = |s: String, x: i32, y: i32, size: i32| {
            root.draw(&Text::new(s, (x, y), ("sans-serif", size)))
                .map_err(failed)
        };
        text("joint".into(), 20, 32, 17)?;
        text("%".into(), 20, 8, 15)?;
        for (g, group) in study.groups.iter().enumerate() {
            let x = FIRST + width * g as i32;
            root.draw(&Rectangle::new([(x, 10), (x + 14, 24)], colour(g).filled()))
                .map_err(failed)?;
            let (name, how) = group.title.split_once(" (").unwrap_or((&group.title, ""));
            text(name.to_string(), x + 20, 8, 16)?;
            if !how.is_empty() {
                text(format!("({how}"), x, 32, 15)?;
            }
        }
        for j in 0..6 {
            let y = HEAD + ROW * j as i32;
            let means: Vec<f64> = study
                .groups
                .iter()
                .map(|g| g.simulation.mean_deviation_pct[l][j])
                .collect();
            let best = (0..means.len())
                .min_by(|&a, &b| means[a].total_cmp(&means[b]))
                .unwrap_or(0);
            root.draw(&PathElement::new(
                vec![(10, y), (FIRST + width * means.len() as i32, y)],
                BLACK.mix(0.3),
            ))
            .map_err(failed)?;
            text(format!("{}", j + 1), 40, y + 12, 18)?;
            for (g, group) in study.groups.iter().enumerate() {
                let x = FIRST + width * g as i32;
                if g == best {
                    root.draw(&Rectangle::new(
                        [(x - 6, y + 2), (x + width - 12, y + ROW - 2)],
                        RGBColor(200, 235, 200).filled(),
                    ))
                    .map_err(failed)?;
                }
                let std = group.simulation.std_deviation_pct[l][j];
                text(format!("{:.3} ± {:.3}", means[g], std), x, y + 12, 17)?;
            }
        }
        Ok(())
    }
}
