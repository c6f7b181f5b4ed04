//! The held-out position error: readings the fit did not see, predicted by the calibrated model.
//!
//! The error of a held-out reading is `b(x, q) - T t` (base frame, m), the predicted position
//! of its measuring point minus the tracker's reading mapped by the calibrated registration.
//! [`cross_validate`] holds out one posture at a time (all its points), fits the rest and
//! predicts it: the leave-one-posture-out error, the prediction error of the model on postures
//! like the campaign's.

use super::error_model::{ErrorModel, Estimate, Observation};
use super::fit::{self, Options};
use nalgebra::{DVector, Vector3};
use rayon::prelude::*;
use stiffid_core::common::progress::{Progress, Tally};
use stiffid_core::{Error, Result};

/// The error of one held-out reading.
#[derive(Debug, Clone, PartialEq)]
pub struct PointError {
    /// The posture (0-based, in its readings).
    pub posture: usize,
    /// The measuring point, 0-based.
    pub point: usize,
    /// Whether `point` is a reflector on the positioner's table rather than a measuring point
    /// of the tool ([`super::error_model::Observation::table`]).
    pub table: bool,
    /// Predicted minus read, base frame, m.
    pub error: Vector3<f64>,
}

/// The held-out errors.
#[derive(Debug, Clone, PartialEq)]
pub struct Validation {
    /// One per held-out reading.
    pub errors: Vec<PointError>,
    /// RMS of the errors' lengths, m.
    pub rms: f64,
    /// The largest error's length, m.
    pub max: f64,
}

impl Validation {
    /// The summary of `errors`.
    pub fn new(errors: Vec<PointError>) -> Self {
        let n = errors.len().max(1) as f64;
        let rms = (errors.iter().map(|e| e.error.norm_squared()).sum::<f64>() / n).sqrt();
        let max = errors.iter().map(|e| e.error.norm()).fold(0.0, f64::max);
        Validation { errors, rms, max }
    }
}

/// The errors of `observations` at `estimate`.
///
/// # Errors
/// [`Error::InvalidField`] (`readings`) with no reading; those of
/// `ErrorModel::residuals`.
pub fn validate(
    model: &ErrorModel,
    estimate: &Estimate,
    observations: &[Observation],
) -> Result<Validation> {
    if observations.is_empty() {
        return Err(Error::InvalidField {
            field: "readings".into(),
            message: "expected held-out unloaded readings, got none".into(),
        });
    }
    let r = model.residuals(estimate, observations)?;
    Ok(Validation::new(
        observations
            .iter()
            .enumerate()
            .map(|(i, o)| PointError {
                posture: o.posture,
                point: o.point,
                table: o.table,
                error: r.fixed_rows::<3>(3 * i).into_owned(),
            })
            .collect(),
    ))
}

/// One fold of leave-one-posture-out: the fit without a posture and that posture's errors.
#[derive(Debug, Clone, PartialEq)]
pub struct Fold {
    /// The posture held out.
    pub posture: usize,
    /// The fit of the other postures, re-centred ([`Estimate::recentre`]).
    pub estimate: Estimate,
    /// The held-out posture's errors predicted by it.
    pub held: Validation,
    /// For a linearised fold ([`leave_one_out_linearised`]), the change of the values from the
    /// full fit's (SI; the frame's perturbation in the frame's six values): its errors are the
    /// full fit's plus the Jacobian at the full fit times it. `None` for a refitted fold.
    pub change: Option<DVector<f64>>,
}

/// Leave-one-posture-out: each posture predicted by the fit of the others, that fit one
/// Gauss-Newton step from the full fit `fit` ([`leave_one_out_linearised`]'s estimate: the
/// step of the problem without the posture, from the full fit's factorisation; exact to second
/// order in the change of the parameters), the held-out posture's errors evaluated there on the
/// model itself (not linearised). The cost of one fit for all the folds: 1000 postures of one
/// measuring point in about a second. `progress` hears a stage `cross-validation` with one unit
/// per posture.
///
/// # Errors
/// Those of [`leave_one_out_linearised`] and [`validate`].
pub fn cross_validate(
    model: &ErrorModel,
    observations: &[Observation],
    fit: &fit::Fit,
    options: &Options,
    progress: &dyn Progress,
) -> Result<Validation> {
    let folds = leave_one_out_linearised(model, observations, fit, options)?;
    progress.begin("cross-validation", folds.len());
    let tally = Tally::new(progress);
    let mut at = vec![Vec::new(); folds.iter().map(|f| f.posture + 1).max().unwrap_or(0)];
    for o in observations {
        at[o.posture].push(o.clone());
    }
    let held = (folds.par_iter())
        .map(|f| {
            let held = validate(model, &f.estimate, &at[f.posture]);
            tally.add(1);
            held.map(|v| v.errors)
        })
        .collect::<Result<Vec<_>>>();
    progress.end();
    Ok(Validation::new(held?.into_iter().flatten().collect()))
}

/// The held-out errors of every fold of [`leave_one_out`], in the order of the folds.
pub fn pooled(folds: &[Fold]) -> Validation {
    Validation::new(folds.iter().flat_map(|f| f.held.errors.clone()).collect())
}

/// The folds of [`cross_validate`], one per posture in increasing order.
///
/// # Errors
/// As [`cross_validate`].
pub fn leave_one_out(
    model: &ErrorModel,
    observations: &[Observation],
    start: &Estimate,
    options: &Options,
    progress: &dyn Progress,
) -> Result<Vec<Fold>> {
    let mut postures: Vec<usize> = observations.iter().map(|o| o.posture).collect();
    postures.sort_unstable();
    postures.dedup();
    if postures.len() < 2 {
        return Err(Error::InvalidField {
            field: "readings".into(),
            message: "cross-validation needs 2 postures or more".into(),
        });
    }
    progress.begin("cross-validation", postures.len());
    let tally = Tally::new(progress);
    let folds: Vec<Result<Fold>> = postures
        .par_iter()
        .map(|&p| {
            let (out, kept): (Vec<Observation>, Vec<Observation>) =
                observations.iter().cloned().partition(|o| o.posture == p);
            let fitted = fit::fit(model, &kept, start, options)?;
            let held = validate(model, &fitted.estimate, &out)?;
            tally.add(1);
            Ok(Fold {
                posture: p,
                estimate: fitted.estimate.recentre(),
                held,
                change: None,
            })
        })
        .collect();
    progress.end();
    folds.into_iter().collect()
}

/// The folds of [`leave_one_out`] linearised at the fit `fit` of `observations` with `options`
/// (`fit::leave_one_out_linearised`: exact to second order in the change of the parameters),
/// each held-out posture's errors linearised too: its residuals at the full fit plus the
/// Jacobian there times the fold's change of the values (the leave-one-out residual
/// `(I - H)^-1 r_p` of the linear model). Linear in the changes, so a fold that moves far along
/// a weakly determined direction changes the predictions by as little as that direction does:
/// the cost of one fit for all the folds.
///
/// # Errors
/// [`Error::InvalidField`] (`readings`) with fewer than 2 postures; those of
/// `fit::leave_one_out_linearised` and [`ErrorModel::jacobian_of`].
pub fn leave_one_out_linearised(
    model: &ErrorModel,
    observations: &[Observation],
    fit: &fit::Fit,
    options: &Options,
) -> Result<Vec<Fold>> {
    let folds = fit::leave_one_out_linearised(model, observations, fit, options)?;
    if folds.len() < 2 {
        return Err(Error::InvalidField {
            field: "readings".into(),
            message: "cross-validation needs 2 postures or more".into(),
        });
    }
    let jacobian = model.jacobian_of(&fit.estimate.values, observations)?;
    Ok(folds
        .into_par_iter()
        .map(|(p, estimate, change)| {
            let errors = (observations.iter().enumerate())
                .filter(|(_, o)| o.posture == p)
                .map(|(i, o)| PointError {
                    posture: p,
                    point: o.point,
                    table: o.table,
                    error: fit.residuals.fixed_rows::<3>(3 * i)
                        + jacobian.fixed_rows::<3>(3 * i) * &change,
                })
                .collect();
            Fold {
                posture: p,
                held: Validation::new(errors),
                estimate,
                change: Some(change),
            }
        })
        .collect())
}
