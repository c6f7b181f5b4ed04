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
    let rot_x = Isometry3::from_parts(
        Translation3::identity(),
        UnitQuaternion::from_axis_angle(&Vector3::x_axis(), row.alpha),
    );
    let trans_x = Isometry3::translation(row.a, 0.0, 0.0);
    let trans_z = Isometry3::translation(0.0, 0.0, row.d);
    let (pre, post) = match convention {
        Convention::ModifiedDh => (rot_x * trans_x, trans_z),
        Convention::StandardDh => (Isometry3::identity(), trans_z * trans_x * rot_x),
    };
    Joint {
        pre,
        axis: Vector3::z_axis(),
        post,
        offset: row.theta_offset,
    }
}
