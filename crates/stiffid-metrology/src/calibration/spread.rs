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

use super::error_model::{ErrorModel, Observation};
use super::fit::Fit;
use nalgebra::{Vector3, Vector6};
use stiffid_core::Result;

/// The RMS over the postures `qs` (axis angles, rad) of the standard deviation (3D, m) of the
/// position `fit` predicts for the measuring point and external axes of `like` (a reading of the
/// fit: its point, carrier and table), section docs; 0 without postures.
///
/// # Errors
/// Those of [`ErrorModel::jacobian_of`].
pub(crate) fn postures_sd(
    model: &ErrorModel,
    fit: &Fit,
    like: &Observation,
    qs: &[Vector6<f64>],
) -> Result<f64> {
    if qs.is_empty() {
        return Ok(0.0);
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
    let propagated = &j * &fit.covariance;
    let variance: f64 = (propagated.row_iter().zip(j.row_iter()))
        .map(|(a, b)| a.dot(&b))
        .sum();
    Ok((variance / observations.len() as f64).max(0.0).sqrt())
}
