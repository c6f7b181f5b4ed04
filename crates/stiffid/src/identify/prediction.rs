//! The calibration of prediction intervals from a cross-validation over postures: each fold's
//! compliance and the scores (P1) of its held-out coordinates ([`crate::model::prediction`],
//! jackknife+ and CV+, Barber, Candes, Ramdas and Tibshirani 2021).

use super::cross_validation::CrossValidation;
use crate::model::prediction::{Calibration, HeldOut};
use crate::observation::Observations;

/// The calibration of the cross-validation `cv` of `obs` ([`crate::model::prediction`], P1),
/// with the noise floor `noise_floor` (m).
pub fn calibrate(obs: &Observations, cv: &CrossValidation, noise_floor: f64) -> Calibration {
    let folds = cv
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
    Calibration {
        postures: obs.postures,
        noise_floor,
        folds,
    }
}
