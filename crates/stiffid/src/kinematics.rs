//! Forward kinematics, point Jacobians and the dexterity index.
//!
//! All results are in the robot base frame (the world frame of [`Robot::base`]), SI units.

use crate::Robot;
use nalgebra::{Isometry3, Matrix6, Point3, UnitQuaternion, Vector3, Vector6};
use serde::{Deserialize, Serialize};

/// Which joint coordinates a Jacobian's columns refer to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Coordinates {
    /// Controller axis angles q: `J_q = J_theta M` (the springs sit in the drives).
    #[default]
    Axis,
    /// Kinematic angles theta of the DH table or URDF.
    Kinematic,
}

/// The forward kinematics of one posture: every joint frame, every joint axis and the flange.
#[derive(Debug, Clone, PartialEq)]
pub struct Frames {
    /// Frame of each joint after its rotation and fixed `post` transform (for a modified-DH robot
    /// the DH frames 1..6), base frame, m.
    pub joints: [Isometry3<f64>; 6],
    /// A point on each joint axis, base frame, m.
    pub axis_points: [Vector3<f64>; 6],
    /// Unit direction of each joint axis, base frame.
    pub axis_directions: [Vector3<f64>; 6],
    /// The flange frame, base frame, m.
    pub flange: Isometry3<f64>,
    /// `M` of the robot's axis map, for Jacobians in axis coordinates.
    axis_matrix: Matrix6<f64>,
}

impl Robot {
    /// Forward kinematics at axis angles `q` (rad).
    pub fn frames(&self, q: &Vector6<f64>) -> Frames {
        let theta = self.axis_map.kinematic(q);
        let mut t = self.base;
        let mut joints = [Isometry3::identity(); 6];
        let mut axis_points = [Vector3::zeros(); 6];
        let mut axis_directions = [Vector3::zeros(); 6];
        for (i, joint) in self.joints.iter().enumerate() {
            t *= joint.pre;
            axis_points[i] = t.translation.vector;
            axis_directions[i] = t.rotation * joint.axis.into_inner();
            t *= UnitQuaternion::from_axis_angle(&joint.axis, theta[i] + joint.offset);
            t *= joint.post;
            joints[i] = t;
        }
        Frames {
            joints,
            axis_points,
            axis_directions,
            flange: t * self.flange,
            axis_matrix: self.axis_map.matrix,
        }
    }
}

impl Frames {
    /// Base-frame position (m) of a point given in the flange frame (m).
    pub fn point(&self, in_flange: &Vector3<f64>) -> Vector3<f64> {
        (self.flange * Point3::from(*in_flange)).coords
    }

    /// Geometric Jacobian (6x6, base frame, rows `[v; omega]`, m/rad and rad/rad) of the body point
    /// given in the flange frame (m), with columns in the chosen joint coordinates.
    ///
    /// Column j in kinematic coordinates is `[z_j x (p - o_j); z_j]`, `z_j` the joint axis and `o_j`
    /// a point on it; in axis coordinates the matrix is multiplied by `M` (`J_q = J_theta M`).
    pub fn jacobian(&self, in_flange: &Vector3<f64>, coordinates: Coordinates) -> Matrix6<f64> {
        let p = self.point(in_flange);
        let mut j = Matrix6::zeros();
        for c in 0..6 {
            let z = self.axis_directions[c];
            let v = z.cross(&(p - self.axis_points[c]));
            j.fixed_view_mut::<3, 1>(0, c).copy_from(&v);
            j.fixed_view_mut::<3, 1>(3, c).copy_from(&z);
        }
        match coordinates {
            Coordinates::Kinematic => j,
            Coordinates::Axis => j * self.axis_matrix,
        }
    }
}

/// Dexterity index `k(J_N) = (1/6) sqrt(tr(A) tr(A^-1))`, `A = J_N J_N^T`,
/// `J_N = diag(I/L, I) J` (Zhang et al. 2021, Eq. 20-21; the Frobenius-norm condition number of the
/// normalised Jacobian, Paden & Sastry 1988).
///
/// `jacobian` is 6x6 with rows `[v; omega]` (m/rad, rad/rad); `characteristic_length` L in m.
/// 1 for an isotropic Jacobian, larger is worse; `+infinity` at a singularity (also a numerical
/// one: a value of `1 / f64::EPSILON` or more, where the computed inverse is rounding noise) or for
/// non-finite input. Since `tr(A) = |J_N|_F^2` and `tr(A^-1) = |J_N^-1|_F^2`, it is computed as
/// `|J_N|_F |J_N^-1|_F / 6` without forming `A`.
pub fn dexterity(jacobian: &Matrix6<f64>, characteristic_length: f64) -> f64 {
    let mut jn = *jacobian;
    jn.fixed_rows_mut::<3>(0)
        .scale_mut(1.0 / characteristic_length);
    if !jn.iter().all(|v| v.is_finite()) {
        return f64::INFINITY;
    }
    match jn.try_inverse() {
        Some(inv) => {
            let k = jn.norm() * inv.norm() / 6.0;
            if k < 1.0 / f64::EPSILON {
                k
            } else {
                f64::INFINITY
            }
        }
        None => f64::INFINITY,
    }
}
