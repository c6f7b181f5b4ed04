//! Validation of an identified stiffness on measurements it was not fitted to (Zhang et al. 2021,
//! Section IV-B, Eq. 22, Table 7).
//!
//! For each measurement the forward model predicts the translation of its measuring point,
//! `delta_c = J_m (h .* tau)` (Eq. 4-7; computed as the measurement's rows of `Psi` times `h`), and
//! `delta_b = |delta_m - delta_c|` (Eq. 22) is how far the prediction is off.

use crate::identify::{observations, Measurement};
use crate::{Error, Result, Setup};
use nalgebra::{Vector3, Vector6};

/// The check of one measurement.
#[derive(Debug, Clone, PartialEq)]
pub struct PointCheck {
    /// The posture's label.
    pub posture: String,
    /// The measuring point, 0-based.
    pub point: usize,
    /// Measured translation `delta_m`, base frame, m.
    pub measured: Vector3<f64>,
    /// Predicted translation `delta_c`, base frame, m.
    pub predicted: Vector3<f64>,
    /// `delta_b = |delta_m - delta_c|` (Eq. 22), m.
    pub delta_b: f64,
}

/// The validation of a stiffness on a list of measurements.
#[derive(Debug, Clone, PartialEq)]
pub struct Validation {
    /// One check per measurement, in the order given.
    pub checks: Vec<PointCheck>,
    /// Mean of `delta_b`, m.
    pub mean: f64,
    /// Largest `delta_b`, m.
    pub max: f64,
    /// Root mean square of `delta_b`, m.
    pub rms: f64,
}

/// Predicts every measurement with joint stiffness `stiffness` (Nm/rad) and compares (Eq. 22).
///
/// # Errors
/// [`Error::InvalidField`] (`stiffness`) unless all six values are finite and positive, or
/// (`measurements`) for an empty list; those of [`observations`].
pub fn validate(
    setup: &Setup,
    stiffness: &Vector6<f64>,
    measurements: &[Measurement],
) -> Result<Validation> {
    if !stiffness.iter().all(|k| k.is_finite() && *k > 0.0) {
        return Err(Error::InvalidField {
            field: "stiffness".into(),
            message: "expected six finite numbers > 0 Nm/rad".into(),
        });
    }
    if measurements.is_empty() {
        return Err(Error::InvalidField {
            field: "measurements".into(),
            message: "expected at least one measurement".into(),
        });
    }
    let obs = observations(setup, measurements)?;
    let predicted = &obs.psi * stiffness.map(|k| 1.0 / k);
    let checks: Vec<PointCheck> = measurements
        .iter()
        .enumerate()
        .map(|(i, meas)| {
            let predicted: Vector3<f64> = predicted.fixed_rows::<3>(3 * i).into_owned();
            PointCheck {
                posture: meas.posture.clone(),
                point: meas.point,
                measured: meas.displacement,
                predicted,
                delta_b: (meas.displacement - predicted).norm(),
            }
        })
        .collect();
    let n = checks.len() as f64;
    let mean = checks.iter().map(|c| c.delta_b).sum::<f64>() / n;
    let max = checks.iter().map(|c| c.delta_b).fold(0.0, f64::max);
    let rms = (checks.iter().map(|c| c.delta_b.powi(2)).sum::<f64>() / n).sqrt();
    Ok(Validation {
        checks,
        mean,
        max,
        rms,
    })
}
