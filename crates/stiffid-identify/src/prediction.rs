//! The calibration of prediction intervals from a cross-validation over postures: each fold's
//! compliance and the scores (P1) of its held-out coordinates ([`stiffid_core::model::prediction`],
//! jackknife+ and CV+, Barber, Candes, Ramdas and Tibshirani 2021), and what the deflection
//! intervals (P3) take from them: the model's error with the tracker noise and the estimate's
//! own variance taken out, and the studentised scores (P4).

use super::cross_validation::CrossValidation;
use stiffid_core::model::prediction::{jackknife_covariance, Calibration, Deflection, HeldOut};
use stiffid_core::observation::Observations;

/// The calibration of the cross-validation `cv` of `obs` ([`stiffid_core::model::prediction`], P1 to
/// P4), with the noise floor `noise_floor` (m: the standard deviation of one displacement
/// coordinate from the tracker noise).
pub fn calibrate(obs: &Observations, cv: &CrossValidation, noise_floor: f64) -> Calibration {
    let mut rows = Vec::new();
    let mut errors = Vec::new();
    let mut predicted = Vec::new();
    let folds: Vec<HeldOut> = cv
        .folds
        .iter()
        .map(|f| {
            let scores = f
                .measurements
                .iter()
                .enumerate()
                .flat_map(|(k, &i)| {
                    let e = f.residuals.fixed_rows::<3>(3 * k);
                    let mu = obs.delta.fixed_rows::<3>(3 * i) - e;
                    rows.extend(3 * i..3 * i + 3);
                    errors.extend(e.iter());
                    predicted.extend([mu.norm(); 3]);
                    let s = mu.norm() + noise_floor;
                    [0, 1, 2].map(|c| e[c].abs() / s)
                })
                .collect();
            HeldOut {
                compliance: f.compliance.clone(),
                scores,
            }
        })
        .collect();
    let covariance = jackknife_covariance(&folds, obs.postures);
    let variances: Vec<f64> = rows
        .iter()
        .map(|&r| {
            let row = obs.psi.row(r);
            (row * &covariance).dot(&row).max(0.0)
        })
        .collect();
    Calibration {
        postures: obs.postures,
        noise_floor,
        deflection: Deflection::from_held_out(
            &errors,
            &predicted,
            &variances,
            noise_floor,
            covariance,
        ),
        folds,
    }
}
