//! The joint error maps of a calibration ([`crate::metrology::calibration::maps`]): the choice by
//! cross-validation inside the fitted readings, its nested held-out gain, and the fit with the
//! maps chosen.

use crate::metrology::calibration::error_model::Observation;
use crate::metrology::calibration::fit::{self, Fit, Options};
use crate::metrology::calibration::maps::{self, Choice, Linear, Nested, Spec};
use crate::metrology::calibration::ErrorModel;
use crate::Result;

/// What the maps' choice found.
#[derive(Debug, Clone, PartialEq)]
pub struct Maps {
    /// What was asked.
    pub spec: Spec,
    /// The distinct postures of the fitted readings.
    pub postures: usize,
    /// The choice, when maps were considered.
    pub choice: Option<Choice>,
    /// Its held-out gain, when maps were considered.
    pub nested: Option<Nested>,
    /// Why no map was considered, when none was.
    pub skipped: Option<String>,
}

/// The model, fit and options after the maps of `spec`: those given when no map is chosen, else
/// the model with the chosen maps fitted from `fitted` with the chosen ridge.
///
/// # Errors
/// Those of [`ErrorModel::with_maps`], [`maps::choose`], [`maps::nested`] and [`fit::fit`].
pub(super) fn fit_maps(
    spec: Spec,
    model: ErrorModel,
    fitted: Fit,
    observations: &[Observation],
    options: Options,
) -> Result<(ErrorModel, Fit, Options, Maps)> {
    let mut postures: Vec<usize> = observations.iter().map(|o| o.posture).collect();
    postures.sort_unstable();
    postures.dedup();
    let mut report = Maps {
        spec,
        postures: postures.len(),
        choice: None,
        nested: None,
        skipped: None,
    };
    report.skipped = match spec {
        Spec::None => Some("--maps none".into()),
        Spec::Auto if postures.len() < maps::MIN_POSTURES => Some(format!(
            "{} distinct postures, fewer than the {} with which maps are chosen",
            postures.len(),
            maps::MIN_POSTURES
        )),
        _ => None,
    };
    if report.skipped.is_some() {
        return Ok((model, fitted, options, report));
    }
    let linear = Linear::at(
        &model,
        &fitted,
        observations,
        options.length,
        spec.candidates(),
    )?;
    let all: Vec<usize> = (0..postures.len()).collect();
    let choice = maps::choose(&linear, &all, spec)?;
    report.nested = Some(maps::nested(&linear, &all, spec)?);
    let harmonics = choice.harmonics;
    let ridge = choice.ridge;
    report.choice = Some(choice);
    if harmonics == [0; 6] {
        return Ok((model, fitted, options, report));
    }
    let model = model.with_maps(harmonics)?;
    let start = maps::extended(&model, &fitted.estimate);
    let options = Options { ridge, ..options };
    let fitted = fit::fit(&model, observations, &start, &options)?;
    Ok((model, fitted, options, report))
}
