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

use super::file::mm;
use super::{invalid, SetupBuilder, Tool};
use crate::robot::file::TransformFile;
use crate::robot::parts::polylines;
use crate::Robot;
use crate::{common::limits, Result};
use nalgebra::{Isometry3, Vector3, Vector6};
use serde::Deserialize;

/// Most obstacles a cell may list.
pub const MAX_OBSTACLES: usize = 100;

/// Largest clearance, link radius or tool radius accepted, mm (10 m: beyond any industrial cell).
pub const MAX_LENGTH_MM: f64 = 10_000.0;

/// The cell around the robot (docs/guide.md, "The cell"), base frame, m.
#[derive(Debug, Clone, PartialEq)]
pub struct Cell {
    /// Height of the floor (base z), m; `None`: no floor check.
    pub floor_z: Option<f64>,
    /// Smallest allowed distance between bodies that must not touch, m (default 0).
    pub clearance: f64,
    /// Axis-aligned boxes the robot, the tool and the rope must clear.
    pub obstacles: Vec<Obstacle>,
}

/// An axis-aligned box of the cell (table, fixture, tracker stand), base frame, m.
#[derive(Debug, Clone, PartialEq)]
pub struct Obstacle {
    /// Its name in reports.
    pub name: String,
    /// Lowest corner, m.
    pub min: Vector3<f64>,
    /// Highest corner, m (every coordinate above `min`'s).
    pub max: Vector3<f64>,
}

impl Obstacle {
    /// Whether the point `p` (m) lies inside the box or on its boundary.
    pub fn contains(&self, p: &Vector3<f64>) -> bool {
        (0..3).all(|i| p[i] >= self.min[i] && p[i] <= self.max[i])
    }
}

/// Capsule radii of the robot bodies, m (see [`crate::cell::capsules`]).
#[derive(Debug, Clone, PartialEq)]
pub struct RobotGeometry {
    /// Radii of the base and of links 1-6, m.
    pub link_radii: [f64; 7],
    /// Radius of the tool capsule, m.
    pub tool_radius: f64,
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
    /// ([`crate::design::SearchOptions::margin`]); `None`: not given.
    pub registration_uncertainty: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CellFile {
    floor_z_mm: Option<f64>,
    clearance_mm: Option<f64>,
    #[serde(default)]
    obstacle: Vec<ObstacleFile>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ObstacleFile {
    name: String,
    #[serde(deserialize_with = "crate::common::exact::array")]
    min_mm: [f64; 3],
    #[serde(deserialize_with = "crate::common::exact::array")]
    max_mm: [f64; 3],
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct GeometryFile {
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    link_radius_mm: Option<[f64; 7]>,
    tool_radius_mm: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct TrackerFile {
    #[serde(default, deserialize_with = "crate::common::exact::option")]
    position_mm: Option<[f64; 3]>,
    max_incidence_deg: Option<f64>,
    #[serde(default, deserialize_with = "crate::common::exact::option_arrays")]
    measuring_normals: Option<Vec<[f64; 3]>>,
    base_from_tracker: Option<TransformFile>,
    registration_uncertainty_mm: Option<f64>,
}

/// The numbers of a field for messages, shortened.
fn shown(values: &[f64]) -> String {
    let text: Vec<String> = values.iter().take(7).map(|v| limits::number(*v)).collect();
    let more = if values.len() > 7 { ", ..." } else { "" };
    format!("[{}{more}]", text.join(", "))
}

/// The SI vector `v` in mm, for messages.
fn in_mm(v: &Vector3<f64>) -> [f64; 3] {
    [v.x * 1e3, v.y * 1e3, v.z * 1e3]
}

/// A position (mm) within the cell's reach: [`limits::LENGTH_MM`] (100 m), the range of every
/// length of a robot file.
fn position(field: &str, values_mm: &[f64]) -> Result<()> {
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
            limits::number(v)
        ),
    ))
}

/// The `[cell]` table in SI units (checked by [`check_cell`] when the setup is built).
pub(super) fn cell(f: CellFile) -> Cell {
    Cell {
        floor_z: f.floor_z_mm.map(|z| z * 1e-3),
        clearance: f.clearance_mm.unwrap_or(0.0) * 1e-3,
        obstacles: f
            .obstacle
            .into_iter()
            .map(|o| Obstacle {
                name: o.name,
                min: mm(&o.min_mm),
                max: mm(&o.max_mm),
            })
            .collect(),
    }
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

/// The builder with the radii the file gives.
pub(super) fn geometry(f: GeometryFile, mut b: SetupBuilder) -> SetupBuilder {
    if let Some(radii) = f.link_radius_mm {
        b = b.with_link_radii(radii.map(|r| r * 1e-3));
    }
    if let Some(r) = f.tool_radius_mm {
        b = b.with_tool_radius(r * 1e-3);
    }
    b
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

/// The `[tracker]` table in SI units: the position is `position_mm`, or the translation of
/// `base_from_tracker` (checked by [`checked_tracker`] when the setup is built).
pub(super) fn tracker(f: TrackerFile) -> Result<Tracker> {
    if let Some(t) = &f.base_from_tracker {
        position("tracker.base_from_tracker.xyz_mm", &t.xyz_mm)?;
        let rpy = &limits::ANGLE_DEG;
        limits::check("tracker.base_from_tracker.rpy_deg", &t.rpy_deg, rpy)?;
    }
    if let Some(u) = f.registration_uncertainty_mm {
        limits::check(
            "tracker.registration_uncertainty_mm",
            &[u],
            &limits::MARGIN_MM,
        )?;
    }
    let base_from_tracker = f.base_from_tracker.map(|t| t.isometry());
    let position = match (f.position_mm, &base_from_tracker) {
        (Some(p), _) => mm(&p),
        (None, Some(t)) => t.translation.vector,
        (None, None) => {
            return Err(invalid(
                "tracker",
                "expected position_mm or base_from_tracker",
            ))
        }
    };
    Ok(Tracker {
        position,
        max_incidence: f.max_incidence_deg.map(f64::to_radians),
        measuring_normals: f
            .measuring_normals
            .map_or(Vec::new(), |n| n.into_iter().map(Vector3::from).collect()),
        base_from_tracker,
        registration_uncertainty: f.registration_uncertainty_mm.map(|u| u * 1e-3),
    })
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
    if let Some(a) = t.max_incidence {
        if !(a > 0.0 && a.to_degrees() <= 90.0) {
            return Err(invalid(
                "tracker.max_incidence_deg",
                format!(
                    "{} given: expected an angle in (0, 90] deg",
                    limits::number(a.to_degrees())
                ),
            ));
        }
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

/// Default radius of the base and links 1-6 as a fraction of the robot's size (the total length
/// of its capsule segments): 8, 6, 4.5, 4, 3, 2.5 and 2 %.
pub const DEFAULT_RADIUS_FRACTIONS: [f64; 7] = [0.08, 0.06, 0.045, 0.04, 0.03, 0.025, 0.02];

/// Smallest default tool radius, m (10 mm).
pub const MIN_TOOL_RADIUS: f64 = 0.01;

/// The default [`RobotGeometry`] of a robot and tool: link radii
/// [`DEFAULT_RADIUS_FRACTIONS`] of the robot's size (the summed length of its base and link
/// segments, the same in every posture; 4.33 m and radii 346, 260, 195, 173, 130, 108, 87 mm for
/// the COMAU NJ 165), and [`default_tool_radius`].
pub fn default_geometry(robot: &Robot, tool: &Tool) -> RobotGeometry {
    let frames = robot.frames(&Vector6::zeros());
    let size: f64 = polylines(&frames)
        .iter()
        .flat_map(|(_, p)| p.windows(2).map(|w| (w[1] - w[0]).norm()))
        .sum();
    RobotGeometry {
        link_radii: DEFAULT_RADIUS_FRACTIONS.map(|f| f * size),
        tool_radius: default_tool_radius(tool),
    }
}

/// The default radius of the tool body, m: half the distance of the nearest measuring point from
/// the flange z axis, at least [`MIN_TOOL_RADIUS`]. The measuring points (reflectors) sit on the
/// outside of the tool, so a body that reached them would hide them from the tracker: the tool
/// capsule stands for the spindle or the bar that carries them, not for their envelope.
pub fn default_tool_radius(tool: &Tool) -> f64 {
    (0.5 * nearest_measuring_point(tool)).max(MIN_TOOL_RADIUS)
}

/// The distance of the measuring point nearest the flange z axis from it, m (infinite without
/// measuring points).
pub fn nearest_measuring_point(tool: &Tool) -> f64 {
    (tool.measuring_points.iter())
        .map(|p| p.xy().norm())
        .fold(f64::INFINITY, f64::min)
}
