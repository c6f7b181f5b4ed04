//! The triangular factor of a group's observation matrix with more than six columns (a model with
//! virtual springs, [`stiffid_core::model`]), and the criteria computed from it.
//!
//! The same quantities as the six-column [`super::Group`], for `n` parameters (`R` is `n x n`):
//! `cond_2(Psi)`, `cond_2(S)` from one-sided Jacobi singular values of `R` and `R_s`
//! ([`stiffid_core::math::jacobi`]);
//! `d-optimal = det((S^T S)^-1)^(1/(2n)) = prod_k |R_s,kk|^(-1/n)`;
//! `relative-a = |R_s^-1|_F / sqrt(n)`; the relative standard deviations as the row norms of
//! `R_s^-1`. Every product is a loop in a fixed order (the same bits on every processor, like
//! [`stiffid_core::math::linalg::times_6x6`]); no general matrix product that picks its kernel at run time.

use nalgebra::{DMatrix, DVector};
use stiffid_core::math::householder;
use stiffid_core::math::jacobi::{cond_n, singular_values_and_vectors_n};
use stiffid_core::math::lsq::RANK_TOLERANCE;

/// The factor of a full-rank group with `n > 6` parameters: `Psi = Q R`, `S = Q R_s`,
/// `R_s = R diag(h) / sigma` (all `n x n`, upper triangular).
#[derive(Debug, Clone)]
pub(super) struct WideGroup {
    pub(super) r: DMatrix<f64>,
    pub(super) r_inv: DMatrix<f64>,
    pub(super) rs: DMatrix<f64>,
    pub(super) rs_inv: DMatrix<f64>,
}

impl WideGroup {
    /// The factor of the column-major `m x n` matrix `psi` (consumed) with the column scaling
    /// `h / sigma`; `None` when it is rank deficient by the rule of [`stiffid_core::math::lsq::Factor::try_new`]
    /// (a column norm at most [`RANK_TOLERANCE`] times the largest, `cond_2 >= 1 / RANK_TOLERANCE`,
    /// fewer rows than columns) or not finite.
    pub(super) fn factor(mut psi: Vec<f64>, m: usize, scaling: &DVector<f64>) -> Option<Self> {
        let n = scaling.len();
        if m < n {
            return None;
        }
        let norms: Vec<f64> = psi.chunks_exact(m).map(|c| dot(c, c).sqrt()).collect();
        let largest = norms.iter().copied().fold(0.0, f64::max);
        if !largest.is_finite() || norms.iter().any(|&c| c <= largest * RANK_TOLERANCE) {
            return None;
        }
        householder::qr(&mut psi, m, n);
        let r = DMatrix::from_fn(n, n, |i, j| if i <= j { psi[j * m + i] } else { 0.0 });
        let r_inv = upper_inverse(&r)?;
        let bound = r.norm() * r_inv.norm();
        let deficient = match bound {
            b if !b.is_finite() => true,
            b if b * RANK_TOLERANCE < 1.0 => false,
            b if b * RANK_TOLERANCE >= n as f64 => true,
            _ => cond_n(&r) * RANK_TOLERANCE >= 1.0,
        };
        if deficient {
            return None;
        }
        Some(Self::from_parts(r, r_inv, scaling))
    }

    /// The group of `R` and `R^-1` with the column scaling `h / sigma`.
    pub(super) fn from_parts(r: DMatrix<f64>, r_inv: DMatrix<f64>, scaling: &DVector<f64>) -> Self {
        let mut rs = r.clone();
        let mut rs_inv = r_inv.clone();
        for (j, s) in scaling.iter().enumerate() {
            rs.column_mut(j).scale_mut(*s);
            rs_inv.row_mut(j).scale_mut(1.0 / s);
        }
        Self {
            r,
            r_inv,
            rs,
            rs_inv,
        }
    }

    /// The group of the upper triangular `R_s` (from a Cholesky factor of `S^T S`); `None` if it
    /// is singular.
    pub(super) fn from_scaled(rs: DMatrix<f64>, scaling: &DVector<f64>) -> Option<Self> {
        let rs_inv = upper_inverse(&rs)?;
        let mut r = rs.clone();
        let mut r_inv = rs_inv.clone();
        for (j, s) in scaling.iter().enumerate() {
            r.column_mut(j).scale_mut(1.0 / s);
            r_inv.row_mut(j).scale_mut(*s);
        }
        Some(Self {
            r,
            r_inv,
            rs,
            rs_inv,
        })
    }

    /// The number of parameters.
    pub(super) fn n(&self) -> usize {
        self.r.ncols()
    }

    /// `sqrt([(S^T S)^-1]_jj)`: the row norms of `R_s^-1`.
    pub(super) fn relative_std(&self) -> Vec<f64> {
        (0..self.n())
            .map(|j| finite(self.rs_inv.row(j).norm()))
            .collect()
    }

    /// `prod_k |R_s,kk|^(-1/n)`.
    pub(super) fn d_optimal(&self) -> f64 {
        let log_det: f64 = self.rs.diagonal().iter().map(|d| d.abs().ln()).sum();
        finite((-log_det / self.n() as f64).exp())
    }

    /// `|R_s^-1|_F / sqrt(n)`.
    pub(super) fn relative_a(&self) -> f64 {
        finite(self.rs_inv.norm() / (self.n() as f64).sqrt())
    }
}

/// The inverse of an upper triangular `n x n` matrix by back substitution, column by column in a
/// fixed order; `None` if a diagonal entry is zero or the result is not finite.
pub(super) fn upper_inverse(r: &DMatrix<f64>) -> Option<DMatrix<f64>> {
    let n = r.ncols();
    let mut inv = DMatrix::zeros(n, n);
    for j in 0..n {
        for i in (0..=j).rev() {
            let mut s = if i == j { 1.0 } else { 0.0 };
            for k in i + 1..=j {
                s -= r[(i, k)] * inv[(k, j)];
            }
            inv[(i, j)] = s / r[(i, i)];
        }
    }
    inv.iter().all(|v| v.is_finite()).then_some(inv)
}

/// `a b` (`a` is `m x k`, `b` is `k x n`), column j of the result `sum_k b[k, j] a_k` with k
/// ascending: the same bits on every processor.
pub(super) fn product(a: &DMatrix<f64>, b: &DMatrix<f64>) -> DMatrix<f64> {
    let (m, n) = (a.nrows(), b.ncols());
    let mut out = DMatrix::zeros(m, n);
    for j in 0..n {
        let mut col = out.column_mut(j);
        for k in 0..a.ncols() {
            let f = b[(k, j)];
            if f != 0.0 {
                col.axpy(f, &a.column(k), 1.0);
            }
        }
    }
    out
}

/// `a^T a`, entry by entry in a fixed order.
pub(super) fn gram(a: &DMatrix<f64>) -> DMatrix<f64> {
    let n = a.ncols();
    let mut out = DMatrix::zeros(n, n);
    for j in 0..n {
        for i in 0..=j {
            let v = dot(a.column(i).as_slice(), a.column(j).as_slice());
            out[(i, j)] = v;
            out[(j, i)] = v;
        }
    }
    out
}

/// The upper Cholesky factor `U` (`a = U^T U`) of a symmetric `n x n` matrix, in a fixed order;
/// `None` unless it is positive definite.
pub(super) fn cholesky_upper(a: &DMatrix<f64>) -> Option<DMatrix<f64>> {
    let n = a.ncols();
    let mut u = DMatrix::zeros(n, n);
    for j in 0..n {
        for i in 0..=j {
            let mut s = a[(i, j)];
            for k in 0..i {
                s -= u[(k, i)] * u[(k, j)];
            }
            if i == j {
                if s.is_nan() || s <= 0.0 {
                    return None;
                }
                u[(j, j)] = s.sqrt();
            } else {
                u[(i, j)] = s / u[(i, i)];
            }
        }
    }
    Some(u)
}

/// `v_max v_max^T / s_max^2 - v_min v_min^T / s_min^2` of the square `r`: the `Y` of
/// `d ln cond_2` (as `super::gradient::cond_weight` for six columns).
pub(super) fn cond_weight(r: &DMatrix<f64>) -> DMatrix<f64> {
    let (s, v) = singular_values_and_vectors_n(r);
    let (max, min) = (s.imax(), s.imin());
    let n = r.ncols();
    DMatrix::from_fn(n, n, |i, j| {
        v[(i, max)] * v[(j, max)] / (s[max] * s[max])
            - v[(i, min)] * v[(j, min)] / (s[min] * s[min])
    })
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    stiffid_core::math::linalg::dot(a, b)
}

/// `v`, or `+infinity` if it is not finite.
fn finite(v: f64) -> f64 {
    if v.is_finite() {
        v
    } else {
        f64::INFINITY
    }
}
