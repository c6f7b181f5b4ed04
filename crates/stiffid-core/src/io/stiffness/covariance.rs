//! The checks of a compliance covariance: finite, symmetric, positive semi-definite.

use super::invalid;
use crate::Result;
use nalgebra::{DMatrix, Matrix6};

/// Checks a covariance `Cov(h)` of the compliance, (rad/Nm)^2 (the key
/// `compliance_covariance_rad2_per_nm2`; paper eq. 12): finite, symmetric to 1e-9 of the largest
/// diagonal entry, non-negative diagonal, positive semi-definite (no eigenvalue below -1e-9 of the
/// largest diagonal entry).
///
/// # Errors
/// [`Error::InvalidField`](crate::Error::InvalidField) naming `compliance_covariance_rad2_per_nm2`.
pub(crate) fn check_covariance(c: &Matrix6<f64>) -> Result<()> {
    let c = DMatrix::from_column_slice(6, 6, c.as_slice());
    check_covariance_of(&c, "compliance_covariance_rad2_per_nm2")
}

/// `check_covariance` of a square matrix of any size (n x n, SI), the error naming `field`.
///
/// # Errors
/// [`Error::InvalidField`](crate::Error::InvalidField) naming `field`.
pub fn check_covariance_of(c: &DMatrix<f64>, field: &str) -> Result<()> {
    let scale = c.diagonal().amax();
    let valid = c.iter().all(|v| v.is_finite())
        && c.diagonal().iter().all(|v| *v >= 0.0)
        && (c - c.transpose()).amax() <= 1e-9 * scale
        && semi_definite(c, scale);
    match valid {
        true => Ok(()),
        false => Err(invalid(
            field.into(),
            format!(
                "expected a covariance: a symmetric positive semi-definite {0}x{0} matrix of finite numbers",
                c.nrows()
            ),
        )),
    }
}

/// Whether the symmetric part of `c` (finite, largest diagonal entry `scale`) has no eigenvalue
/// below `-1e-9 scale`: a covariance gives every combination of the parameters a variance >= 0,
/// so the standard deviations propagated from it are real.
fn semi_definite(c: &DMatrix<f64>, scale: f64) -> bool {
    let symmetric = (c + c.transpose()) * 0.5;
    nalgebra::SymmetricEigen::try_new(symmetric, f64::EPSILON, 10_000)
        .is_some_and(|e| e.eigenvalues.min() >= -1e-9 * scale)
}
