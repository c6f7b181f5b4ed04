//! Cartesian compliance and stiffness of a tool point (Salisbury 1980; Zhang et al. 2021,
//! Eq. 1-6).
//!
//! A wrench `W = [f; m]` (N, Nm, base frame) at a tool point p loads the joint springs with
//! `tau = J_p^T W` (Eq. 4), which deflect by `dq = K^-1 tau` (Eq. 5), which move the point and the
//! tool by `[dp; dphi] = J_p dq` (Eq. 6). So `[dp; dphi] = C_x W` with the 6x6 Cartesian compliance
//!
//! `C_x = J_p K^-1 J_p^T`,
//!
//! and, where `J_p` is invertible, the Cartesian stiffness `K_x = C_x^-1 = J_p^-T K J_p^-1`
//! (J. K. Salisbury, "Active stiffness control of a manipulator in Cartesian coordinates",
//! IEEE CDC 1980). `J_p` is the geometric Jacobian of p in the springs' coordinates (base frame,
//! rows `[v; omega]`), `K = diag(k)` the joint stiffness (Nm/rad).
//!
//! Over the model ([`crate::model`]), `J_p` is augmented by one column per virtual spring and
//! `K^-1` by its compliance: `C_x = J_q K^-1 J_q^T + sum_s c_s J_s J_s^T`.
//!
//! Blocks of `C_x` (base frame): translation per force m/N, translation per moment m/(N m),
//! rotation per force rad/N, rotation per moment rad/(N m); `K_x` holds their inverses (N/m, N/rad,
//! N m/m, N m/rad).
//!
//! **Neglected: the complementary (geometric) stiffness** `K_c = d(J^T)/dq W` of the loaded posture
//! (Chen and Kao, "Conservative congruence transformation for joint and Cartesian stiffness
//! matrices", Int. J. Robotics Research 19(7), 2000). The torques are those of the unloaded
//! posture. On the paper's setup we measured its effect at about 2 micrometres (1.9 um) of a 2 mm
//! deflection (0.1%, the `predict` example of docs/guide.md; test
//! `the_complementary_stiffness_is_about_a_thousandth_of_the_deflection`).

use crate::robot::kinematics::Frames;
use crate::setup::Arm;
use nalgebra::{DVector, Matrix6, Vector3};

/// `C_x = J_p diag(h) J_p^T` (6x6, symmetric, base frame, SI blocks as in the module docs) of the
/// tool point `point` (flange frame, m) in the posture `frames`, with the compliance `h` of every
/// parameter of the arm's model (rad/Nm, m/N; drives first): `J_p` the augmented Jacobian, so
/// that with virtual springs `C_x = J_q K^-1 J_q^T + sum_s c_s J_s J_s^T`.
///
/// # Panics
/// If `h` does not have one value per parameter.
pub fn compliance(
    arm: &Arm,
    frames: &Frames,
    point: &Vector3<f64>,
    h: &DVector<f64>,
) -> Matrix6<f64> {
    assert_eq!(h.len(), arm.model().len(), "one compliance per parameter");
    let j = arm.model().jacobian(frames, point);
    let mut jh = j.clone();
    for (c, mut col) in jh.column_iter_mut().enumerate() {
        col *= h[c];
    }
    let full = jh * j.transpose();
    symmetric(Matrix6::from_fn(|r, c| full[(r, c)]))
}

/// `(A + A^T) / 2`: exactly symmetric, as `C_x` and `K_x` are in exact arithmetic.
fn symmetric(a: Matrix6<f64>) -> Matrix6<f64> {
    (a + a.transpose()) * 0.5
}

/// The condition number of the point Jacobian `J_p` (SI) beyond which [`stiffness`] calls it
/// singular: a wrist or elbow singularity, where the inverse's entries are rounding error.
const MAX_COND_JACOBIAN: f64 = 1e10;

/// The condition number of `C_x` beyond which [`stiffness`] calls it singular: its inverse loses
/// every digit of a double.
const MAX_COND_COMPLIANCE: f64 = 1e15;

/// Whether `a`'s condition number exceeds `max` (or is no number).
fn singular(a: &Matrix6<f64>, max: f64) -> bool {
    let cond = crate::math::jacobi::cond(a);
    cond.is_nan() || cond > max
}

/// `K_x = C_x^-1` (6x6, symmetric, base frame, SI blocks as in the module docs) of the tool point
/// `point` (flange frame, m), with the compliance `h` of every parameter of the arm's model.
/// For the drives alone it is computed from the inverse Jacobian, `J_p^-T diag(1/h) J_p^-1`, not
/// by inverting `C_x` (whose condition number is the square of `J_p`'s); with virtual springs
/// (`J_p` is 6 x n) by inverting `C_x`. `None` where it is singular (numerically: the condition
/// number of `J_p` above 1e10, of `C_x` above 1e15, where the inverse's entries say nothing; or
/// non-finite).
///
/// # Panics
/// If `h` does not have one value per parameter.
pub fn stiffness(
    arm: &Arm,
    frames: &Frames,
    point: &Vector3<f64>,
    h: &DVector<f64>,
) -> Option<Matrix6<f64>> {
    assert_eq!(h.len(), arm.model().len(), "one compliance per parameter");
    let kx = match arm.model().is_drives_only() {
        true => {
            let jp = frames.jacobian(point, arm.springs());
            if singular(&jp, MAX_COND_JACOBIAN) {
                return None;
            }
            let inv = jp.try_inverse()?;
            let mut kj = inv;
            for (r, mut row) in kj.row_iter_mut().enumerate() {
                row *= 1.0 / h[r];
            }
            symmetric(inv.transpose() * kj)
        }
        false => {
            let cx = compliance(arm, frames, point, h);
            if singular(&cx, MAX_COND_COMPLIANCE) {
                return None;
            }
            symmetric(cx.try_inverse()?)
        }
    };
    kx.iter().all(|v| v.is_finite()).then_some(kx)
}
