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

impl AxisMap {
    /// The axes' limits (rad) of a robot whose limits `joints` bound its kinematic angles (a
    /// URDF's joint positions): an axis `k` that a row `j` maps alone (`theta_j = m q_k + c_j`:
    /// a sign, an offset) is bounded by `(joints_j - c_j) / m`; an axis that no row maps alone
    /// (coupled into its joint, FANUC's J3 in joint 3 = J2 + J3) keeps joint `k`'s limits as its
    /// own.
    pub(crate) fn axis_limits(
        &self,
        joints: &crate::common::limits::JointBox,
    ) -> crate::common::limits::JointBox {
        let mut out = *joints;
        for j in 0..6 {
            let row = self.matrix.row(j);
            let nonzero: Vec<usize> = (0..6).filter(|&k| row[k] != 0.0).collect();
            let [k] = nonzero[..] else { continue };
            let (m, c) = (row[k], self.offset[j]);
            let (a, b) = ((joints.lower[j] - c) / m, (joints.upper[j] - c) / m);
            out.lower[k] = a.min(b);
            out.upper[k] = a.max(b);
        }
        out
    }
}
