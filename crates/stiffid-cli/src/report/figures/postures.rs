//! The robot in every posture of a group, side (x-z) and top (x-y) views (the paper's Figs. 5-7):
//! a stick figure through the base, the joint origins, the flange and the tool centre point, the
//! loading point as a square and the rope to the anchor as a thin grey line. The same scale for every
//! group so the figures compare.

use super::{colour, failed, render, Figure, Plot};
use crate::study::Study;
use anyhow::Result;
use nalgebra::{Vector3, Vector6};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use stiffid::Setup;

/// The points of one posture's stick figure (base frame, m), and its loading point.
pub struct Stick {
    /// Base, joint origins, flange, TCP, base frame, m.
    pub chain: Vec<Vector3<f64>>,
    /// The loading point, base frame, m.
    pub loading_point: Vector3<f64>,
}

pub fn stick(setup: &Setup, q: &Vector6<f64>) -> Stick {
    let frames = setup.robot.frames(q);
    let mut chain = vec![setup.robot.base.translation.vector];
    chain.extend(frames.axis_points.iter().copied());
    chain.push(frames.flange.translation.vector);
    chain.push(frames.point(&setup.tool.tcp));
    Stick {
        chain,
        loading_point: frames.point(&setup.tool.loading_point),
    }
}

struct Postures<'a> {
    study: &'a Study,
    group: usize,
    /// Data box of every group, m: (min, max) per axis.
    range: [(f64, f64); 3],
}

/// The figure `postures_<group>`.
pub fn figure(study: &Study, group: usize) -> Result<Figure> {
    let g = &study.groups[group];
    render(
        &format!("postures_{}", g.name),
        &format!(
            "{}: the robot in its {} postures, side view (x-z) and top view (x-y), base frame, m. \
             Lines: base, joint origins, flange, tool centre point (numbered); squares: loading \
             point; grey: the rope to the anchor (star).",
            g.title,
            g.postures.len()
        ),
        &Postures {
            study,
            group,
            range: data_range(study),
        },
    )
}

fn data_range(study: &Study) -> [(f64, f64); 3] {
    let setup = &study.setup;
    let mut range = [(f64::INFINITY, f64::NEG_INFINITY); 3];
    let points = study
        .groups
        .iter()
        .flat_map(|g| g.postures.iter().map(|q| stick(setup, q)))
        .flat_map(|s| s.chain.into_iter().chain([s.loading_point]))
        .chain([setup.load.anchor, Vector3::zeros()]);
    for p in points {
        for (a, r) in range.iter_mut().enumerate() {
            *r = (r.0.min(p[a]), r.1.max(p[a]));
        }
    }
    range.map(|(lo, hi)| (lo - 0.2, hi + 0.2))
}

/// The points without those that coincide with the previous one (a zero-length segment would
/// make a thick line's outline degenerate), closer than 0.1 mm.
fn distinct(points: impl Iterator<Item = (f64, f64)>) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::new();
    for p in points {
        if out
            .last()
            .is_none_or(|q| (p.0 - q.0).hypot(p.1 - q.1) > 1e-4)
        {
            out.push(p);
        }
    }
    out
}

/// Ranges of two axes widened so one metre has the same length on both in a `w x h` pixel area.
fn equal_aspect(x: (f64, f64), y: (f64, f64), w: f64, h: f64) -> ((f64, f64), (f64, f64)) {
    let scale = ((x.1 - x.0) / w).max((y.1 - y.0) / h);
    let widen = |r: (f64, f64), px: f64| {
        let c = 0.5 * (r.0 + r.1);
        (c - 0.5 * scale * px, c + 0.5 * scale * px)
    };
    (widen(x, w), widen(y, h))
}

/// A chart of one projection of the base frame, x against axis `v` (2: z, 1: y), m, with one
/// metre as long on both axes, covering the ranges `x` and `y`; and its x range.
pub fn projection<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    name: &str,
    v: usize,
    x: (f64, f64),
    y: (f64, f64),
) -> Result<(Projection<'a, DB>, (f64, f64))> {
    let (w, h) = area.dim_in_pixel();
    let (xr, yr) = equal_aspect(x, y, w as f64 - 90.0, h as f64 - 90.0);
    let mut chart = ChartBuilder::on(area)
        .caption(name, ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(45)
        .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
        .map_err(failed)?;
    chart
        .configure_mesh()
        .x_desc("x, m")
        .y_desc(if v == 2 { "z, m" } else { "y, m" })
        .label_style(("sans-serif", 13))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(failed)?;
    Ok((chart, xr))
}

/// A chart of [`projection`].
pub type Projection<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Draws a stick figure projected on x and axis `v` in colour `c`, a line per link and a dot per
/// point; returns the projected points.
pub fn draw_stick<DB: DrawingBackend>(
    chart: &mut Projection<'_, DB>,
    stick: &Stick,
    v: usize,
    c: RGBColor,
) -> Result<Vec<(f64, f64)>> {
    let pts = distinct(stick.chain.iter().map(|p| (p.x, p[v])));
    // One line per link: a polyline's joins spike where a link folds back in projection.
    for link in pts.windows(2) {
        chart
            .draw_series(LineSeries::new(
                link.to_vec(),
                ShapeStyle::from(c).stroke_width(3),
            ))
            .map_err(failed)?;
    }
    chart
        .draw_series(pts.iter().map(|p| Circle::new(*p, 3, c.filled())))
        .map_err(failed)?;
    Ok(pts)
}

impl Plot for Postures<'_> {
    fn size(&self) -> (u32, u32) {
        (1200, 560)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let title = &self.study.groups[self.group].title;
        let root = root.titled(title, ("sans-serif", 22)).map_err(failed)?;
        let (side, top) = root.split_horizontally(600);
        self.view(&side, "side view", 2)?;
        self.view(&top, "top view", 1)
    }
}

impl Postures<'_> {
    /// One projection: x against axis `v` (2: z, 1: y).
    fn view<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        name: &str,
        v: usize,
    ) -> Result<()> {
        let (mut chart, xr) = projection(area, name, v, self.range[0], self.range[v])?;
        let setup = &self.study.setup;
        let anchor = (setup.load.anchor.x, setup.load.anchor[v]);
        for (i, q) in self.study.groups[self.group].postures.iter().enumerate() {
            let s = stick(setup, q);
            let c = colour(i + 1);
            let lp = (s.loading_point.x, s.loading_point[v]);
            chart
                .draw_series(LineSeries::new(
                    [lp, anchor],
                    ShapeStyle::from(BLACK.mix(0.25)),
                ))
                .map_err(failed)?;
            let pts = draw_stick(&mut chart, &s, v, c)?;
            chart
                .draw_series(
                    [EmptyElement::at(lp) + Rectangle::new([(-4, -4), (4, 4)], c.filled())],
                )
                .map_err(failed)?;
            let tip = pts[pts.len() - 1];
            chart
                .draw_series([EmptyElement::at(tip)
                    + Text::new(
                        format!("{}", i + 1),
                        (6, -18),
                        ("sans-serif", 18).into_font().color(&c),
                    )])
                .map_err(failed)?;
        }
        chart
            .draw_series([EmptyElement::at(anchor) + Text::new("*", (-6, -12), ("sans-serif", 28))])
            .map_err(failed)?;
        if v == 2 {
            chart
                .draw_series(LineSeries::new(
                    [(xr.0, 0.0), (xr.1, 0.0)],
                    ShapeStyle::from(BLACK.mix(0.5)),
                ))
                .map_err(failed)?;
        }
        Ok(())
    }
}
