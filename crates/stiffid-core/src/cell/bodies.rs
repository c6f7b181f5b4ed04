//! The robot and tool bodies of a posture: capsules (segments with a radius) along the chain, or
//! the robot's own collision shapes ([`Arm::shapes`]) with the tool's capsule.

use crate::robot::collision::Shape;
use crate::robot::kinematics::Frames;
use crate::robot::parts::polylines;
pub use crate::robot::parts::Part;
use crate::setup::{Arm, Tool};
use nalgebra::{Isometry3, Vector3};

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

/// A collision shape of the robot posed in the base frame (a URDF `<collision>` element).
#[derive(Debug, Clone)]
pub struct Solid {
    /// The part it belongs to (the URDF link's body).
    pub part: Part,
    /// The shape, in its own frame.
    pub shape: Shape,
    /// Its pose, base frame, m.
    pub pose: Isometry3<f64>,
    /// A sphere holding it, base frame: centre and radius, m.
    pub bound: (Vector3<f64>, f64),
}

/// One body of the robot or tool in a posture, base frame.
#[derive(Debug, Clone)]
pub enum Body {
    /// A capsule (the tool's always; the robot's without collision shapes).
    Capsule(Capsule),
    /// A convex collision shape of the robot.
    Solid(Solid),
}

impl Body {
    /// The part it belongs to.
    pub fn part(&self) -> Part {
        match self {
            Body::Capsule(c) => c.part,
            Body::Solid(s) => s.part,
        }
    }

    /// A sphere holding it, base frame: centre and radius, m (for the broad phase).
    pub fn bound(&self) -> (Vector3<f64>, f64) {
        match self {
            Body::Capsule(c) => ((c.a + c.b) / 2.0, (c.b - c.a).norm() / 2.0 + c.radius),
            Body::Solid(s) => s.bound,
        }
    }

    /// The outline of its projection on the plane of the unit vectors `u` and `v` (base frame):
    /// `n` points `(p . u, p . v)`, m, counter-clockwise, each the body's farthest point in a
    /// direction `cos t u + sin t v` (its support point), `t = 2 pi k / n`: the convex outline
    /// a drawing fills, true to scale.
    pub fn outline(&self, u: &Vector3<f64>, v: &Vector3<f64>, n: usize) -> Vec<(f64, f64)> {
        with_parry(self, |shape, pose| {
            let support = shape.as_support_map().expect("every body is convex");
            (0..n)
                .map(|k| {
                    let t = std::f64::consts::TAU * k as f64 / n as f64;
                    let p = support.support_point(pose, &(u * t.cos() + v * t.sin()));
                    (p.coords.dot(u), p.coords.dot(v))
                })
                .collect()
        })
    }

    /// Whether it spans nothing along the chain: a capsule whose segment is a point.
    pub(super) fn degenerate(&self) -> bool {
        matches!(self, Body::Capsule(c) if c.a == c.b)
    }
}

/// The bodies of the posture whose forward kinematics are `frames`, base frame, m: with the
/// robot's collision shapes ([`Arm::shapes`]), each shape posed by its body's frame (the base,
/// or joint frame i for link i) then the tool's capsule ([`capsules`]); else [`capsules`]. The same
/// bodies in the same order in every posture. What the cell's checks and the drawings use. The
/// bodies of an arm on a carrier move with it: give the frames of [`crate::Robot::frames_at`].
pub fn bodies(arm: &Arm, frames: &Frames) -> Vec<Body> {
    let Some(g) = arm.shapes() else {
        return capsules(arm, frames)
            .into_iter()
            .map(Body::Capsule)
            .collect();
    };
    let base = frames.base;
    let mut out: Vec<Body> = g
        .shapes
        .iter()
        .map(|s| {
            let (part, frame) = match s.body {
                0 => (Part::Base, base),
                i => (Part::Link(i), frames.joints[i - 1]),
            };
            Body::Solid(Solid {
                part,
                shape: s.shape.clone(),
                pose: frame * s.origin,
                bound: (
                    (frame * nalgebra::Point3::from(s.bound.0)).coords,
                    s.bound.1,
                ),
            })
        })
        .collect();
    out.push(Body::Capsule(tool_capsule(arm, frames)));
    out
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
/// Radii from [`RobotGeometry`](crate::setup::RobotGeometry). This is what `stiffid plot` draws.
pub fn capsules(arm: &Arm, frames: &Frames) -> Vec<Capsule> {
    let g = &arm.geometry();
    let mut out = Vec::with_capacity(16);
    for (part, points) in polylines(frames) {
        push_polyline(&mut out, part, &points, g.link_radii[part.index()]);
    }
    out.push(tool_capsule(arm, frames));
    out
}

/// The tool's capsule: from the flange origin along the flange z axis to the tool point farthest
/// along it, radius [`RobotGeometry::tool_radius`].
fn tool_capsule(arm: &Arm, frames: &Frames) -> Capsule {
    let tip = frames.point(&Vector3::new(0.0, 0.0, tool_length(arm.tool())));
    Capsule {
        part: Part::Tool,
        a: frames.flange.translation.vector,
        b: tip,
        radius: arm.geometry().tool_radius,
    }
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
    tool.points()
        .map(|p| p.z)
        .fold(0.0, |best, z| if z.abs() > best.abs() { z } else { best })
}

/// Calls `f` with the body as parry takes it: a shape and its pose, base frame.
pub(super) fn with_parry<R>(
    b: &Body,
    f: impl FnOnce(&dyn parry3d_f64::shape::Shape, &Isometry3<f64>) -> R,
) -> R {
    match b {
        Body::Capsule(c) => {
            let capsule = parry3d_f64::shape::Capsule::new(
                nalgebra::Point3::from(c.a),
                nalgebra::Point3::from(c.b),
                c.radius,
            );
            f(&capsule, &Isometry3::identity())
        }
        Body::Solid(s) => {
            let (shape, fix) = s.shape.parry();
            f(shape, &(s.pose * fix))
        }
    }
}
