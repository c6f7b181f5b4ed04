//! The observation matrix `Psi` with `Psi h = delta` (Zhang et al. 2021, Eq. 10-11).
//!
//! For one posture, one measuring point and wrench `W`: `Psi[r, j] = J_m[r, j] * tau_j` with
//! `tau = J_f^T W` (Eq. 4), `J_m` the Jacobian of the measuring point and `J_f` that of the loading
//! point, both in the springs' coordinates. Only translations are observed (laser tracker), so each
//! measuring point gives three rows (x, y, z, base frame, m/Nm * Nm = m per rad/Nm).
//!
//! Row order of a stacked matrix: posture-major, then measuring point, then x, y, z: row
//! `3 (p i + k) + a` is posture i, measuring point k (of p), coordinate a.

use crate::kinematics::Frames;
use crate::setup::Setup;
use crate::stiffness::joint_torques;
use nalgebra::{DMatrix, Matrix3x6, Vector6};

/// The three translation rows of one measuring point (index into the setup's measuring points)
/// under joint torques `tau` (Nm): `J_m[0..3, j] * tau_j`.
pub fn point_rows(
    setup: &Setup,
    frames: &Frames,
    point: usize,
    tau: &Vector6<f64>,
) -> Matrix3x6<f64> {
    let jm = frames.jacobian(&setup.tool.measuring_points[point], setup.springs);
    let mut rows = jm.fixed_rows::<3>(0).into_owned();
    for (j, mut col) in rows.column_iter_mut().enumerate() {
        col *= tau[j];
    }
    rows
}

/// The `3p x 6` block of one posture under a wrench `[f; m]` (N, Nm, base frame) at the loading point.
pub fn posture_block(setup: &Setup, frames: &Frames, wrench: &Vector6<f64>) -> DMatrix<f64> {
    let tau = joint_torques(setup, frames, wrench);
    let p = setup.tool.measuring_points.len();
    let mut block = DMatrix::zeros(3 * p, 6);
    for k in 0..p {
        block
            .fixed_view_mut::<3, 6>(3 * k, 0)
            .copy_from(&point_rows(setup, frames, k, &tau));
    }
    block
}

/// The `3pn x 6` observation matrix of postures `q` (axis angles, rad) under the setup's rope-mass
/// load (the design matrix of Section III and of the simulation of Section IV-A).
pub fn rope_observation_matrix(setup: &Setup, postures: &[Vector6<f64>]) -> DMatrix<f64> {
    let p3 = 3 * setup.tool.measuring_points.len();
    let mut psi = DMatrix::zeros(p3 * postures.len(), 6);
    for (i, q) in postures.iter().enumerate() {
        let frames = setup.robot.frames(q);
        let wrench = setup.rope_wrench(&frames);
        psi.view_mut((p3 * i, 0), (p3, 6))
            .copy_from(&posture_block(setup, &frames, &wrench));
    }
    psi
}
