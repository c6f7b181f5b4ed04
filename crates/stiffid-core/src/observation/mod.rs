//! The observation matrix `Psi` with `Psi h = delta` (Zhang et al. 2021, Eq. 10-11).
//!
//! For one posture, one measuring point and wrench `W`: `Psi[r, j] = J_m[r, j] * tau_j` with
//! `tau = J_f^T W` (Eq. 4), `J_m` the Jacobian of the measuring point and `J_f` that of the loading
//! point, both in the springs' coordinates. Only translations are observed (laser tracker), so each
//! measuring point gives three rows (x, y, z, base frame, m/Nm * Nm = m per rad/Nm).
//!
//! Two sources of rows: measured data ([`Measurement`]s, checked and stacked by
//! [`Observations::from_measurements`], for identification) and a planned group of postures under
//! the setup's rope-mass load ([`rope_observation_matrix`], for experiment design and simulation).
//!
//! **Row order** (the one definition; every stacked `Psi`, `delta` and residual vector of stiffid
//! uses it): three rows per measuring point in a posture, x, y, z (base frame), in the order the
//! measurements are given: row `3 i + a` is measurement `i`, coordinate `a`. A planned group is
//! posture-major, then measuring point: measurement `i = p j + k` is posture `j`, measuring point
//! `k` of `p`.

pub mod cartesian;
pub mod deflection;
pub mod dynamics;
pub mod frames;
mod measurement;
pub mod stiffness;

pub use measurement::{assemble, Check, Measurement, Observations};

use crate::model::Placed;
use crate::observation::stiffness::joint_torques;
use crate::robot::kinematics::Frames;
use crate::setup::{Arm, Setup, Tool};
use nalgebra::{DMatrix, Matrix3x6, Matrix6, MatrixXx6, Vector3, Vector6};

/// The three translation rows of the measuring point `point` (flange frame, m; any point, so no
/// index can be out of range) under joint torques `tau` (Nm): `J_m[0..3, j] * tau_j`, the
/// Jacobian in the arm's spring coordinates.
pub fn point_rows(
    arm: &Arm,
    frames: &Frames,
    point: &Vector3<f64>,
    tau: &Vector6<f64>,
) -> Matrix3x6<f64> {
    let jm = frames.jacobian(point, arm.springs());
    let mut rows = jm.fixed_rows::<3>(0).into_owned();
    for (j, mut col) in rows.column_iter_mut().enumerate() {
        col *= tau[j];
    }
    rows
}

/// The `3p x n` block of one posture under a wrench `[f; m]` (N, Nm, base frame) at the loading
/// point, `n` the parameters of the arm's model ([`Arm::model`]: the six drives, then the
/// virtual springs).
pub fn posture_block(arm: &Arm, frames: &Frames, wrench: &Vector6<f64>) -> DMatrix<f64> {
    let n = arm.model().len();
    let mut block = DMatrix::zeros(3 * arm.tool().measuring_points.len(), n);
    write_posture_block(arm, frames, wrench, &mut block, 0);
    block
}

/// Writes the block of one posture ([`posture_block`]) into rows `first..first + 3p` of `psi`
/// (no temporary matrix): the drive columns `0..6` (Eq. 11) and, when `psi` has them, the
/// virtual springs' columns `6..n` ([`SpringLoads::write_rows`]).
///
/// # Panics
/// If `psi` has fewer than `first + 3p` rows or fewer than six columns, or more columns than
/// the model has parameters.
pub fn write_posture_block(
    arm: &Arm,
    frames: &Frames,
    wrench: &Vector6<f64>,
    psi: &mut DMatrix<f64>,
    first: usize,
) {
    let tau = joint_torques(arm, frames, wrench);
    let springs = SpringLoads::new(arm, frames, wrench, psi.ncols() - 6);
    for (k, point) in arm.tool().measuring_points.iter().enumerate() {
        psi.fixed_view_mut::<3, 6>(first + 3 * k, 0)
            .copy_from(&point_rows(arm, frames, point, &tau));
        springs.write_rows(frames, point, psi, first + 3 * k);
    }
}

/// The virtual springs of a model placed at a posture with their generalised loads
/// `J_f,s^T W` (Nm or N) under one wrench, through each one's law ([`crate::model::Law`]): what their columns of `Psi` need beside the
/// measuring point. Empty (no allocation) for the drives alone.
#[derive(Debug, Clone, Default)]
pub struct SpringLoads {
    placed: Vec<Placed>,
    loads: Vec<f64>,
}

impl SpringLoads {
    /// The first `count` virtual springs of the arm's model at the posture `frames`, loaded by
    /// the wrench `[f; m]` (N, Nm, base frame) at the loading point.
    ///
    /// # Panics
    /// If the model has fewer than `count` virtual springs.
    pub fn new(arm: &Arm, frames: &Frames, wrench: &Vector6<f64>, count: usize) -> Self {
        if count == 0 {
            return Self::default();
        }
        let springs = &arm.model().springs()[..count];
        let loading = frames.point(&arm.tool().loading_point);
        let placed: Vec<Placed> = springs.iter().map(|s| s.placed(frames)).collect();
        let loads = springs
            .iter()
            .zip(&placed)
            .map(|(s, p)| s.response(p, &loading, wrench))
            .collect();
        Self { placed, loads }
    }

    /// Writes the three rows of the measuring point `point` (flange frame, m) into columns
    /// `6..6 + count` of `psi` from row `row`: `J_m,s[0..3] (J_f,s^T W)` per spring.
    pub fn write_rows(
        &self,
        frames: &Frames,
        point: &Vector3<f64>,
        psi: &mut DMatrix<f64>,
        row: usize,
    ) {
        if self.placed.is_empty() {
            return;
        }
        let p = frames.point(point);
        for (s, (spring, load)) in self.placed.iter().zip(&self.loads).enumerate() {
            psi.fixed_view_mut::<3, 1>(row, 6 + s)
                .copy_from(&(spring.velocity(&p) * *load));
        }
    }
}

/// The `3pn x n` observation matrix of postures `q` (axis angles, rad) under the setup's rope-mass
/// load (the design matrix of Section III and of the simulation of Section IV-A), one column per
/// parameter of the setup's model.
pub fn rope_observation_matrix(setup: &Setup, postures: &[Vector6<f64>]) -> DMatrix<f64> {
    let p3 = 3 * setup.tool().measuring_points.len();
    let mut psi = DMatrix::zeros(p3 * postures.len(), setup.model().len());
    for (i, q) in postures.iter().enumerate() {
        let frames = setup.robot().frames(q);
        let wrench = setup.rope_wrench(&frames);
        write_posture_block(setup.arm(), &frames, &wrench, &mut psi, p3 * i);
    }
    psi
}

/// The measuring points' factor `R_P` (6x6, upper triangular): the triangular factor of the
/// Householder QR `P = Q_P R_P` of the `3p x 6` matrix `P` whose rows `3k..3k + 3` are
/// `[I_3, -[p_k]x]`, `p_k` measuring point k (flange frame, m) and `[p]x` the cross-product matrix.
/// Rows `min(3p, 6)..6` are zero.
///
/// The translation rows of point k's Jacobian are `R_f [I_3, -[p_k]x] J_b` (the velocity
/// `v + omega x (p - t)` of a body point), `J_b` the flange-frame Jacobian of the flange origin t and
/// `R_f` the flange's rotation. A posture's block is therefore `B = (I_p (x) R_f) Q_P C` with
/// `C = R_P J_b diag(tau)` ([`compact_posture_block`]): `(I_p (x) R_f) Q_P` has orthonormal columns,
/// so `B^T B = C^T C`, and the stacked `C` of a group have the triangular factor, column norms and
/// singular values of `Psi` (an orthogonal change of rows, no normal equations) on `min(3p, 6)`
/// rows per posture instead of `3p`.
pub fn points_factor(tool: &Tool) -> Matrix6<f64> {
    let points = &tool.measuring_points;
    let rows = DMatrix::from_fn(3 * points.len(), 6, |r, c| {
        let p = points[r / 3];
        match c {
            0..3 => f64::from(u8::from(c == r % 3)),
            _ => -p.cross_matrix()[(r % 3, c - 3)],
        }
    });
    crate::math::householder::triangular_factor(rows)
}

/// The compact block `C = R_P J_b diag(tau)` of one posture under the setup's rope-mass load
/// ([`points_factor`]: `B^T B = C^T C` for its block B of [`rope_observation_matrix`]); rows
/// `min(3p, 6)..6` are zero. `J_b`: the body Jacobian of the flange origin in the springs'
/// coordinates (`Frames::body_jacobian`); `tau = J_f^T W` (Eq. 4).
pub fn compact_posture_block(
    setup: &Setup,
    frames: &Frames,
    points_factor: &Matrix6<f64>,
) -> Matrix6<f64> {
    let tau = joint_torques(setup.arm(), frames, &setup.rope_wrench(frames));
    let body = frames.body_jacobian(setup.springs());
    // R_P is upper triangular: row i of R_P J_b starts at column i of R_P.
    Matrix6::from_fn(|i, j| {
        tau[j]
            * (i..6)
                .map(|k| points_factor[(i, k)] * body[(k, j)])
                .sum::<f64>()
    })
}

/// The gradient with respect to the axis angles q (per rad) of `<G, B(q)>` (Frobenius product),
/// `B(q)` the `3p x 6` block of the posture under the setup's rope-mass load
/// ([`rope_observation_matrix`]) and `G` a fixed weight of the same shape: the vector-Jacobian
/// product through which every design criterion's gradient reaches the postures.
///
/// With `B_m = J_m diag(tau)` the rows of measuring point m (translation rows of its Jacobian
/// `J_m`), `tau = J_f^T W` and the rope wrench `W = [f(p_f); 0]` at the loading point p_f:
/// `d<G, B> = sum_m <G_m diag(tau), dJ_m> + c . dtau`, `c_j = sum_m G_m[:, j] . J_m[:, j]`, and
/// `c . dtau = <W c^T, dJ_f> + (J_f c) . dW`, the last through [`crate::setup::RopeLoad::force_gradient`].
/// Each term is a [`Frames::jacobian_gradient`].
///
/// # Panics
/// If `weight` has fewer than the block's `3p` rows (`p` measuring points), as nalgebra's views.
pub fn rope_block_gradient(
    setup: &Setup,
    frames: &Frames,
    weight: &MatrixXx6<f64>,
) -> Vector6<f64> {
    let wrench = setup.rope_wrench(frames);
    let tau = joint_torques(setup.arm(), frames, &wrench);
    let mut c = Vector6::zeros();
    let mut grad = Vector6::zeros();
    for (k, p) in setup.tool().measuring_points.iter().enumerate() {
        let g = weight.fixed_view::<3, 6>(3 * k, 0);
        let jm = frames.jacobian(p, setup.springs());
        let mut w = Matrix6::zeros();
        for j in 0..6 {
            let gj = g.column(j);
            c[j] += gj.dot(&jm.fixed_view::<3, 1>(0, j));
            w.fixed_view_mut::<3, 1>(0, j).copy_from(&(gj * tau[j]));
        }
        grad += frames.jacobian_gradient(p, setup.springs(), &w, &Vector3::zeros());
    }
    let loading = &setup.tool().loading_point;
    let jf = frames.jacobian(loading, setup.springs());
    let mut w = Matrix6::zeros();
    w.fixed_view_mut::<3, 6>(0, 0)
        .copy_from(&(wrench.fixed_rows::<3>(0) * c.transpose()));
    let e = (jf * c).fixed_rows::<3>(0).into_owned();
    let point = setup.load().force_gradient(&frames.point(loading), &e);
    grad + frames.jacobian_gradient(loading, setup.springs(), &w, &point)
}
