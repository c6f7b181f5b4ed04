//! How uncertain a calibration's predictions are where the robot can go, not only where it was
//! read: the fit's covariance carried to measuring points at postures spread over the robot's
//! joint limits.
//!
//! A reading's predicted position `mu(x)` has the covariance `J_f C J_f^T` (`J_f` the Jacobian of
//! [`ErrorModel::jacobian_of`] at the fit, its fitted parameters' columns; `C` the fit's
//! covariance, [`Fit::covariance`], the posterior of the priors where the fit has them). Its
//! trace is the position's variance. Over [`super::gravity::spanning`] postures of the robot's
//! joint limits it measures what the readings leave open: a term the readings hold only through
//! its prior (gravity terms fitted on a thin sweep of the joints that carry the weight) spreads the
//! predictions there by the prior's size, millimetres, where a term they determine spreads them
//! by about the noise over the square root of the readings.
//!
//! *At another noise.* The covariance is the posterior's, `C = (D + P)^-1`: `D` what the readings
//! determine (inversely as the square of the noise the fit was weighed at), `P` its prior rows'
//! precision ([`Fit::prior_precision`]). A model whose residuals another model leaves smaller by
//! the factor `s` (the same gravity model with joint error maps, which hold an axis's periodic
//! error the fit without them counts as noise) is known from its readings `1/s^2` times better
//! and from its priors as well: `C_s = (D / s^2 + P)^-1` ([`postures_sds`]). The terms the
//! readings determine spread `s` times less, those left to their prior by as much.

use super::error_model::{ErrorModel, Observation};
use super::fit::Fit;
use nalgebra::{DMatrix, Vector3, Vector6};
use stiffid_core::Result;

/// The RMS over the postures `qs` (axis angles, rad) of the standard deviation (3D, m) of the
/// position `fit` predicts for the measuring point and external axes of `like` (a reading of the
/// fit: its point, carrier and table), section docs, with the readings' noise scaled by each of
/// `scales` (module docs, *At another noise*; 1 the fit's own covariance), the Jacobian over `qs`
/// taken once; 0 without postures.
///
/// # Errors
/// Those of [`ErrorModel::jacobian_of`].
pub(crate) fn postures_sds(
    model: &ErrorModel,
    fit: &Fit,
    like: &Observation,
    qs: &[Vector6<f64>],
    scales: &[f64],
) -> Result<Vec<f64>> {
    if qs.is_empty() {
        return Ok(vec![0.0; scales.len()]);
    }
    let observations: Vec<Observation> = (qs.iter().enumerate())
        .map(|(posture, &q)| Observation {
            posture,
            q,
            measured: Vector3::zeros(),
            wrench: Vector6::zeros(),
            direction: Vector6::zeros(),
            ..like.clone()
        })
        .collect();
    let j = model
        .jacobian_of(&fit.estimate.values, &observations)?
        .select_columns(fit.fitted.iter());
    Ok((scales.iter())
        .map(|&s| {
            let covariance = at_noise(fit, s);
            let propagated = &j * &covariance;
            let variance: f64 = (propagated.row_iter().zip(j.row_iter()))
                .map(|(a, b)| a.dot(&b))
                .sum();
            (variance / observations.len() as f64).max(0.0).sqrt()
        })
        .collect())
}

/// The covariance of `fit` with the readings' noise scaled by `s` (module docs, *At another
/// noise*): `(D / s^2 + P)^-1`, computed in the basis of the parameters' standard deviations (a
/// correlation matrix's scale); `s^2 C` where the fit has no prior rows or `C` is not positive
/// definite (rounding).
pub(super) fn at_noise(fit: &Fit, s: f64) -> DMatrix<f64> {
    let c = &fit.covariance;
    let p = &fit.prior_precision;
    if s == 1.0 || p.len() != c.nrows() || p.iter().all(|&v| v == 0.0) {
        return c * (s * s);
    }
    let d = c.diagonal().map(|v| v.max(0.0).sqrt());
    if d.iter().any(|&v| v == 0.0 || !v.is_finite()) {
        return c * (s * s);
    }
    let n = c.nrows();
    let scaled = DMatrix::from_fn(n, n, |a, b| c[(a, b)] / (d[a] * d[b]));
    let Some(inverse) = scaled.cholesky().map(|f| f.inverse()) else {
        return c * (s * s);
    };
    let mut precision = inverse / (s * s);
    for i in 0..n {
        let prior = p[i] * d[i] * d[i];
        precision[(i, i)] += prior - prior / (s * s);
    }
    match precision.cholesky() {
        Some(f) => {
            let unit = f.inverse();
            DMatrix::from_fn(n, n, |a, b| unit[(a, b)] * d[a] * d[b])
        }
        None => c * (s * s),
    }
}
