//! The robot in every posture of a group, side (x-z) and top (x-y) views (the paper's Figs. 5-7):
//! a stick figure through the base, the joint origins, the flange and the tool centre point, the
//! loading point as a square and the rope to the anchor as a thin grey line. The same scale for every
//! group so the figures compare.

use crate::{colour, failed, Drawing, Plot};
use anyhow::Result;
use nalgebra::{Vector3, Vector6};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use stiffid_core::cell::{bodies, Body, Part};
use stiffid_core::Setup;
use stiffid_design::study::Study;

/// The points of one posture's stick figure (base frame, m), and its loading point.
pub struct Stick {
    /// Base, joint origins, flange, TCP, base frame, m.
    pub chain: Vec<Vector3<f64>>,
    /// The loading point, base frame, m.
    pub loading_point: Vector3<f64>,
}

/// The stick figure of `setup`'s robot at the axis angles `q` (rad).
pub fn stick(setup: &Setup, q: &Vector6<f64>) -> Stick {
    let frames = setup.robot().frames(q);
    let mut chain = vec![setup.robot().base().translation.vector];
    chain.extend(frames.axis_points.iter().copied());
    chain.push(frames.flange.translation.vector);
    chain.push(frames.point(&setup.tool().tcp));
    Stick {
        chain,
        loading_point: frames.point(&setup.tool().loading_point),
    }
}

/// Postures of one setup drawn in side and top views.
pub struct Postures<'a> {
    setup: &'a Setup,
    title: String,
    /// The postures drawn, each with its number (label and colour).
    postures: Vec<(usize, Vector6<f64>)>,
    /// Data box, m: (min, max) per axis.
    range: [(f64, f64); 3],
}

impl<'a> Postures<'a> {
    /// The numbered `postures` (axis angles, rad) of `setup` in views of the data box `range`
    /// (see [`data_range`]).
    pub fn new(
        setup: &'a Setup,
        title: &str,
        postures: Vec<(usize, Vector6<f64>)>,
        range: [(f64, f64); 3],
    ) -> Self {
        Self {
            setup,
            title: title.to_string(),
            postures,
            range,
        }
    }
}

/// The figure `postures_<group>`.
pub fn figure(study: &Study, group: usize) -> Drawing<'_> {
    let g = &study.groups[group];
    let all = study.groups.iter().flat_map(|g| g.postures.iter());
    let numbered = g
        .postures
        .iter()
        .copied()
        .enumerate()
        .map(|(i, q)| (i + 1, q));
    Drawing::new(
        &format!("postures_{}", g.name),
        &format!(
            "{}: the robot in its {} postures, side view (x-z) and top view (x-y), base frame, m. \
             Lines: base, joint origins, flange, tool centre point (numbered); squares: loading \
             point; grey: the rope to the anchor (star).",
            g.title,
            g.postures.len()
        ),
        Postures::new(
            &study.setup,
            &g.title,
            numbered.collect(),
            data_range(&study.setup, all),
        ),
    )
}

/// The figures of a group of postures of `setup` (axis angles, rad), all at one scale: `postures`
/// (every posture) and `posture_<i>` (each alone, i from 01), numbered from 1 as in `plan.csv`.
pub fn each<'a>(setup: &'a Setup, postures: &[Vector6<f64>]) -> Vec<Drawing<'a>> {
    let range = data_range(setup, postures.iter());
    let numbered: Vec<(usize, Vector6<f64>)> = postures
        .iter()
        .copied()
        .enumerate()
        .map(|(i, q)| (i + 1, q))
        .collect();
    let legend = "side view (x-z) and top view (x-y), base frame, m, to scale. Shaded: the robot \
                  and tool bodies (capsules, or the robot's own collision shapes); lines: base, joint origins, flange, tool centre point \
                  (numbered); squares: loading point; grey: the rope to the anchor (star); dashed: \
                  the tracker's lines of sight (triangle); boxes: obstacles; the floor (or the \
                  base plane z = 0).";
    // Every posture alone after the group.
    (0..=numbered.len())
        .map(|k| match k {
            0 => Drawing::new(
                "postures",
                &format!(
                    "The robot in the {} postures of the plan, {legend}",
                    postures.len()
                ),
                Postures::new(setup, "every posture", numbered.clone(), range),
            ),
            _ => {
                let (number, q) = numbered[k - 1];
                Drawing::new(
                    &format!("posture_{number:02}"),
                    &format!("Posture {number}, {legend}"),
                    Postures::new(
                        setup,
                        &format!("posture {number}"),
                        vec![(number, q)],
                        range,
                    ),
                )
            }
        })
        .collect()
}

/// The box (m, (min, max) per axis) of the robot in `postures` (its chain, widened by the largest
/// body radius, and 0.2 m), the anchor, the base origin, the cell's obstacles and the tracker.
pub fn data_range<'p>(
    setup: &Setup,
    postures: impl Iterator<Item = &'p Vector6<f64>>,
) -> [(f64, f64); 3] {
    let mut range = [(f64::INFINITY, f64::NEG_INFINITY); 3];
    let obstacles = setup
        .cell()
        .into_iter()
        .flat_map(|c| c.obstacles.iter().flat_map(|o| [o.min, o.max]));
    let points = postures
        .map(|q| stick(setup, q))
        .flat_map(|s| s.chain.into_iter().chain([s.loading_point]))
        .chain([setup.load().anchor, Vector3::zeros()])
        .chain(obstacles)
        .chain(setup.tracker().into_iter().map(|t| t.position));
    for p in points {
        for (a, r) in range.iter_mut().enumerate() {
            *r = (r.0.min(p[a]), r.1.max(p[a]));
        }
    }
    let g = &setup.geometry();
    let mut margin = 0.2 + g.link_radii.iter().fold(g.tool_radius, |a, &b| a.max(b));
    if let Some(shapes) = setup.shapes() {
        // A shape reaches its bounding sphere's radius beyond its centre, and the centre lies
        // within its origin's offset of the chain.
        let reach = shapes
            .shapes
            .iter()
            .map(|s| s.bound.0.norm() + s.bound.1)
            .fold(0.0, f64::max);
        margin = margin.max(0.2 + reach);
    }
    range.map(|(lo, hi)| (lo - margin, hi + margin))
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

/// The outline of a body's projection on the view's plane (x against axis `v`), m.
fn outline(body: &Body, v: usize) -> Vec<(f64, f64)> {
    body.outline(&Vector3::x(), &Vector3::ith(v, 1.0), 48)
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
        let root = root
            .titled(&self.title, ("sans-serif", 22))
            .map_err(failed)?;
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
        self.cell(&mut chart, v, xr)?;
        for (number, q) in &self.postures {
            self.posture(&mut chart, v, *number, q)?;
        }
        let setup = self.setup;
        let anchor = (setup.load().anchor.x, setup.load().anchor[v]);
        chart
            .draw_series([EmptyElement::at(anchor) + Text::new("*", (-6, -12), ("sans-serif", 28))])
            .map_err(failed)?;
        Ok(())
    }

    /// The floor (or, without one, the base plane z = 0) in the side view, the obstacles and the
    /// tracker.
    fn cell<DB: DrawingBackend>(
        &self,
        chart: &mut Projection<'_, DB>,
        v: usize,
        xr: (f64, f64),
    ) -> Result<()> {
        let cell = self.setup.cell();
        let base_frames = self.setup.robot().frames(&Vector6::zeros());
        let base = bodies(self.setup.arm(), &base_frames)
            .into_iter()
            .filter(|b| b.part() == Part::Base);
        for body in base {
            let outline = outline(&body, v);
            chart
                .draw_series([Polygon::new(outline, BLACK.mix(0.15).filled())])
                .map_err(failed)?;
        }
        if v == 2 {
            let (z, label) = match cell.and_then(|c| c.floor_z) {
                Some(z) => (z, "floor"),
                None => (0.0, ""),
            };
            chart
                .draw_series(LineSeries::new(
                    [(xr.0, z), (xr.1, z)],
                    ShapeStyle::from(BLACK.mix(0.5)).stroke_width(if label.is_empty() {
                        1
                    } else {
                        2
                    }),
                ))
                .map_err(failed)?;
            chart
                .draw_series([
                    EmptyElement::at((xr.0, z)) + Text::new(label, (6, 4), ("sans-serif", 14))
                ])
                .map_err(failed)?;
        }
        for o in cell.map_or(&[][..], |c| &c.obstacles[..]) {
            let corners = [(o.min.x, o.min[v]), (o.max.x, o.max[v])];
            chart
                .draw_series([Rectangle::new(corners, BLACK.mix(0.12).filled())])
                .map_err(failed)?;
            chart
                .draw_series([Rectangle::new(corners, ShapeStyle::from(BLACK.mix(0.6)))])
                .map_err(failed)?;
            chart
                .draw_series([EmptyElement::at((o.min.x, o.max[v]))
                    + Text::new(o.name.clone(), (3, 3), ("sans-serif", 13))])
                .map_err(failed)?;
        }
        if let Some(t) = &self.setup.tracker() {
            let at = (t.position.x, t.position[v]);
            chart
                .draw_series([EmptyElement::at(at)
                    + TriangleMarker::new((0, 0), 7, BLACK.filled())
                    + Text::new("tracker", (8, -6), ("sans-serif", 14))])
                .map_err(failed)?;
        }
        Ok(())
    }

    /// One posture: its bodies (their projections, true to scale: capsules or the robot's own
    /// collision shapes), the chain of joint origins,
    /// the loading point and rope, the lines of sight, the number.
    fn posture<DB: DrawingBackend>(
        &self,
        chart: &mut Projection<'_, DB>,
        v: usize,
        number: usize,
        q: &Vector6<f64>,
    ) -> Result<()> {
        let setup = self.setup;
        let frames = setup.robot().frames(q);
        let c = colour(number);
        let project = |p: &Vector3<f64>| (p.x, p[v]);
        let moving = bodies(setup.arm(), &frames)
            .into_iter()
            .filter(|b| b.part() != Part::Base);
        for body in moving {
            let outline = outline(&body, v);
            chart
                .draw_series([Polygon::new(outline, c.mix(0.2).filled())])
                .map_err(failed)?;
        }
        let s = stick(setup, q);
        let lp = project(&s.loading_point);
        let anchor = project(&setup.load().anchor);
        chart
            .draw_series(LineSeries::new(
                [lp, anchor],
                ShapeStyle::from(BLACK.mix(0.35)),
            ))
            .map_err(failed)?;
        if let Some(t) = &setup.tracker() {
            for p in &setup.tool().measuring_points {
                chart
                    .draw_series(DashedLineSeries::new(
                        [project(&t.position), project(&frames.point(p))],
                        3,
                        5,
                        ShapeStyle::from(colour(6).mix(0.6)),
                    ))
                    .map_err(failed)?;
            }
        }
        let pts = draw_stick(chart, &s, v, c)?;
        chart
            .draw_series([EmptyElement::at(lp) + Rectangle::new([(-4, -4), (4, 4)], c.filled())])
            .map_err(failed)?;
        let tip = pts[pts.len() - 1];
        chart
            .draw_series([EmptyElement::at(tip)
                + Text::new(
                    format!("{number}"),
                    (6, -18),
                    ("sans-serif", 18).into_font().color(&c),
                )])
            .map_err(failed)?;
        Ok(())
    }
}
