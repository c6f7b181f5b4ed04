//! Linear least squares for the observation matrix, by Householder QR (never normal equations).
//!
//! `Psi = Q R` with `Q` (m x 6) orthonormal columns and `R` (6x6) upper triangular. Then
//! `h = R^-1 Q^T delta` solves Eq. 13-14 without forming `Psi^T Psi` (whose condition number is
//! `cond^2(Psi)`, Eq. 19), and `(Psi^T Psi)^-1 = R^-1 R^-T`. The singular values of `R` are those of
//! `Psi`. A factor is made once per observation matrix and reused for many right-hand sides (Monte
//! Carlo runs). A problem too large to hold `Psi` is reduced block by block instead ([`Reduced`]).
//!
//! The kernels are specialised to six columns (`crate::math::linalg`): Householder QR in place (LAPACK
//! `dgeqrf` convention, `Q` kept as its six reflectors) and one-sided Jacobi (Hestenes) for the
//! singular values of `R`, accurate to a few ulps relative to each singular value (Demmel & Veselic
//! 1992), as good as the SVD.

mod reduced;

pub use reduced::{Reduced, Solution};

use crate::math::householder::{householder_qr, upper_triangle};
use crate::math::jacobi::singular_values;
use crate::math::linalg::CappedSvd;
use crate::math::linalg::{axpy, column_norms, dot};
use crate::{Error, Result};
use nalgebra::{DMatrix, DVector, Matrix6, Vector6};

/// Relative singular-value threshold below which `Psi` counts as rank deficient.
pub const RANK_TOLERANCE: f64 = 1e-10;

/// A QR factorisation of a full-column-rank `m x 6` observation matrix.
#[derive(Debug, Clone)]
pub struct Factor {
    /// `R` on and above the diagonal, the Householder vectors (without their leading 1) below.
    reflectors: DMatrix<f64>,
    /// `tau_k` of the reflectors `H_k = I - tau_k v_k v_k^T`, `Q = H_1 .. H_6`.
    taus: Vector6<f64>,
    r: Matrix6<f64>,
    r_inv: Matrix6<f64>,
}

impl Factor {
    /// Factors `psi` (m x 6, m >= 6) in place: it takes the matrix by value and reuses its storage
    /// for the reflectors, as nalgebra's `QR::new` and `SVD::try_new` do (clone to keep `Psi`).
    /// `try_`: it fails unless `Psi` has full column rank (nalgebra's convention for a fallible
    /// constructor).
    ///
    /// The rank rule: `Psi` is rank deficient when a column's norm is at most [`RANK_TOLERANCE`]
    /// times the largest, or when `cond_2(Psi) >= 1 / RANK_TOLERANCE`. The condition number is
    /// bracketed first by `|R|_F |R^-1|_F / 6 <= cond_2(R) <= |R|_F |R^-1|_F`; the singular values
    /// are only computed when the bracket leaves the rule undecided.
    ///
    /// # Errors
    /// [`Error::TooFewRows`] for m < 6 (or a matrix without 6 columns), [`Error::NotFinite`] for NaN
    /// or infinite entries (checked before any decomposition), [`Error::Unidentifiable`] naming the
    /// joints whose column is zero (no posture loads them or no measuring point moves with them) or
    /// whose columns are dependent.
    pub fn try_new(mut psi: DMatrix<f64>) -> Result<Self> {
        let m = psi.nrows();
        if m < 6 || psi.ncols() != 6 {
            return Err(Error::TooFewRows { rows: m });
        }
        let norms = column_norms(psi.as_slice(), m);
        if !norms.iter().all(|n| n.is_finite()) && !psi.iter().all(|v| v.is_finite()) {
            return Err(Error::NotFinite {
                what: "the observation matrix".into(),
            });
        }
        let taus = householder_qr(psi.as_mut_slice(), m);
        let r = upper_triangle(psi.as_slice(), m);
        let r_inv = checked_inverse(&r, &norms)?;
        Ok(Self {
            reflectors: psi,
            taus,
            r,
            r_inv,
        })
    }

    /// The least-squares solution `h = argmin |Psi h - delta|` (Eq. 13-14). `delta` has m entries.
    ///
    /// # Panics
    /// If `delta` does not have as many entries as `Psi` has rows.
    pub fn solve(&self, delta: &DVector<f64>) -> Vector6<f64> {
        self.r_inv * self.project(delta)
    }

    /// The first six entries `c` of `Q^T delta`: `|Psi h - delta|^2 = |R h - c|^2 + const`, so
    /// any problem in `h` over these rows (e.g. with bounds) can be solved on the 6x6 `R`.
    ///
    /// # Panics
    /// If `delta` does not have as many entries as `Psi` has rows.
    pub fn project(&self, delta: &DVector<f64>) -> Vector6<f64> {
        let mut d = delta.clone();
        self.reflect(&mut d);
        Vector6::from_column_slice(&d.as_slice()[..6])
    }

    /// `d <- Q^T d`: the reflectors `H_1 .. H_6` applied in turn.
    fn reflect(&self, d: &mut DVector<f64>) {
        assert_eq!(
            d.len(),
            self.reflectors.nrows(),
            "delta must have one entry per row of Psi"
        );
        let m = d.len();
        let (a, d) = (self.reflectors.as_slice(), d.as_mut_slice());
        for k in 0..6 {
            let v = &a[k * m + k + 1..(k + 1) * m];
            let w = self.taus[k] * (d[k] + dot(v, &d[k + 1..]));
            d[k] -= w;
            axpy(-w, v, &mut d[k + 1..]);
        }
    }

    /// `(Psi^T Psi)^-1 = R^-1 R^-T`: the covariance of `h` per unit noise variance.
    pub fn unit_covariance(&self) -> Matrix6<f64> {
        self.r_inv * self.r_inv.transpose()
    }

    /// The triangular factor `R` (6x6).
    pub fn r(&self) -> &Matrix6<f64> {
        &self.r
    }

    /// `R^-1` (6x6, upper triangular).
    pub fn r_inv(&self) -> &Matrix6<f64> {
        &self.r_inv
    }

    /// The singular values of `Psi`, in no particular order (computed on each call).
    pub fn singular_values(&self) -> Vector6<f64> {
        singular_values(&self.r)
    }

    /// The 2-norm condition number `cond_2(Psi) = s_max / s_min` (computed on each call).
    pub fn cond(&self) -> f64 {
        crate::math::jacobi::cond(&self.r)
    }
}

/// `R^-1` after the rank rule of [`Factor::try_new`] on `R` and the column norms of `Psi`.
fn checked_inverse(r: &Matrix6<f64>, norms: &Vector6<f64>) -> Result<Matrix6<f64>> {
    let largest = norms.max();
    let unloaded: Vec<usize> = (0..6)
        .filter(|&j| norms[j] <= largest * RANK_TOLERANCE)
        .map(|j| j + 1)
        .collect();
    if !unloaded.is_empty() {
        return Err(Error::Unidentifiable {
            joints: unloaded,
            reason:
                "no posture loads the joint or moves a measuring point with it (zero column of Psi)"
                    .into(),
        });
    }
    let r_inv = r
        .solve_upper_triangular(&Matrix6::identity())
        .filter(|inv| inv.iter().all(|v| v.is_finite()))
        .ok_or_else(|| dependent_columns(r))?;
    let bound = r.norm() * r_inv.norm();
    let deficient = match bound {
        b if !b.is_finite() => true,
        b if b * RANK_TOLERANCE < 1.0 => false,
        b if b * RANK_TOLERANCE >= 6.0 => true,
        _ => {
            let s = singular_values(r);
            s.min() <= s.max() * RANK_TOLERANCE
        }
    };
    if deficient {
        return Err(dependent_columns(r));
    }
    Ok(r_inv)
}

/// The error for dependent columns of `Psi`: the joints with a large share in the right singular
/// vector of the smallest singular value of `R`.
fn dependent_columns(r: &Matrix6<f64>) -> Error {
    let joints = r
        .capped_svd(false, true)
        .and_then(|svd| {
            let (imin, _) = svd.singular_values.argmin();
            let v = svd.v_t?.row(imin).transpose();
            Some(
                (0..6)
                    .filter(|&j| v[j].abs() > 0.1)
                    .map(|j| j + 1)
                    .collect(),
            )
        })
        .unwrap_or_else(|| (1..=6).collect());
    Error::Unidentifiable {
        joints,
        reason: "their columns of Psi are linearly dependent: choose postures that load them differently".into(),
    }
}
