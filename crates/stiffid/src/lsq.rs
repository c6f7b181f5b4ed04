//! Linear least squares for the observation matrix, by Householder QR (never normal equations).
//!
//! `Psi = Q R` with `Q` (m x 6) orthonormal columns and `R` (6x6) upper triangular. Then
//! `h = R^-1 Q^T delta` solves Eq. 13-14 without forming `Psi^T Psi` (whose condition number is
//! `cond^2(Psi)`, Eq. 19), and `(Psi^T Psi)^-1 = R^-1 R^-T`. The singular values of `R` are those of
//! `Psi`. A factor is made once per observation matrix and reused for many right-hand sides (Monte
//! Carlo runs).

use crate::{Error, Result};
use nalgebra::{DMatrix, DVector, Matrix6, Vector6};

/// Relative singular-value threshold below which `Psi` counts as rank deficient.
pub const RANK_TOLERANCE: f64 = 1e-10;

/// A QR factorisation of a full-column-rank `m x 6` observation matrix.
#[derive(Debug, Clone)]
pub struct Factor {
    qt: DMatrix<f64>,
    r: Matrix6<f64>,
    r_inv: Matrix6<f64>,
    singular_values: Vector6<f64>,
}

impl Factor {
    /// Factors `psi` (m x 6, m >= 6).
    ///
    /// # Errors
    /// [`Error::TooFewRows`] for m < 6 (or a matrix without 6 columns), [`Error::NotFinite`] for NaN
    /// or infinite entries (checked before any decomposition), [`Error::Unidentifiable`] naming the
    /// joints whose column is zero (no posture loads them or no measuring point moves with them) or
    /// whose columns are dependent (smallest singular value below [`RANK_TOLERANCE`] times the
    /// largest).
    pub fn try_new(psi: &DMatrix<f64>) -> Result<Self> {
        if psi.nrows() < 6 || psi.ncols() != 6 {
            return Err(Error::TooFewRows { rows: psi.nrows() });
        }
        if !psi.iter().all(|v| v.is_finite()) {
            return Err(Error::NotFinite {
                what: "the observation matrix".into(),
            });
        }
        let scale = psi.amax();
        let unloaded: Vec<usize> = (0..6)
            .filter(|&j| psi.column(j).amax() <= scale * RANK_TOLERANCE)
            .map(|j| j + 1)
            .collect();
        if !unloaded.is_empty() {
            return Err(Error::Unidentifiable {
                joints: unloaded,
                reason: "no posture loads the joint or moves a measuring point with it (zero column of Psi)".into(),
            });
        }
        let qr = psi.clone().qr();
        let r: Matrix6<f64> = qr.r().fixed_view::<6, 6>(0, 0).into_owned();
        let svd = r
            .try_svd(false, true, f64::EPSILON, 200)
            .ok_or(Error::NotFinite {
                what: "the SVD of the observation matrix".into(),
            })?;
        let (imin, smin) = svd.singular_values.argmin();
        if smin <= svd.singular_values.max() * RANK_TOLERANCE {
            let v = svd.v_t.expect("requested").row(imin).transpose();
            let joints = (0..6)
                .filter(|&j| v[j].abs() > 0.1)
                .map(|j| j + 1)
                .collect();
            return Err(Error::Unidentifiable {
                joints,
                reason: "their columns of Psi are linearly dependent: choose postures that load them differently".into(),
            });
        }
        let r_inv = r.try_inverse().ok_or(Error::Unidentifiable {
            joints: (1..=6).collect(),
            reason: "R is singular".into(),
        })?;
        Ok(Self {
            qt: qr.q().transpose(),
            r,
            r_inv,
            singular_values: svd.singular_values,
        })
    }

    /// The least-squares solution `h = argmin |Psi h - delta|` (Eq. 13-14). `delta` has m entries.
    pub fn solve(&self, delta: &DVector<f64>) -> Vector6<f64> {
        self.r_inv * (&self.qt * delta)
    }

    /// `(Psi^T Psi)^-1 = R^-1 R^-T`: the covariance of `h` per unit noise variance.
    pub fn unit_covariance(&self) -> Matrix6<f64> {
        self.r_inv * self.r_inv.transpose()
    }

    /// The triangular factor `R` (6x6).
    pub fn r(&self) -> &Matrix6<f64> {
        &self.r
    }

    /// `Q^T` (6 x m).
    pub fn qt(&self) -> &DMatrix<f64> {
        &self.qt
    }

    /// The singular values of `Psi`, in no particular order.
    pub fn singular_values(&self) -> &Vector6<f64> {
        &self.singular_values
    }

    /// The 2-norm condition number `cond_2(Psi) = s_max / s_min`.
    pub fn cond(&self) -> f64 {
        self.singular_values.max() / self.singular_values.min()
    }
}
