//! Postures of a group that are not distinct: two postures whose axis angles are close, or whose
//! flanges sit at the same pose (a wrist flip, or the elbow's other branch, reaching the same pose
//! counts: for the tracker and the rope both are one measurement place), add little information
//! and are flagged in the plan.
//!
//! Two postures `a`, `b` are *near* when `max_j |q_a,j - q_b,j| <` [`JOINT_TOLERANCE`] or when
//! their flange origins lie within [`POSITION_TOLERANCE`] and their flange orientations within
//! [`ANGLE_TOLERANCE`] of each other.

use crate::Robot;
use nalgebra::Vector6;

/// Axis angles closer than this in every joint make two postures near, rad (2 deg).
pub const JOINT_TOLERANCE: f64 = 2.0 * std::f64::consts::PI / 180.0;
/// Flange origins closer than this (with [`ANGLE_TOLERANCE`]) make two postures near, m (10 mm).
pub const POSITION_TOLERANCE: f64 = 0.010;
/// Flange orientations closer than this (with [`POSITION_TOLERANCE`]) make two postures near,
/// rad (2 deg).
pub const ANGLE_TOLERANCE: f64 = 2.0 * std::f64::consts::PI / 180.0;

/// Two near postures of a group.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Near {
    /// The first posture's index in the group (0-based).
    pub a: usize,
    /// The second's (`> a`).
    pub b: usize,
    /// `max_j |q_a,j - q_b,j|`, rad.
    pub joint_distance: f64,
    /// The distance between their flange origins, m.
    pub position_distance: f64,
    /// The angle between their flange orientations, rad.
    pub angle_distance: f64,
}

impl Near {
    /// Whether the flange reaches the same pose with other axis angles (a wrist flip or another
    /// branch), rather than the axis angles being close.
    pub fn same_pose_other_branch(&self) -> bool {
        self.joint_distance >= JOINT_TOLERANCE
    }
}

/// Every near pair of `postures` (axis angles, rad) on `robot`, in the order `(a, b)`, `a < b`.
pub fn near_pairs(robot: &Robot, postures: &[Vector6<f64>]) -> Vec<Near> {
    let flanges: Vec<_> = postures.iter().map(|q| robot.frames(q).flange).collect();
    let mut out = Vec::new();
    for a in 0..postures.len() {
        for b in a + 1..postures.len() {
            let joint_distance = (postures[a] - postures[b]).amax();
            let position_distance =
                (flanges[a].translation.vector - flanges[b].translation.vector).norm();
            let angle_distance = flanges[a].rotation.angle_to(&flanges[b].rotation);
            let same_pose =
                position_distance < POSITION_TOLERANCE && angle_distance < ANGLE_TOLERANCE;
            if joint_distance < JOINT_TOLERANCE || same_pose {
                out.push(Near {
                    a,
                    b,
                    joint_distance,
                    position_distance,
                    angle_distance,
                });
            }
        }
    }
    out
}
