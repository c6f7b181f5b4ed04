//! The joint-space mass matrix by the composite rigid body algorithm (R. Featherstone, *Rigid
//! Body Dynamics Algorithms*, Springer 2008, section 6.2), in the base frame.
//!
//! Bodies `k..6` moving together form the composite body `k` (mass `m_k`, centre `c_k`, tensor
//! `I_k` about it). A unit speed of joint `k` (axis `z_k` through `o_k`) gives it the momentum
//! `p = m_k z_k x (c_k - o_k)` and the angular momentum `I_k z_k` about `c_k`; the power it takes
//! through joint `j <= k` is the entry
//!
//! `H_jk = z_j . (I_k z_k + (c_k - o_j) x p)`,
//!
//! so `H` costs 21 such products and 6 unions of bodies, and no link Jacobian. In axis angles
//! (`theta = A q + c`) the matrix is `M_q = A^T H A`.

use crate::robot::kinematics::Frames;
use crate::robot::LinkMass;
use nalgebra::{Matrix6, Vector3};

/// `H(theta)` (kg m^2, symmetric, kinematic coordinates) of the six bodies `world` given in the
/// base frame (body k turned by joints 1..=k+1), in the posture `frames`.
pub(super) fn kinematic(frames: &Frames, world: &[LinkMass; 6]) -> Matrix6<f64> {
    let mut composite = world[5];
    let mut h = Matrix6::zeros();
    for k in (0..6).rev() {
        if k < 5 {
            composite = world[k].plus(&composite);
        }
        let (z, o) = (frames.axis_directions[k], frames.axis_points[k]);
        let p: Vector3<f64> = z.cross(&(composite.centre - o)) * composite.mass;
        let spin = composite.inertia * z;
        for j in 0..=k {
            let (zj, oj) = (frames.axis_directions[j], frames.axis_points[j]);
            let v = zj.dot(&(spin + (composite.centre - oj).cross(&p)));
            h[(j, k)] = v;
            h[(k, j)] = v;
        }
    }
    h
}
