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

use super::{field_error, mm};
use crate::robot::file::TransformFile;
use crate::{limits, Result};
use nalgebra::{Isometry3, Vector3};
use serde::Deserialize;

/// Most obstacles a cell may list.
pub const MAX_OBSTACLES: usize = 100;

/// Largest clearance, link radius or tool radius accepted, mm (10 m: beyond any industrial cell).
pub const MAX_LENGTH_MM: f64 = 10_000.0;

/// The cell around the robot (Section "The cell model" of the README), base frame, m.
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
    /// Outward unit normal of every measuring point, flange frame (default the flange z axis).
    pub measuring_normals: Vec<Vector3<f64>>,
    /// The tracker frame in the robot base frame (m), to turn displacements measured in the
    /// tracker frame into the base frame ([`crate::identify::frames`]); `None` if not given.
    pub base_from_tracker: Option<Isometry3<f64>>,
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
    min_mm: [f64; 3],
    max_mm: [f64; 3],
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct GeometryFile {
    link_radius_mm: Option<[f64; 7]>,
    tool_radius_mm: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct TrackerFile {
    position_mm: Option<[f64; 3]>,
    max_incidence_deg: Option<f64>,
    measuring_normals: Option<Vec<[f64; 3]>>,
    base_from_tracker: Option<TransformFile>,
}

/// The numbers of a field for messages, shortened.
fn shown(values: &[f64]) -> String {
    let text: Vec<String> = values.iter().take(7).map(|v| limits::number(*v)).collect();
    let more = if values.len() > 7 { ", ..." } else { "" };
    format!("[{}{more}]", text.join(", "))
}

fn finite(src: &str, field: &str, values: &[f64]) -> Result<()> {
    match values.iter().all(|v| v.is_finite()) {
        true => Ok(()),
        false => Err(field_error(
            src,
            field,
            format!("{} given: expected finite numbers", shown(values)),
        )),
    }
}

/// A length in `[lowest, MAX_LENGTH_MM]` mm (`lowest` excluded when `open`).
fn length(src: &str, field: &str, v: f64, open: bool) -> Result<f64> {
    let above = if open { v > 0.0 } else { v >= 0.0 };
    if above && v <= MAX_LENGTH_MM {
        return Ok(v * 1e-3);
    }
    let low = if open { "> 0" } else { ">= 0" };
    Err(field_error(
        src,
        field,
        format!(
            "{} given: expected a length {low} and <= {MAX_LENGTH_MM} mm",
            limits::number(v)
        ),
    ))
}

pub(super) fn cell(f: CellFile, src: &str) -> Result<Cell> {
    if let Some(z) = f.floor_z_mm {
        finite(src, "cell.floor_z_mm", &[z])?;
    }
    let clearance = length(
        src,
        "cell.clearance_mm",
        f.clearance_mm.unwrap_or(0.0),
        false,
    )?;
    if f.obstacle.len() > MAX_OBSTACLES {
        return Err(field_error(
            src,
            "cell.obstacle",
            format!("{} boxes given: at most {MAX_OBSTACLES}", f.obstacle.len()),
        ));
    }
    let obstacles = f
        .obstacle
        .iter()
        .enumerate()
        .map(|(i, o)| obstacle(o, &format!("cell.obstacle[{}]", i + 1), src))
        .collect::<Result<_>>()?;
    Ok(Cell {
        floor_z: f.floor_z_mm.map(|z| z * 1e-3),
        clearance,
        obstacles,
    })
}

fn obstacle(o: &ObstacleFile, field: &str, src: &str) -> Result<Obstacle> {
    if o.name.trim().is_empty() {
        return Err(field_error(
            src,
            &format!("{field}.name"),
            "expected a name",
        ));
    }
    finite(src, &format!("{field}.min_mm"), &o.min_mm)?;
    finite(src, &format!("{field}.max_mm"), &o.max_mm)?;
    if (0..3).any(|i| o.min_mm[i] >= o.max_mm[i]) {
        return Err(field_error(
            src,
            field,
            format!(
                "min_mm {} and max_mm {}: expected every min below its max",
                shown(&o.min_mm),
                shown(&o.max_mm)
            ),
        ));
    }
    Ok(Obstacle {
        name: o.name.clone(),
        min: mm(&o.min_mm),
        max: mm(&o.max_mm),
    })
}

/// The radii of the file, or `defaults` (m) where it gives none.
pub(super) fn geometry(
    f: Option<GeometryFile>,
    defaults: RobotGeometry,
    src: &str,
) -> Result<RobotGeometry> {
    let Some(f) = f else {
        return Ok(defaults);
    };
    let mut g = defaults;
    if let Some(radii) = f.link_radius_mm {
        for (i, r) in radii.iter().enumerate() {
            let field = format!("robot_geometry.link_radius_mm[{}]", i + 1);
            g.link_radii[i] = length(src, &field, *r, true)?;
        }
    }
    if let Some(r) = f.tool_radius_mm {
        g.tool_radius = length(src, "robot_geometry.tool_radius_mm", r, true)?;
    }
    Ok(g)
}

pub(super) fn tracker(
    f: TrackerFile,
    measuring_points: usize,
    cell: Option<&Cell>,
    src: &str,
) -> Result<Tracker> {
    let base_from_tracker = match &f.base_from_tracker {
        None => None,
        Some(t) => {
            finite(src, "tracker.base_from_tracker.xyz_mm", &t.xyz_mm)?;
            finite(src, "tracker.base_from_tracker.rpy_deg", &t.rpy_deg)?;
            Some(t.isometry())
        }
    };
    let position_mm = position_mm(&f, src)?;
    let position = mm(&position_mm);
    if let Some(o) = cell.and_then(|c| c.obstacles.iter().find(|o| o.contains(&position))) {
        return Err(field_error(
            src,
            "tracker.position_mm",
            format!(
                "{} is inside obstacle '{}': every line of sight would be blocked",
                shown(&position_mm),
                o.name
            ),
        ));
    }
    let max_incidence = match f.max_incidence_deg {
        None => None,
        Some(a) if a > 0.0 && a <= 90.0 => Some(a.to_radians()),
        Some(a) => {
            return Err(field_error(
                src,
                "tracker.max_incidence_deg",
                format!(
                    "{} given: expected an angle in (0, 90] deg",
                    limits::number(a)
                ),
            ))
        }
    };
    let measuring_normals = normals(f.measuring_normals, measuring_points, src)?;
    Ok(Tracker {
        position,
        max_incidence,
        measuring_normals,
        base_from_tracker,
    })
}

/// The tracker position, mm: `position_mm`, or the translation of `base_from_tracker`; both given
/// must agree to 1 mm.
fn position_mm(f: &TrackerFile, src: &str) -> Result<[f64; 3]> {
    let from_transform = f.base_from_tracker.map(|t| t.xyz_mm);
    let position = match (f.position_mm, from_transform) {
        (Some(p), Some(t)) if (0..3).any(|i| (p[i] - t[i]).abs() > 1.0) => {
            return Err(field_error(
                src,
                "tracker.position_mm",
                format!(
                    "{} given: expected the translation of base_from_tracker, {} (or leave one out)",
                    shown(&p),
                    shown(&t)
                ),
            ))
        }
        (Some(p), _) | (None, Some(p)) => p,
        (None, None) => {
            return Err(field_error(
                src,
                "tracker",
                "expected position_mm or base_from_tracker",
            ))
        }
    };
    finite(src, "tracker.position_mm", &position)?;
    Ok(position)
}

fn normals(given: Option<Vec<[f64; 3]>>, count: usize, src: &str) -> Result<Vec<Vector3<f64>>> {
    let Some(given) = given else {
        return Ok(vec![Vector3::z(); count]);
    };
    if given.len() != count {
        return Err(field_error(
            src,
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
            finite(src, &field, n)?;
            Vector3::from_column_slice(n)
                .try_normalize(1e-12)
                .ok_or_else(|| {
                    field_error(
                        src,
                        &field,
                        format!("{} given: expected a non-zero direction", shown(n)),
                    )
                })
        })
        .collect()
}
