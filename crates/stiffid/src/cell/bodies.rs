//! The robot and tool as capsules: segments with a radius.

use crate::kinematics::Frames;
use crate::setup::{RobotGeometry, Setup, Tool};
use crate::Robot;
use nalgebra::{Vector3, Vector6};
use std::fmt;

/// A part of the robot that carries capsules.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Part {
    /// The fixed base: the column along axis 1 from the base origin's foot on axis 1 up to the
    /// height of joint 2.
    Base,
    /// Moving link 1..=6 (link i turns with axis i).
    Link(usize),
    /// The tool on the flange.
    Tool,
}

impl Part {
    /// Index of the part's radius: 0 the base, i link i, 7 the tool.
    pub fn index(self) -> usize {
        match self {
            Part::Base => 0,
            Part::Link(i) => i,
            Part::Tool => 7,
        }
    }
}

impl fmt::Display for Part {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Part::Base => write!(f, "base"),
            Part::Link(i) => write!(f, "link {i}"),
            Part::Tool => write!(f, "tool"),
        }
    }
}

/// A capsule of a robot part: the points within `radius` of the segment `a`-`b`, base frame, m.
/// A capsule with `a == b` is a ball.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Capsule {
    /// The part it belongs to.
    pub part: Part,
    /// Segment start, base frame, m.
    pub a: Vector3<f64>,
    /// Segment end, base frame, m.
    pub b: Vector3<f64>,
    /// Radius, m.
    pub radius: f64,
}

/// Points closer than this (m) are one point of a part's polyline.
const SAME_POINT: f64 = 1e-9;

/// The body capsules of the posture whose forward kinematics are `frames`, base frame, m, in the
/// order base, links 1-6, tool (one or two capsules per link, the same count in every posture):
///
/// - base: along axis 1 from the foot of the base origin on axis 1 to the foot of joint 2's
///   axis point (the column that carries joint 1);
/// - link 1: from that foot to joint 2's axis point;
/// - link i = 2..6: the polyline joint i's axis point -> joint frame i's origin -> joint i+1's
///   axis point (the flange origin for link 6): for a modified-DH robot `d_i` then `a_i`;
/// - tool: from the flange origin along the flange z axis to the height (flange z) of the tool
///   point farthest along it (loading, measuring and tool centre points).
///
/// Radii from [`RobotGeometry`]. This is what `stiffid plot` draws.
pub fn capsules(setup: &Setup, frames: &Frames) -> Vec<Capsule> {
    let g = &setup.geometry();
    let mut out = Vec::with_capacity(16);
    for (part, points) in polylines(frames) {
        push_polyline(&mut out, part, &points, g.link_radii[part.index()]);
    }
    let tip = frames.point(&Vector3::new(0.0, 0.0, tool_length(setup.tool())));
    out.push(Capsule {
        part: Part::Tool,
        a: frames.flange.translation.vector,
        b: tip,
        radius: g.tool_radius,
    });
    out
}

/// The polyline of every robot part, base then links 1-6.
fn polylines(f: &Frames) -> Vec<(Part, Vec<Vector3<f64>>)> {
    let foot = |p: &Vector3<f64>| {
        let (o, d) = (f.axis_points[0], f.axis_directions[0]);
        o + d * d.dot(&(p - o))
    };
    let shoulder = f.axis_points[1];
    let column_top = foot(&shoulder);
    let mut lines = vec![
        (Part::Base, vec![foot(&Vector3::zeros()), column_top]),
        (Part::Link(1), vec![column_top, shoulder]),
    ];
    for i in 2..=6 {
        let next = match i {
            6 => f.flange.translation.vector,
            _ => f.axis_points[i],
        };
        let points = vec![
            f.axis_points[i - 1],
            f.joints[i - 1].translation.vector,
            next,
        ];
        lines.push((Part::Link(i), points));
    }
    lines
}

/// Adds the segments of a polyline, merging repeated points; a polyline of one point is a ball.
fn push_polyline(out: &mut Vec<Capsule>, part: Part, points: &[Vector3<f64>], radius: f64) {
    let mut distinct: Vec<Vector3<f64>> = Vec::with_capacity(points.len());
    for p in points {
        if distinct.last().is_none_or(|q| (p - q).norm() > SAME_POINT) {
            distinct.push(*p);
        }
    }
    if distinct.len() == 1 {
        distinct.push(distinct[0]);
    }
    for w in distinct.windows(2) {
        out.push(Capsule {
            part,
            a: w[0],
            b: w[1],
            radius,
        });
    }
}

/// The tool capsule's length along the flange z axis: the largest `|z|` of a tool point, signed, m.
fn tool_length(tool: &Tool) -> f64 {
    tool_points(tool)
        .map(|p| p.z)
        .fold(0.0, |best, z| if z.abs() > best.abs() { z } else { best })
}

fn tool_points(tool: &Tool) -> impl Iterator<Item = &Vector3<f64>> {
    std::iter::once(&tool.loading_point)
        .chain(&tool.measuring_points)
        .chain(std::iter::once(&tool.tcp))
}

/// Default radius of the base and links 1-6 as a fraction of the robot's size (the total length
/// of its capsule segments): 8, 6, 4.5, 4, 3, 2.5 and 2 %.
pub const DEFAULT_RADIUS_FRACTIONS: [f64; 7] = [0.08, 0.06, 0.045, 0.04, 0.03, 0.025, 0.02];

/// The default [`RobotGeometry`] of a robot and tool: link radii
/// [`DEFAULT_RADIUS_FRACTIONS`] of the robot's size (the summed length of its base and link
/// segments, the same in every posture; 4.33 m and radii 346, 260, 195, 173, 130, 108, 87 mm for
/// the COMAU NJ 165), and a tool radius that holds every tool point: the largest distance of a
/// tool point from the flange z axis, at least 10 mm.
pub fn default_geometry(robot: &Robot, tool: &Tool) -> RobotGeometry {
    let frames = robot.frames(&Vector6::zeros());
    let size: f64 = polylines(&frames)
        .iter()
        .flat_map(|(_, p)| p.windows(2).map(|w| (w[1] - w[0]).norm()))
        .sum();
    let radial = tool_points(tool)
        .map(|p| p.xy().norm())
        .fold(0.01, f64::max);
    RobotGeometry {
        link_radii: DEFAULT_RADIUS_FRACTIONS.map(|f| f * size),
        tool_radius: radial,
    }
}
