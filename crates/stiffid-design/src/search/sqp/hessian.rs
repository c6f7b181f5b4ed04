//! The SQP's damped-BFGS approximation `B` of the Lagrangian's Hessian, kept with its inverse
//! `H = B^-1` (what the range-space QP works with, [`super::qp`]), so that no step factors a
//! matrix.
//!
//! - **Update**: Powell's damping (`y` is moved towards `B s` until `s^T y >= 0.2 s^T B s`, so `B`
//!   stays positive definite; the first update scales `B` to `y^T y / s^T y`, Nocedal and Wright,
//!   Numerical Optimization, 2nd ed., 6.20), then the BFGS update of `B` (Eq. 6.19) and the same
//!   update of its inverse (Eq. 6.17: `H+ = (I - rho s y^T) H (I - rho y s^T) + rho s s^T`,
//!   `rho = 1 / s^T y`) with the damped `y`: `O(n^2)` each.
//! - **Drift**: every `REFACTOR` updates (at least `n`), `H` is computed again from `B`
//!   (Cholesky factor), so the rounding of the two recurrences never accumulates.

use super::qp::inverse;
use stiffid_core::math::linalg::{axpy, dot};

/// Fewest updates between two inversions of `B` (and at least `n`).
const REFACTOR: usize = 64;

/// A damped-BFGS `B` and `H = B^-1` (both column-major `n x n`, symmetric).
pub(crate) struct Hessian {
    n: usize,
    b: Vec<f64>,
    h: Vec<f64>,
    /// Still the identity: the first update scales it.
    pub fresh: bool,
    /// Updates since `H` was last computed from `B`.
    updates: usize,
}

impl Hessian {
    /// The identity of size `n` (and its inverse), the start of the updates.
    pub(crate) fn identity(n: usize) -> Self {
        let mut b = vec![0.0; n * n];
        (0..n).for_each(|k| b[k + n * k] = 1.0);
        Self {
            n,
            h: b.clone(),
            b,
            fresh: true,
            updates: 0,
        }
    }

    /// `H = B^-1` (column-major `n x n`).
    pub(crate) fn inverse(&self) -> &[f64] {
        &self.h
    }

    /// The largest diagonal entry of `B`.
    pub(crate) fn largest_diagonal(&self) -> f64 {
        (0..self.n)
            .map(|k| self.b[k + self.n * k])
            .fold(0.0, f64::max)
    }

    /// `M v` for a symmetric column-major `m`.
    fn times(&self, m: &[f64], v: &[f64]) -> Vec<f64> {
        let n = self.n;
        let mut out = vec![0.0; n];
        for (k, vk) in v.iter().enumerate() {
            axpy(*vk, &m[n * k..n * k + n], &mut out);
        }
        out
    }

    /// Powell's damped BFGS update with the step `s` and the gradient change `y` (module docs).
    pub(crate) fn update(&mut self, s: &[f64], y: &[f64]) {
        let n = self.n;
        let sy0 = dot(s, y);
        if self.fresh && sy0 > 0.0 {
            let scale = dot(y, y) / sy0;
            if scale.is_finite() && scale > 0.0 {
                (0..n).for_each(|k| {
                    self.b[k + n * k] = scale;
                    self.h[k + n * k] = 1.0 / scale;
                });
            }
        }
        self.fresh = false;
        let bs = self.times(&self.b, s);
        let sbs = dot(s, &bs);
        let positive = sbs > 0.0;
        if !positive || !sbs.is_finite() {
            return;
        }
        let mut y = y.to_vec();
        if sy0 < 0.2 * sbs {
            let theta = 0.8 * sbs / (sbs - sy0);
            y.iter_mut()
                .zip(&bs)
                .for_each(|(y, b)| *y = theta * *y + (1.0 - theta) * b);
        }
        let sy = dot(s, &y);
        let positive = sy > 0.0;
        if !positive || !sy.is_finite() {
            return;
        }
        let hy = self.times(&self.h, &y);
        let yhy = dot(&y, &hy);
        let ss = (sy + yhy) / (sy * sy);
        for k in 0..n {
            let column = n * k..n * k + n;
            axpy(y[k] / sy, &y, &mut self.b[column.clone()]);
            axpy(-bs[k] / sbs, &bs, &mut self.b[column.clone()]);
            let h = &mut self.h[column];
            axpy(ss * s[k] - hy[k] / sy, s, h);
            axpy(-s[k] / sy, &hy, h);
        }
        self.updates += 1;
        if self.updates >= REFACTOR.max(n) {
            self.updates = 0;
            match inverse(&self.b, n) {
                Ok(h) => self.h = h,
                Err(_) => *self = Self::identity(n),
            }
        }
    }

    /// The Hessian approximation `B` itself, `n x n` column-major (what [`Hessian::inverse`]
    /// inverts); the tests' view of it.
    #[cfg(test)]
    pub(crate) fn matrix(&self) -> &[f64] {
        &self.b
    }
}
