//! The physical cell of a setup: floor, obstacles, body radii and the laser tracker (all optional;
//! base frame, mm in the file, m inside).
//!
//! ```toml
//! [cell]
//! floor_z_mm = 0.0                  # no body below floor_z_mm + clearance_mm
//! clearance_mm = 50.0               # smallest distance between bodies that must not touch
//! [[cell.obstacle]]                 # axis-aligned boxes: tables, fixtures, the tracker stand
//! name = "table"
//! min_mm = [1200, -400, 0]
//! max_mm = [1800, 400, 750]
//! # carried_by = "rotate"           # a positioner axis: the box turns with the part
//! [robot_geometry]                  # capsule radii (default: scaled to the robot's size)
//! link_radius_mm = [350, 260, 195, 175, 130, 110, 90]   # base, links 1-6
//! tool_radius_mm = 150
//! [tracker]
//! position_mm = [3000, -2000, 1500]  # or the translation of base_from_tracker
//! # base_from_tracker = { xyz_mm = [3000, -2000, 1500], rpy_deg = [0, 0, 180] }
//! #   the tracker's frame: measurement files may give displacements in it (dx_tracker_mm, ...)
//! max_incidence_deg = 30            # SMR acceptance half-angle; needs no other field
//! measuring_normals = [[0, 0, 1]]   # per measuring point, flange frame; default flange z
//! ```

use super::{invalid, RobotGeometry};
use crate::{common::limits, Result};
use nalgebra::{Isometry3, Vector3};

/// Most obstacles a cell may list.
pub(crate) const MAX_OBSTACLES: usize = 100;

/// Largest clearance, link radius or tool radius accepted, mm (10 m: beyond any industrial cell).
pub(crate) const MAX_LENGTH_MM: f64 = 10_000.0;

/// The cell around the robot (docs/guide.md, "The cell"), base frame, m.
#[derive(Debug, Clone, PartialEq)]
pub struct Cell {
    /// Height of the floor (base z), m; `None`: no floor check.
    pub floor_z: Option<f64>,
    /// Smallest allowed distance between bodies that must not touch, m (default 0).
    pub clearance: f64,
    /// Boxes the robot, the tool and the rope must clear: fixed, or carried by a positioner
    /// axis ([`Obstacle::carried_by`], [`Cell::obstacles_at`]).
    pub obstacles: Vec<Obstacle>,
}

/// A box of the cell (table, fixture, tracker stand): axis-aligned in its own frame, which
/// stands at [`Obstacle::pose`] in the cell (base frame), m.
#[derive(Debug, Clone, PartialEq)]
pub struct Obstacle {
    /// Its name in reports.
    pub name: String,
    /// Lowest corner, its own frame, m.
    pub min: Vector3<f64>,
    /// Highest corner, its own frame, m (every coordinate above `min`'s).
    pub max: Vector3<f64>,
    /// The name of the positioner axis (an `[[external_axis]]` of role positioner) that
    /// carries it, as the part is carried: with the cell's external axes at `e` it stands at
    /// `P_j(e) * pose`, `P_j` the positioner's pose through that axis (the axes before it in
    /// the chain included, [`Obstacle::at`]); `None`: it stands in the cell. A track carries
    /// the arm, not obstacles.
    pub carried_by: Option<String>,
    /// Its frame in the cell (cell frame from its own), m: the identity for a box of a setup
    /// file (an axis-aligned box, a carried one as given at `e = 0` with zero offsets, the frame
    /// the part's points are given in); a carried box frozen at a station ([`Obstacle::at`])
    /// is turned.
    pub pose: Isometry3<f64>,
}

impl Obstacle {
    /// A fixed axis-aligned box between the corners `min` and `max` (cell frame, m).
    pub fn fixed(name: impl Into<String>, min: Vector3<f64>, max: Vector3<f64>) -> Self {
        Self {
            name: name.into(),
            min,
            max,
            carried_by: None,
            pose: Isometry3::identity(),
        }
    }

    /// Whether the point `p` (cell frame, m) lies inside the box or on its boundary.
    pub(crate) fn contains(&self, p: &Vector3<f64>) -> bool {
        let p = self.local(p);
        (0..3).all(|i| p[i] >= self.min[i] && p[i] <= self.max[i])
    }

    /// The point of the box nearest `p` (cell frame, m): `p` itself inside.
    pub(crate) fn nearest(&self, p: &Vector3<f64>) -> Vector3<f64> {
        let inside = (self.local(p)).zip_zip_map(&self.min, &self.max, |v, lo, hi| v.clamp(lo, hi));
        match self.turned() {
            false => inside,
            true => (self.pose * nalgebra::Point3::from(inside)).coords,
        }
    }

    /// Whether its frame is not the cell's (a box to turn into its frame for a distance).
    pub(crate) fn turned(&self) -> bool {
        self.pose != Isometry3::identity()
    }

    /// `p` (cell frame) in the box's own frame.
    fn local(&self, p: &Vector3<f64>) -> Vector3<f64> {
        match self.turned() {
            false => *p,
            true => {
                self.pose
                    .inverse_transform_point(&nalgebra::Point3::from(*p))
                    .coords
            }
        }
    }
}

/// The laser tracker that measures the measuring points.
#[derive(Debug, Clone, PartialEq)]
pub struct Tracker {
    /// Position of the tracker head, base frame, m.
    pub position: Vector3<f64>,
    /// Largest angle between a measuring point's normal and its line of sight to the tracker
    /// (SMR acceptance half-angle), rad; `None`: not checked.
    pub max_incidence: Option<f64>,
    /// Outward unit normal of every measuring point, flange frame: one per measuring point, or
    /// none for the flange z axis at every point (normalised when the setup is built).
    pub measuring_normals: Vec<Vector3<f64>>,
    /// The tracker frame in the robot base frame (m), to turn displacements measured in the
    /// tracker frame into the base frame ([`crate::observation::frames`]); `None` if not given.
    pub base_from_tracker: Option<Isometry3<f64>>,
    /// How far the tracker may be from where the setup puts it, m
    /// (`registration_uncertainty_mm`, 0 to [`limits::MARGIN_MM`]; `stiffid register` writes
    /// three standard deviations of the registered position): the margin a design keeps to
    /// every constraint of the cell unless one is stated
    /// (`stiffid_design::SearchOptions::margin`); `None`: not given.
    pub registration_uncertainty: Option<f64>,
}

/// The numbers of a field for messages, shortened.
fn shown(values: &[f64]) -> String {
    let text: Vec<String> = values
        .iter()
        .take(7)
        .map(|v| crate::common::words::number(*v))
        .collect();
    let more = if values.len() > 7 { ", ..." } else { "" };
    format!("[{}{more}]", text.join(", "))
}

/// The SI vector `v` in mm, for messages.
fn in_mm(v: &Vector3<f64>) -> [f64; 3] {
    [v.x * 1e3, v.y * 1e3, v.z * 1e3]
}

/// A position (mm) within the cell's reach: [`limits::LENGTH_MM`] (100 m), the range of every
/// length of a robot file.
pub(super) fn position(field: &str, values_mm: &[f64]) -> Result<()> {
    limits::check(field, values_mm, &limits::LENGTH_MM)
}

/// A length `v` (m) in `[0, MAX_LENGTH_MM]` mm (0 excluded when `open`).
fn length(field: &str, v: f64, open: bool) -> Result<()> {
    let v = v * 1e3;
    let above = if open { v > 0.0 } else { v >= 0.0 };
    if above && v <= MAX_LENGTH_MM {
        return Ok(());
    }
    let low = if open { "> 0" } else { ">= 0" };
    Err(invalid(
        field,
        format!(
            "{} given: expected a length {low} and <= {MAX_LENGTH_MM} mm",
            crate::common::words::number(v)
        ),
    ))
}

/// Checks a cell: floor height within [`limits::LENGTH_MM`], clearance within [`MAX_LENGTH_MM`],
/// at most [`MAX_OBSTACLES`] named boxes, each with corners within [`limits::LENGTH_MM`] and
/// every min below its max.
pub(super) fn check_cell(c: &Cell) -> Result<()> {
    if let Some(z) = c.floor_z {
        position("cell.floor_z_mm", &[z * 1e3])?;
    }
    length("cell.clearance_mm", c.clearance, false)?;
    if c.obstacles.len() > MAX_OBSTACLES {
        return Err(invalid(
            "cell.obstacle",
            format!("{} boxes given: at most {MAX_OBSTACLES}", c.obstacles.len()),
        ));
    }
    c.obstacles
        .iter()
        .enumerate()
        .try_for_each(|(i, o)| check_obstacle(o, &format!("cell.obstacle[{}]", i + 1)))
}

fn check_obstacle(o: &Obstacle, field: &str) -> Result<()> {
    if o.name.trim().is_empty() {
        return Err(invalid(&format!("{field}.name"), "expected a name"));
    }
    let (min, max) = (in_mm(&o.min), in_mm(&o.max));
    position(&format!("{field}.min_mm"), &min)?;
    position(&format!("{field}.max_mm"), &max)?;
    if (0..3).any(|i| min[i] >= max[i]) {
        return Err(invalid(
            field,
            format!(
                "min_mm {} and max_mm {}: expected every min below its max",
                shown(&min),
                shown(&max)
            ),
        ));
    }
    Ok(())
}

/// Checks every radius: a length in `(0, MAX_LENGTH_MM]` mm.
pub(super) fn check_geometry(g: &RobotGeometry) -> Result<()> {
    for (i, r) in g.link_radii.iter().enumerate() {
        length(
            &format!("robot_geometry.link_radius_mm[{}]", i + 1),
            *r,
            true,
        )?;
    }
    length("robot_geometry.tool_radius_mm", g.tool_radius, true)
}

/// The tracker checked, its normals made unit (the flange z axis for each of the
/// `measuring_points` if none are given): a `base_from_tracker` whose translation is the
/// position (to 1 mm), a position within [`limits::LENGTH_MM`] outside every obstacle of the cell, an incidence in
/// `(0, 90]` deg, one finite non-zero normal per measuring point.
pub(super) fn checked_tracker(
    mut t: Tracker,
    measuring_points: usize,
    cell: Option<&Cell>,
) -> Result<Tracker> {
    let position_mm = in_mm(&t.position);
    if let Some(b) = &t.base_from_tracker {
        let xyz = in_mm(&b.translation.vector);
        position("tracker.base_from_tracker.xyz_mm", &xyz)?;
        if (0..3).any(|i| (position_mm[i] - xyz[i]).abs() > 1.0) {
            return Err(invalid(
                "tracker.position_mm",
                format!(
                    "{} given: expected the translation of base_from_tracker, {} (or leave one out)",
                    shown(&position_mm),
                    shown(&xyz)
                ),
            ));
        }
    }
    position("tracker.position_mm", &position_mm)?;
    if let Some(o) = cell.and_then(|c| c.obstacles.iter().find(|o| o.contains(&t.position))) {
        return Err(invalid(
            "tracker.position_mm",
            format!(
                "{} is inside obstacle '{}': every line of sight would be blocked",
                shown(&position_mm),
                o.name
            ),
        ));
    }
    if let Some(a) = t.max_incidence
        && !(a > 0.0 && a.to_degrees() <= 90.0)
    {
        return Err(invalid(
            "tracker.max_incidence_deg",
            format!(
                "{} given: expected an angle in (0, 90] deg",
                crate::common::words::number(a.to_degrees())
            ),
        ));
    }
    t.measuring_normals = normals(&t.measuring_normals, measuring_points)?;
    Ok(t)
}

fn normals(given: &[Vector3<f64>], count: usize) -> Result<Vec<Vector3<f64>>> {
    if given.is_empty() {
        return Ok(vec![Vector3::z(); count]);
    }
    if given.len() != count {
        return Err(invalid(
            "tracker.measuring_normals",
            format!(
                "{} given: expected one per measuring point ({count})",
                given.len()
            ),
        ));
    }
    given
        .iter()
        .enumerate()
        .map(|(i, n)| {
            let field = format!("tracker.measuring_normals[{}]", i + 1);
            position(&field, n.as_slice())?;
            n.try_normalize(1e-12).ok_or_else(|| {
                invalid(
                    &field,
                    format!(
                        "{} given: expected a non-zero direction",
                        shown(n.as_slice())
                    ),
                )
            })
        })
        .collect()
}
