//! The robot model: an immutable 6-axis serial chain of revolute joints.
//!
//! A [`Robot`] is built from a DH table ([`dh`]), a URDF file ([`urdf`]), a robot TOML file
//! ([`mod@file`]) or a built-in preset ([`presets`]). Its kinematics are in [`crate::kinematics`].

pub mod collision;
pub mod dh;
pub mod file;
pub mod presets;
pub mod urdf;

mod axis_map;
pub use axis_map::AxisMap;

use nalgebra::{Isometry3, Unit, Vector3};
use std::sync::Arc;

use crate::limits::JointBox;

/// One revolute joint of the chain, in the frame of the previous joint's child link.
///
/// The transform across the joint at kinematic angle `theta` is
/// `pre * Rot(axis, theta + offset) * post`. A modified-DH row gives
/// `pre = RotX(alpha_{i-1}) TransX(a_{i-1})`, `post = TransZ(d_i)`; a standard-DH row gives
/// `pre = I`, `post = TransZ(d_i) TransX(a_i) RotX(alpha_i)`; a URDF joint gives `pre` = its origin
/// (with fixed joints before it folded in) and `post = I`. Lengths in metres.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// Fixed transform from the previous joint frame to this joint's rotation frame.
    pub pre: Isometry3<f64>,
    /// Unit rotation axis, in the rotation frame.
    pub axis: Unit<Vector3<f64>>,
    /// Fixed transform after the rotation, to this joint's frame.
    pub post: Isometry3<f64>,
    /// Constant added to the kinematic angle (a DH table's theta offset), rad.
    pub offset: f64,
}

/// An immutable 6-axis serial robot with revolute joints.
///
/// Postures are axis angles `q` (rad, controller convention); [`AxisMap`] turns them into the
/// kinematic angles `theta` of the chain. Joint limits are in axis coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct Robot {
    /// Human-readable name, e.g. "COMAU SMART5 NJ 165-3.0".
    pub name: String,
    /// Where the numbers come from (datasheet, paper, repository).
    pub source: String,
    /// The six joints, base to flange.
    pub joints: [Joint; 6],
    /// Controller axis angles to kinematic angles.
    pub axis_map: AxisMap,
    /// Joint limits, axis coordinates, rad.
    pub limits: JointBox,
    /// Base transform: world (robot base frame of all results) to the chain's first frame.
    pub base: Isometry3<f64>,
    /// Flange transform: last joint frame to the flange frame.
    pub flange: Isometry3<f64>,
    /// The robot's own bodies, for the cell's checks and drawings ([`crate::cell::bodies`]).
    pub bodies: Bodies,
}

/// The bodies of a robot as its description gives them.
#[derive(Debug, Clone, Default)]
pub enum Bodies {
    /// None given: capsules along the chain, radii scaled to the robot's size
    /// ([`crate::cell::DEFAULT_RADIUS_FRACTIONS`]).
    #[default]
    Scaled,
    /// Capsules along the chain with these radii of the base and links 1-6, m (a robot TOML
    /// file's `[robot_geometry] link_radius_mm`).
    Capsules([f64; 7]),
    /// Convex collision shapes: a URDF's `<collision>` elements ([`collision::parse`]).
    Shapes(Arc<collision::CollisionGeometry>),
}

/// Shapes are equal when they are the same read (the same `Arc`).
impl PartialEq for Bodies {
    fn eq(&self, other: &Self) -> bool {
        match (self, other) {
            (Bodies::Scaled, Bodies::Scaled) => true,
            (Bodies::Capsules(a), Bodies::Capsules(b)) => a == b,
            (Bodies::Shapes(a), Bodies::Shapes(b)) => Arc::ptr_eq(a, b),
            _ => false,
        }
    }
}
