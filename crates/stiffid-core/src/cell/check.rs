//! The kinds of feasibility check a posture must pass in the cell, the setup fields that decide
//! each, and the signed margin of one tested pair ([`Margin`], between two [`Thing`]s).

use super::bodies::Part;
use crate::setup::Setup;
use std::fmt;

/// One kind of feasibility check (the checks 1-6; the body checks split by what they
/// test).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum CheckKind {
    /// 1. Inside the experiment bounds (which lie within the joint limits). Margin in rad.
    Bounds,
    /// 2. No body below `floor_z + clearance` (the base excepted: it stands on the floor). m.
    Floor,
    /// 2. Every body (base included) at least the clearance from every obstacle. m.
    Obstacles,
    /// 3. Non-adjacent links, and the tool against the base and links 1-3, at least the clearance
    ///    apart. m.
    SelfCollision,
    /// 4. The rope (loading point to anchor) at least the clearance from every body and obstacle
    ///    (from the tool only beyond `tool_radius + clearance` of the loading point). m.
    Rope,
    /// 5. The line from the tracker to every measuring point misses every body and obstacle (the
    ///    tool only beyond `tool_radius` of the measuring point). m.
    LineOfSight,
    /// 5. The angle between a measuring point's normal and its line of sight at most
    ///    `max_incidence`. rad.
    Incidence,
    /// 6. `[constraints] loading_point_min_z_mm`. m.
    LoadingPointHeight,
    /// 6. `[constraints] anchor_below_loading_point`. m.
    AnchorBelow,
}

impl CheckKind {
    /// Every kind, in report order.
    pub const ALL: [CheckKind; 9] = [
        CheckKind::Bounds,
        CheckKind::Floor,
        CheckKind::Obstacles,
        CheckKind::SelfCollision,
        CheckKind::Rope,
        CheckKind::LineOfSight,
        CheckKind::Incidence,
        CheckKind::LoadingPointHeight,
        CheckKind::AnchorBelow,
    ];

    /// Its name in reports and JSON, e.g. `self-collision`.
    pub fn key(self) -> &'static str {
        match self {
            CheckKind::Bounds => "bounds",
            CheckKind::Floor => "floor",
            CheckKind::Obstacles => "obstacles",
            CheckKind::SelfCollision => "self-collision",
            CheckKind::Rope => "rope",
            CheckKind::LineOfSight => "line-of-sight",
            CheckKind::Incidence => "incidence",
            CheckKind::LoadingPointHeight => "loading-point-min-z",
            CheckKind::AnchorBelow => "anchor-below-loading-point",
        }
    }

    /// Whether the margin is an angle (rad) rather than a length (m).
    pub fn is_angle(self) -> bool {
        matches!(self, CheckKind::Bounds | CheckKind::Incidence)
    }
}

impl fmt::Display for CheckKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.key())
    }
}

impl CheckKind {
    /// The setup fields that decide this check, with their values, in words: what a user changes
    /// when the check fails in every posture searched (e.g. `[robot_geometry] tool_radius_mm =
    /// 150 (the nearest measuring point is 40 mm off the flange axis) and [tracker] position_mm =
    /// [3000, -2000, 1500]`).
    pub fn remedy(self, setup: &Setup) -> String {
        let mm = |v: f64| format!("{}", round_mm(v));
        let clearance = setup.cell().map_or(0.0, |c| c.clearance);
        let geometry = setup.geometry();
        let radii = || {
            let r: Vec<String> = geometry.link_radii.iter().map(|&v| mm(v)).collect();
            format!(
                "[robot_geometry] link_radius_mm = [{}], tool_radius_mm = {}",
                r.join(", "),
                mm(geometry.tool_radius)
            )
        };
        let clear = format!("[cell] clearance_mm = {}", mm(clearance));
        match self {
            CheckKind::Bounds => "the setup's [bounds] lower_deg and upper_deg".to_string(),
            CheckKind::Floor => {
                let z = setup.cell().and_then(|c| c.floor_z).unwrap_or(0.0);
                format!(
                    "[cell] floor_z_mm = {}, {clear} and the body radii ({})",
                    mm(z),
                    radii()
                )
            }
            CheckKind::Obstacles => {
                let n = setup.cell().map_or(0, |c| c.obstacles.len());
                format!(
                    "the {n} [[cell.obstacle]] boxes, {clear} and the body radii ({})",
                    radii()
                )
            }
            CheckKind::SelfCollision => format!("{clear} and the body radii ({})", radii()),
            CheckKind::Rope => {
                let a = setup.load().anchor;
                format!(
                    "[loading] anchor_mm = [{}, {}, {}], {clear} and the body radii ({})",
                    mm(a.x),
                    mm(a.y),
                    mm(a.z),
                    radii()
                )
            }
            CheckKind::LineOfSight => {
                let nearest = crate::setup::nearest_measuring_point(setup.tool());
                let at = setup.tracker().map(|t| t.position).unwrap_or_default();
                format!(
                    "[tracker] position_mm = [{}, {}, {}], the tool body's \
                     [robot_geometry] tool_radius_mm = {} (the nearest measuring point is {} mm off \
                     the flange axis: a body that holds a reflector hides it) and the cell's boxes",
                    mm(at.x),
                    mm(at.y),
                    mm(at.z),
                    mm(geometry.tool_radius),
                    mm(nearest)
                )
            }
            CheckKind::Incidence => {
                let max = setup.tracker().and_then(|t| t.max_incidence).unwrap_or(0.0);
                format!(
                    "[tracker] max_incidence_deg = {}, measuring_normals and position_mm",
                    (max.to_degrees() * 1e3).round() / 1e3
                )
            }
            CheckKind::LoadingPointHeight => {
                let z = setup.constraints().loading_point_min_z.unwrap_or(0.0);
                format!("[constraints] loading_point_min_z_mm = {}", mm(z))
            }
            CheckKind::AnchorBelow => {
                let z = setup.load().anchor.z;
                format!(
                    "[constraints] anchor_below_loading_point with [loading] anchor_mm at z = {} mm",
                    mm(z)
                )
            }
        }
    }
}

/// A length in m as mm to 0.1 mm.
fn round_mm(v: f64) -> f64 {
    (v * 1e4).round() / 10.0
}

/// What a margin is measured at.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Thing {
    /// A robot or tool body.
    Part(Part),
    /// The floor.
    Floor,
    /// Obstacle i (0-based) of the cell.
    Obstacle(usize),
    /// The rope.
    Rope,
    /// The line of sight to measuring point i (0-based).
    Sight(usize),
    /// Measuring point i (0-based).
    MeasuringPoint(usize),
    /// Axis i (0-based).
    Axis(usize),
    /// The loading point.
    LoadingPoint,
    /// The rope anchor.
    Anchor,
}

impl Thing {
    /// Its name in reports, obstacles by their names in the setup.
    pub(crate) fn name(self, setup: &Setup) -> String {
        match self {
            Thing::Part(p) => p.to_string(),
            Thing::Floor => "floor".into(),
            Thing::Obstacle(i) => setup.cell().map_or_else(
                || format!("obstacle {}", i + 1),
                |c| c.obstacles[i].name.clone(),
            ),
            Thing::Rope => "rope".into(),
            Thing::Sight(i) => format!("line of sight {}", i + 1),
            Thing::MeasuringPoint(i) => format!("measuring point {}", i + 1),
            Thing::Axis(i) => format!("axis {}", i + 1),
            Thing::LoadingPoint => "loading point".into(),
            Thing::Anchor => "anchor".into(),
        }
    }
}

/// The signed margin of one tested pair: `>= 0` satisfied.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Margin {
    /// The check it belongs to.
    pub kind: CheckKind,
    /// Distance (or angle, height) minus what is required: m, or rad for angles.
    pub margin: f64,
    /// What is required on top of contact: the clearance for body checks, plus the margin the
    /// checker keeps ([`Checker::keeping`](super::Checker::keeping)) for every check but the bounds (m; rad for the
    /// incidence).
    pub required: f64,
    /// The pair.
    pub between: (Thing, Thing),
}
