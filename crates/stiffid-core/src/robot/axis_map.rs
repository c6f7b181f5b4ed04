//! Controller axis angles to kinematic angles.

use nalgebra::{Matrix6, Vector6};

/// The affine map `theta = M q + c` from controller axis angles `q` to the kinematic angles
/// `theta` of the DH table or URDF (rad).
///
/// It carries sign conventions, zero offsets and the J2/J3 parallelogram coupling of heavy robots
/// (`theta_3 = -q_3 - q_2 - 90 deg` on the COMAU SMART5 NJ, for example). The Jacobian in axis
/// coordinates is `J_q = J_theta M` (chain rule). Identity by default.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisMap {
    /// `M`, 6x6, dimensionless.
    pub matrix: Matrix6<f64>,
    /// `c`, rad.
    pub offset: Vector6<f64>,
}

impl Default for AxisMap {
    fn default() -> Self {
        Self {
            matrix: Matrix6::identity(),
            offset: Vector6::zeros(),
        }
    }
}

impl AxisMap {
    /// Kinematic angles `theta = M q + c` (rad) of axis angles `q` (rad).
    pub fn kinematic(&self, q: &Vector6<f64>) -> Vector6<f64> {
        self.matrix * q + self.offset
    }

    /// Axis angles `q = M^-1 (theta - c)`, or `None` if `M` is singular.
    pub fn axis(&self, theta: &Vector6<f64>) -> Option<Vector6<f64>> {
        self.matrix.try_inverse().map(|m| m * (theta - self.offset))
    }
}
