//! The robot's links as a scene draws them: one link per body that moves as one (the base, links
//! 1-6, the tool), named as the robot's URDF names them (`link K` for a DH robot), each a set of
//! triangle meshes in the link's own frame, so that one transform per posture places it.
//!
//! With the robot's collision shapes ([`stiffid_core::setup::Arm::shapes`]) a link is its shapes as the
//! cell's checks take them (boxes, cylinders, spheres, capsules; a mesh by its convex hull, its
//! file named as the URDF names it); without them, the capsules of [`stiffid_core::cell::capsules`].
//! The tool is its capsule in both cases.

use super::{Geometry, Link};
use nalgebra::{Isometry3, Point3, Vector3};
use parry3d_f64::shape::{self, Ball};
use std::collections::BTreeSet;
use stiffid_core::cell::{self, Capsule, Part};
use stiffid_core::robot::collision::Shape;
use stiffid_core::robot::kinematics::Frames;
use stiffid_core::setup::Arm;

/// Subdivisions of a round shape's circle (capsules, cylinders, spheres).
const ROUND: u32 = 24;

/// The frame that carries `part` in the posture `frames`, base frame, m: the robot's base (on its
/// carrier with external axes, [`Frames::base`]), joint
/// frame i for link i ([`Frames::joints`]), the flange for the tool.
pub(super) fn frame(frames: &Frames, part: Part) -> Isometry3<f64> {
    match part {
        Part::Base => frames.base,
        Part::Link(i) => frames.joints[i - 1],
        Part::Tool => frames.flange,
    }
}

/// Every part in the scene's order: the base, links 1-6, the tool.
pub(super) fn parts() -> [Part; 8] {
    [
        Part::Base,
        Part::Link(1),
        Part::Link(2),
        Part::Link(3),
        Part::Link(4),
        Part::Link(5),
        Part::Link(6),
        Part::Tool,
    ]
}

/// The links of the arm with their meshes in their own frames, worked out at the posture
/// `frames` (capsules are fixed in their link's frame, so any posture gives the same meshes).
pub(super) fn links(arm: &Arm, frames: &Frames) -> Vec<Link> {
    let names = names(arm);
    let capsules = cell::capsules(arm, frames);
    parts()
        .iter()
        .zip(names)
        .map(|(part, name)| {
            let to_link = frame(frames, *part).inverse();
            let mut link = Link {
                name,
                part: part.to_string(),
                meshes: Vec::new(),
                geometry: Vec::new(),
            };
            match (arm.shapes(), part) {
                (Some(g), Part::Base | Part::Link(_)) => {
                    let body = part.index();
                    let mut files = BTreeSet::new();
                    for s in g.shapes.iter().filter(|s| s.body == body) {
                        link.geometry.push(solid(&s.shape, &s.origin));
                        files.extend(s.mesh.clone());
                    }
                    link.meshes = files.into_iter().collect();
                }
                _ => {
                    let own = capsules.iter().filter(|c| c.part == *part);
                    link.geometry = own.map(|c| capsule(c, &to_link)).collect();
                }
            }
            link
        })
        .collect()
}

/// The parts' names: a URDF robot's chain links (the root link for the base, the child of
/// revolute joint i for link i), else `base`, `link K`; the tool is `tool`.
fn names(arm: &Arm) -> Vec<String> {
    let mut out: Vec<String> = parts().iter().map(Part::to_string).collect();
    let Some(source) = arm.robot().urdf_source() else {
        return out;
    };
    // The URDF was read when the robot was; a text it came from reads again.
    let Ok(urdf) = urdf_rs::read_from_string(&source.text) else {
        return out;
    };
    for (i, joint) in source.joints.iter().enumerate() {
        if let Some(j) = urdf.joints.iter().find(|j| &j.name == joint) {
            out[i + 1].clone_from(&j.child.link);
            if i == 0 {
                out[0] = root(&urdf, &j.parent.link);
            }
        }
    }
    out
}

/// The root of the URDF tree above `link`.
fn root(urdf: &urdf_rs::Robot, link: &str) -> String {
    let mut at = link.to_string();
    for _ in 0..urdf.joints.len() {
        match urdf.joints.iter().find(|j| j.child.link == at) {
            Some(j) => at.clone_from(&j.parent.link),
            None => break,
        }
    }
    at
}

/// A collision shape as triangles in its body's frame (`origin` places it there).
fn solid(s: &Shape, origin: &Isometry3<f64>) -> Geometry {
    let (kind, (points, triangles)) = match s {
        Shape::Cuboid(c) => ("box", c.to_trimesh()),
        Shape::Cylinder(c) => ("cylinder", c.to_trimesh(ROUND)),
        Shape::Ball(b) => ("sphere", b.to_trimesh(ROUND, ROUND / 2)),
        Shape::Capsule(c) => ("capsule", c.to_trimesh(ROUND, ROUND / 2)),
        Shape::Convex(c) => ("mesh hull", c.to_trimesh()),
    };
    // parry's round shapes turn about y, URDF's about z ([`Shape::parry`]).
    let pose = origin * s.parry().1;
    Geometry::new(kind, &points, triangles, &pose)
}

/// A capsule (base frame) as triangles in its link's frame.
fn capsule(c: &Capsule, to_link: &Isometry3<f64>) -> Geometry {
    let (a, b) = (Point3::from(c.a), Point3::from(c.b));
    let (points, triangles) = match (c.b - c.a).norm() > 0.0 {
        true => shape::Capsule::new(a, b, c.radius).to_trimesh(ROUND, ROUND / 2),
        false => {
            let (p, t) = Ball::new(c.radius).to_trimesh(ROUND, ROUND / 2);
            (p.iter().map(|p| p + a.coords).collect(), t)
        }
    };
    Geometry::new("capsule", &points, triangles, to_link)
}

impl Geometry {
    /// Triangles of `points` placed by `pose`, positions rounded to f32.
    pub(super) fn new(
        kind: &str,
        points: &[Point3<f64>],
        triangles: Vec<[u32; 3]>,
        pose: &Isometry3<f64>,
    ) -> Self {
        let f32s = |v: Vector3<f64>| [v.x as f32, v.y as f32, v.z as f32];
        Geometry {
            kind: kind.to_string(),
            positions_m: points.iter().map(|p| f32s((pose * p).coords)).collect(),
            triangles,
        }
    }
}
