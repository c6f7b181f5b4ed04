//! Denavit-Hartenberg tables, in both common notations.

use super::Joint;
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};

/// Which Denavit-Hartenberg notation a table uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Convention {
    /// Standard (distal) DH: `T_i = RotZ(theta_i) TransZ(d_i) TransX(a_i) RotX(alpha_i)`.
    StandardDh,
    /// Modified (proximal, Craig) DH: `T_i = RotX(alpha_{i-1}) TransX(a_{i-1}) RotZ(theta_i) TransZ(d_i)`;
    /// row i holds `alpha_{i-1}`, `a_{i-1}`, `d_i`.
    ModifiedDh,
}

/// One row of a DH table, SI units (m, rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Row {
    /// Link length `a` (`a_{i-1}` in modified DH), m.
    pub a: f64,
    /// Link twist `alpha` (`alpha_{i-1}` in modified DH), rad.
    pub alpha: f64,
    /// Link offset `d_i`, m.
    pub d: f64,
    /// Constant added to the kinematic angle `theta_i`, rad.
    pub theta_offset: f64,
}

/// The revolute joint (rotation about its z axis) of one DH row.
pub fn joint(convention: Convention, row: &Row) -> Joint {
    hayati_joint(convention, row, 0.0)
}

/// The revolute joint of one DH row with Hayati's `beta` (rad): a rotation about the y axis after
/// the twist, `T_i = RotZ(theta_i) TransZ(d_i) TransX(a_i) RotX(alpha_i) RotY(beta_i)` (standard)
/// or `RotX(alpha_{i-1}) TransX(a_{i-1}) RotY(beta_{i-1}) RotZ(theta_i) TransZ(d_i)` (modified), for
/// consecutive (nearly) parallel axes, where the common normal and `d` degenerate (Hayati and
/// Mirmirani 1985). `beta = 0` is [`joint`].
pub fn hayati_joint(convention: Convention, row: &Row, beta: f64) -> Joint {
    let rot_x = Isometry3::from_parts(
        Translation3::identity(),
        UnitQuaternion::from_axis_angle(&Vector3::x_axis(), row.alpha),
    );
    let trans_x = Isometry3::translation(row.a, 0.0, 0.0);
    let trans_z = Isometry3::translation(0.0, 0.0, row.d);
    let (mut pre, mut post) = match convention {
        Convention::ModifiedDh => (rot_x * trans_x, trans_z),
        Convention::StandardDh => (Isometry3::identity(), trans_z * trans_x * rot_x),
    };
    if beta != 0.0 {
        let rot_y = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), beta);
        match convention {
            Convention::ModifiedDh => pre *= rot_y,
            Convention::StandardDh => post *= rot_y,
        }
    }
    Joint {
        pre,
        axis: Vector3::z_axis(),
        post,
        offset: row.theta_offset,
    }
}
