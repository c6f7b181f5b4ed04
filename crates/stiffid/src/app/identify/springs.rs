//! The identify job over a model with virtual springs ([`stiffid_core::model`]), by the column-scaled
//! SVD: every parameter of the
//! setup's model identified by least squares, the bounded non-negative fit or a robust fit
//! ([`stiffid_identify::svd::fit_by`]), with its identifiability and intervals, and if asked the
//! cross-validation over postures ([`cross_validate_model`]): leave one posture out, or `K`
//! folds, each fold fitted as the full fit.
//!
//! Offsets beside the compliances take the six drives alone ([`super::drives`]).

use super::drives::{noise_floor, Request};
use super::{Fit as Method, Folds};
use crate::app::measurements::{angle_warnings, on_measurements, Origin};
use crate::app::{Warning, WarningKind};
use std::io::Read;
use stiffid_core::common::words::count;
use stiffid_core::model::prediction::Calibration;
use stiffid_core::observation::{Measurement, Observations};
use stiffid_core::JobOption;
use stiffid_core::{Error, Result, Setup};
use stiffid_identify::cross_validation::{cross_validate_model, CrossValidation};
use stiffid_identify::prediction::calibrate;
use stiffid_identify::svd::{fit_by, Fit};

/// What the identify job found over a model.
#[derive(Debug, Clone)]
pub struct Report {
    /// The setup as the user named it ([`super::Request::setup_name`]).
    pub setup: String,
    /// The setup's tracker noise (SI).
    pub noise: stiffid_core::setup::Noise,
    /// The data's name (a file's, or `arrays`).
    pub data_name: String,
    /// The fit asked for.
    pub method: Method,
    /// The fit of every parameter of the setup's model.
    pub fit: Fit,
    /// Where each measurement came from.
    pub origin: Origin,
    /// The cross-validation, if asked: stiffness in the order of [`Fit::parameters`], SI.
    pub cross_validation: Option<CrossValidation>,
    /// With the cross-validation: what prediction intervals are built from.
    pub prediction: Option<Calibration>,
    /// Results to look at before trusting them (parameters the data cannot separate,
    /// compliances that are not positive).
    pub warnings: Vec<Warning>,
    /// The stiffness file of the model comparison's bootstrap
    /// ([`super::comparison::Report::stiffness_file`]): the models the data support and their
    /// resampled parameter sets; `None` otherwise.
    pub model_form: Option<stiffid_core::io::stiffness::ModelFormSection>,
}

/// Runs the identify job over the setup's model (any number of parameters; the six drives alone
/// give the same compliance as [`super::drives`] to rounding).
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::Offsets`]) when offsets are asked; errors about the data as
/// [`Error::Input`] naming the data (a file's line and column): those of
/// the measurement file's parser, [`Observations::from_measurements`], [`fit_by`] and
/// [`cross_validate_model`] (a fold whose other postures cannot identify every parameter).
pub(super) fn run<R: Read>(request: Request<'_, R>) -> Result<Report> {
    let Request {
        setup,
        setup_name,
        data,
        fit: method,
        folds,
        offsets,
    } = request;
    if offsets {
        return Err(Error::InvalidOption {
            option: JobOption::Offsets,
            message:
                "offsets are fitted beside the six drive springs alone, not beside virtual springs"
                    .into(),
        });
    }
    let (data_name, origin, (fit, cross_validation)) =
        on_measurements(setup, data, |m| fit_all(setup, method, folds, m))?;
    let (cross_validation, prediction) = cross_validation.unzip();
    let (prediction, folds) = super::folds::carried(
        prediction,
        cross_validation.as_ref(),
        &origin,
        setup.model(),
    );
    let mut warnings = warnings(&fit);
    warnings.extend(folds);
    warnings.extend(angle_warnings(&data_name, &origin));
    Ok(Report {
        setup: setup_name,
        noise: setup.noise().clone(),
        data_name,
        method,
        fit,
        origin,
        cross_validation,
        prediction,
        warnings,
        model_form: None,
    })
}

/// The fit of every parameter and the cross-validation (and its calibration) if asked.
fn fit_all(
    setup: &Setup,
    method: Method,
    folds: Option<Folds>,
    measurements: &[Measurement],
) -> Result<(Fit, Option<(CrossValidation, Calibration)>)> {
    let obs = Observations::from_measurements(setup.arm(), measurements)?;
    let method = method.method();
    let fit = fit_by(&obs, &setup.model().parameters(), method)?;
    let cv = folds
        .map(|f| {
            let cv = cross_validate_model(&obs, &fit, f.count(obs.postures), method)?;
            let calibration = calibrate(&obs, &cv, noise_floor(setup.noise()));
            Ok::<_, Error>((cv, calibration))
        })
        .transpose()?;
    Ok((fit, cv))
}

/// Parameters the data cannot separate; compliances that are not positive.
fn warnings(fit: &Fit) -> Vec<Warning> {
    let mut out: Vec<Warning> = fit
        .robust
        .as_ref()
        .and_then(|r| r.warning())
        .into_iter()
        .collect();
    let n = fit.compliance.len();
    out.extend((fit.nonnegative_stop).and_then(|s| stiffid_identify::nonnegative::warning(s, n)));
    let combinations = &fit.identifiability.unidentifiable;
    if !combinations.is_empty() {
        let written: Vec<String> = combinations
            .iter()
            .map(|c| c.describe(&fit.parameters))
            .collect();
        out.push(Warning::new(
            WarningKind::Unidentifiable,
            format!(
                "the data cannot separate every parameter ({}: {}): no intervals for those; measure more postures or drop springs",
                count(combinations.len(), "combination"),
                written.join("; ")
            ),
        ));
    }
    let negative: Vec<&str> = fit
        .parameters
        .iter()
        .zip(fit.compliance.iter())
        .filter(|(_, h)| !(h.is_finite() && **h > 0.0))
        .map(|(p, _)| p.name.as_str())
        .collect();
    if !negative.is_empty() {
        out.push(Warning::new(
            WarningKind::Negative,
            format!(
                "{}: compliance not positive, not physical: a non-negative fit bounds the compliances at 0, or compare models with fewer springs",
                negative.join(", ")
            ),
        ));
    }
    out
}
