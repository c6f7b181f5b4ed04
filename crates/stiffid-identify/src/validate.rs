//! Validation of an identified stiffness on measurements it was not fitted to (Zhang et al. 2021,
//! Section IV-B, Eq. 22, Table 7).
//!
//! For each measurement the forward model predicts the translation of its measuring point,
//! `delta_c = J_m (h .* tau)` (Eq. 4-7; computed as the measurement's rows of `Psi` times `h`, over
//! every parameter of the setup's model: the drives and the virtual springs), and
//! `delta_b = |delta_m - delta_c|` (Eq. 22) is how far the prediction is off. Beside it, the size of
//! the measured deflections `|delta_m|` and the share of them the model explains,
//! `1 - RMS(delta_b) / RMS(|delta_m|)` (1: perfect prediction; 0: no better than predicting no
//! deflection; negative: worse).
//!
//! With a compliance that carries the held-out residuals of its identification
//! ([`Compliance::prediction`]), each measurement also gets its prediction interval
//! ([`stiffid_core::model::prediction`], jackknife+ or CV+) and the summary the share of the measured
//! coordinates inside their intervals: the coverage, to compare with the level.

use nalgebra::Vector3;
use stiffid_core::model::prediction::{check_level, inside, Interval, DEFAULT_LEVEL};
use stiffid_core::model::Compliance;
use stiffid_core::observation::{Measurement, Observations};
use stiffid_core::setup::Arm;
use stiffid_core::{Error, Result};

/// The check of one measurement.
#[derive(Debug, Clone, PartialEq)]
pub struct PointCheck {
    /// The posture ([`Measurement::posture`]).
    pub posture: usize,
    /// The measuring point, 0-based.
    pub point: usize,
    /// Measured translation `delta_m`, base frame, m.
    pub measured: Vector3<f64>,
    /// Predicted translation `delta_c`, base frame, m.
    pub predicted: Vector3<f64>,
    /// `delta_b = |delta_m - delta_c|` (Eq. 22), m.
    pub delta_b: f64,
    /// The prediction interval of each coordinate of `measured`, m, with the compliance's
    /// prediction calibration.
    pub interval: Option<Interval>,
}

/// How well the prediction intervals covered the measurements.
#[derive(Debug, Clone, PartialEq)]
pub struct Coverage {
    /// The intervals' level.
    pub level: f64,
    /// `jackknife+` or `cv+` ([`stiffid_core::model::prediction::Calibration::method`]).
    pub method: &'static str,
    /// Measured coordinates inside their intervals.
    pub covered: usize,
    /// Measured coordinates (three per measurement).
    pub coordinates: usize,
}

impl Coverage {
    /// `covered / coordinates`.
    pub fn coverage(&self) -> f64 {
        self.covered as f64 / self.coordinates as f64
    }
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
    /// Mean, largest and root mean square of the measured displacement magnitudes `|delta_m|`, m.
    pub measured: [f64; 3],
    /// `1 - RMS(delta_b) / RMS(|delta_m|)`: the share of the measured deflection the model explains.
    pub explained: f64,
    /// The coverage of the prediction intervals, with the compliance's prediction calibration.
    pub prediction: Option<Coverage>,
}

/// Predicts every measurement with the compliance `compliance` of every parameter of the arm's
/// model ([`stiffid_core::model`]; rad/Nm, m/N) and compares (Eq. 22); prediction intervals at
/// [`DEFAULT_LEVEL`] ([`compare_at`]).
///
/// # Errors
/// Those of [`compare_at`].
pub fn compare(
    arm: &Arm,
    compliance: &Compliance,
    measurements: &[Measurement],
) -> Result<Validation> {
    compare_at(arm, compliance, measurements, DEFAULT_LEVEL)
}

/// [`compare`] with prediction intervals at `level` (when the compliance carries a prediction
/// calibration).
///
/// # Errors
/// [`Error::InvalidField`] (`level`) outside 0.5 to 0.999;
/// Those of [`Compliance::check`]; [`Error::InvalidField`] (`stiffness`) unless every compliance
/// is positive, or (`measurements`) for an empty list; those of
/// [`Observations::from_measurements`].
pub fn compare_at(
    arm: &Arm,
    compliance: &Compliance,
    measurements: &[Measurement],
    level: f64,
) -> Result<Validation> {
    check_level("level", level)?;
    compliance.check(arm.model())?;
    if !compliance.h.iter().all(|h| *h > 0.0) {
        return Err(Error::InvalidField {
            field: "stiffness".into(),
            message: "expected finite numbers > 0 (Nm/rad, N/mm)".into(),
        });
    }
    if measurements.is_empty() {
        return Err(Error::InvalidField {
            field: "measurements".into(),
            message: "expected at least one measurement".into(),
        });
    }
    let obs = Observations::from_measurements(arm, measurements)?;
    let predicted = &obs.psi * &compliance.h;
    let checks: Vec<PointCheck> = measurements
        .iter()
        .enumerate()
        .map(|(i, meas)| {
            let predicted: Vector3<f64> = predicted.fixed_rows::<3>(3 * i).into_owned();
            let interval = compliance
                .prediction
                .as_ref()
                .map(|p| p.interval(&obs.psi.rows(3 * i, 3).into_owned(), level));
            PointCheck {
                posture: meas.posture,
                point: meas.point,
                measured: meas.displacement,
                predicted,
                delta_b: (meas.displacement - predicted).norm(),
                interval,
            }
        })
        .collect();
    let prediction = compliance.prediction.as_ref().map(|p| Coverage {
        level,
        method: p.method(),
        covered: checks
            .iter()
            .filter_map(|c| Some(inside(c.interval.as_ref()?, &c.measured.into())))
            .flatten()
            .filter(|b| *b)
            .count(),
        coordinates: 3 * checks.len(),
    });
    let [mean, max, rms] = summary(checks.iter().map(|c| c.delta_b));
    let measured = summary(checks.iter().map(|c| c.measured.norm()));
    Ok(Validation {
        checks,
        mean,
        max,
        rms,
        explained: 1.0 - rms / measured[2],
        measured,
        prediction,
    })
}

/// Mean, largest and root mean square of non-negative values.
fn summary(values: impl Iterator<Item = f64> + Clone) -> [f64; 3] {
    let n = values.clone().count() as f64;
    [
        values.clone().sum::<f64>() / n,
        values.clone().fold(0.0, f64::max),
        (values.map(|v| v * v).sum::<f64>() / n).sqrt(),
    ]
}
