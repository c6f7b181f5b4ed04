//! The gravity prior weighed against the residuals' noise (the module docs' *Thin readings*).

use super::{fit_once, strength, Fit, GravityPrior, Options, MAX_ITERATIONS};
use crate::calibration::error_model::{ErrorModel, Estimate, Observation};
use stiffid_core::Result;

/// Most fits of the noise's fixed point ([`GravityPrior`] weighed against the residuals' noise:
/// module docs, *Thin readings*).
pub(crate) const MAX_REWEIGHTS: usize = 4;

/// The relative change of the noise under which its fixed point is reached.
pub(crate) const NOISE_TOLERANCE: f64 = 0.05;

/// [`super::fit_within`] at most `limit` iterations, the gravity prior weighed against the residuals'
/// noise when `reweigh` and the model has gravity terms ([`reweighed`]; module docs, *Thin
/// readings*): fitted anew from `start` with the noise per coordinate of the last fit's
/// residuals (`|r|^2 / (3n - p_e)`, `p_e` its effective parameters) while it exceeds the
/// prior's noise by more than [`NOISE_TOLERANCE`], at most [`MAX_REWEIGHTS`] times; then, when
/// `choose`, the prior's strength chosen by cross-validation ([`strength::chosen`]) and, where it
/// is tighter than stated, fitted anew from `start` at it; the last fit's iterations and stop.
pub(super) fn fit_with(
    model: &ErrorModel,
    observations: &[Observation],
    start: &Estimate,
    options: &Options,
    (limit, reweigh, choose): (usize, bool, bool),
) -> Result<Fit> {
    let mut fit = fit_once(model, observations, start, options, limit)?;
    let Some(prior) = options.gravity.filter(|_| reweigh && reweighed(model)) else {
        return Ok(fit);
    };
    let mut noise = prior.noise;
    let with = |gravity| Options {
        gravity: Some(gravity),
        ..*options
    };
    for _ in 0..MAX_REWEIGHTS {
        let dof = 3.0 * observations.len() as f64 - fit.effective_parameters;
        let sigma = (fit.residuals.norm_squared() / dof.max(1.0)).sqrt();
        if !(sigma.is_finite() && sigma > noise * (1.0 + NOISE_TOLERANCE)) {
            break;
        }
        noise = sigma;
        fit = fit_once(
            model,
            observations,
            start,
            &with(GravityPrior { noise, ..prior }),
            limit,
        )?;
    }
    let weighed = GravityPrior { noise, ..prior };
    let strength = match choose {
        true => strength::chosen(model, observations, &fit, &with(weighed))?,
        false => 1.0,
    };
    if strength > 1.0 {
        let deflection = prior.deflection / strength;
        fit = fit_once(
            model,
            observations,
            start,
            &with(GravityPrior {
                deflection,
                ..weighed
            }),
            limit,
        )?;
        fit.gravity_deflection = Some(deflection);
    }
    fit.gravity_noise = (noise > prior.noise).then_some(noise);
    Ok(fit)
}

/// [`fit`](super::fit) with the gravity prior's strength chosen by the readings (module docs,
/// *The prior's strength chosen by the readings*), for a gravity model whose terms the readings
/// may not tell from a misfit. `calibrate` does not use it: every gravity model there, chosen by
/// the ladder or given, is fitted at the stated bound ([`fit`](super::fit)). The same as
/// [`fit`](super::fit) for a model without gravity terms or with maps.
///
/// # Errors
/// Those of [`fit`](super::fit); [`stiffid_core::Error::NotFinite`] when an SVD of the choice
/// does not converge.
pub fn fit_choosing_strength(
    model: &ErrorModel,
    observations: &[Observation],
    start: &Estimate,
    options: &Options,
) -> Result<Fit> {
    fit_with(
        model,
        observations,
        start,
        options,
        (MAX_ITERATIONS, true, true),
    )
}

/// [`fit`](super::fit) with the gravity prior weighed against the noise [`GravityPrior::noise`] states
/// only, never the residuals' (the comparison of the module docs' *Thin
/// readings*).
///
/// # Errors
/// Those of [`fit`](super::fit).
pub fn fit_at_stated_noise(
    model: &ErrorModel,
    observations: &[Observation],
    start: &Estimate,
    options: &Options,
) -> Result<Fit> {
    fit_with(
        model,
        observations,
        start,
        options,
        (MAX_ITERATIONS, false, false),
    )
}

/// Whether the fit of `model` weighs its gravity prior against the residuals' noise: a model with
/// gravity terms and no maps (the maps' coefficients have their own ridge).
fn reweighed(model: &ErrorModel) -> bool {
    !model.gravity().is_empty() && model.map_start().is_none()
}
