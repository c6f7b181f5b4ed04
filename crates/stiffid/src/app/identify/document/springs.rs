//! The document of the identify job over a model with virtual springs
//! ([`crate::app::identify`]): `stiffid identify --json` and the stiffness file of `--out`
//! for such a setup. Every parameter is named with its kind and unit (Nm/rad for the drives and
//! rotational springs, N/mm for translational ones) and every stiffness is in that unit.

use super::drives::{labels, prediction, region, Residual, Robust};
use crate::app::document::{finite, units};
use crate::app::identify::springs::Report;
use nalgebra::DVector;
use serde::Serialize;
use stiffid_core::common::warning::Warning;
use stiffid_core::io::stiffness::{ModelFormSection, PredictionSection, RegionSection};
use stiffid_core::model::Parameter;
use stiffid_identify::compare::document::{fit_doc, FitDoc};
use stiffid_identify::cross_validation::CrossValidation;

/// The identify document over a model. With `parameters` and `compliance_covariance_si`, what a
/// stiffness file holds ([`stiffid_core::io::stiffness`]).
///
/// A view of the report ([`Report::document`]), built as it is written: its names are the
/// report's, its lengths the report's in SI, written in the units their keys name by the unit
/// adapters ([`units`]).
#[derive(Debug, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "identify-springs")]
#[cfg_attr(
    feature = "schema",
    schemars(
        description = "The identify document over a model. With `parameters` and `compliance_covariance_si`, what a\nstiffness file holds ([`stiffid_core::io::stiffness`])."
    )
)]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("identify-springs")))]
pub struct Document<'a> {
    /// The setup as given.
    pub setup: &'a str,
    /// The measurements (a file's name, or `arrays`).
    pub data: &'a str,
    /// The fit: `least-squares`, `nonnegative-least-squares`, `huber` or `tukey`.
    pub method: &'static str,
    /// Rows of the stacked system (3 per measurement).
    pub rows: usize,
    /// Distinct postures in the data.
    pub postures: usize,
    /// Every parameter with its stiffness and interval, what the data cannot separate.
    #[serde(flatten)]
    pub fit: FitDoc,
    /// `P(X >= rss / sigma^2)` for `X ~ chi2(dof)`: small when the residuals exceed the tracker
    /// noise; `null` without degrees of freedom.
    pub chi2_p_value: Option<f64>,
    /// With a non-negative fit: why its active-set steps stopped, `converged` (the bounded
    /// minimum, also when the least-squares fit is already non-negative) or `iteration-limit`
    /// (a warning says so); left out for another fit.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub nonnegative_stop_reason: Option<stiffid_core::common::stop::Stop>,
    /// The setup's tracker noise on a displacement coordinate, the model check's: m, written in
    /// mm.
    #[serde(rename = "noise_std_mm", serialize_with = "units::mm")]
    pub noise_std: f64,
    /// Every measurement's residual, measured and predicted displacement.
    pub residuals: Vec<Residual<'a>>,
    /// With a robust fit: the reweighting.
    pub robust: Option<Robust<'a>>,
    /// With cross-validation: the cross-validation over postures.
    pub cross_validation: Option<CrossValidationDoc<'a>>,
    /// With cross-validation: the held-out residuals that prediction intervals are built from
    /// (the stiffness file's `prediction`, [`stiffid_core::io::stiffness::PredictionSection`]).
    pub prediction: Option<PredictionSection>,
    /// The region of axis angles the data's postures span, widened by a margin (the stiffness
    /// file's `region`, [`stiffid_core::io::stiffness::RegionSection`]).
    pub region: Option<RegionSection>,
    /// With `--compare-models --bootstrap N --stiffness-out`: the models the data support and
    /// their resampled parameter sets (the stiffness file's `model_form`,
    /// [`stiffid_core::io::stiffness::ModelFormSection`]); left out otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub model_form: Option<&'a ModelFormSection>,
    /// Results to look at before trusting them.
    pub warnings: &'a [Warning],
}

/// The cross-validation over postures of every parameter.
#[derive(Debug, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct CrossValidationDoc<'a> {
    /// Number of folds.
    pub folds: usize,
    /// Per parameter, in the order of `parameters`: the spread of its stiffness over the folds.
    pub spread: Vec<Spread<'a>>,
    /// RMS prediction error of the held-out measurements (Eq. 22): m, written in mm.
    #[serde(rename = "rms_delta_b_mm", serialize_with = "units::mm")]
    pub rms_delta_b: f64,
    /// RMS of the measured displacements: m, written in mm.
    #[serde(rename = "rms_measured_mm", serialize_with = "units::mm")]
    pub rms_measured: f64,
    /// `1 - rms_delta_b_mm / rms_measured_mm`: the held-out explained share.
    pub explained: f64,
    /// The standard error of `explained` over the postures (delta method of the ratio, the
    /// postures as independent units).
    pub explained_std_error: f64,
    /// `explained`, %.
    pub explained_pct: f64,
    /// `explained_std_error`, %.
    pub explained_std_error_pct: f64,
    /// Every fold.
    pub per_fold: Vec<FoldDoc<'a>>,
}

/// One parameter's stiffness over the folds, in its unit (`null` if not finite).
#[derive(Debug, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Spread<'a> {
    /// `k1` .. `k6` or the spring's name.
    pub name: &'a str,
    /// `Nm/rad` or `N/mm`.
    pub unit: &'static str,
    /// Mean over the folds.
    pub mean: Option<f64>,
    /// Sample standard deviation over the folds.
    pub std: Option<f64>,
    /// Smallest over the folds.
    pub min: Option<f64>,
    /// Largest over the folds.
    pub max: Option<f64>,
}

/// One fold.
#[derive(Debug, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct FoldDoc<'a> {
    /// The postures left out (labels).
    pub postures: Vec<&'a str>,
    /// The stiffness of every parameter fitted without them, each in its unit.
    pub stiffness: Vec<Option<f64>>,
    /// The parameters whose stiffness the removal moves by more than its standard error in the
    /// full fit.
    pub influential: Vec<&'a str>,
    /// RMS prediction error of the held-out measurements: m, written in mm.
    #[serde(rename = "rms_delta_b_mm", serialize_with = "units::mm")]
    pub rms_delta_b: f64,
    /// Prediction error of each held-out measurement (Eq. 22): m, written in mm.
    #[serde(rename = "delta_b_mm", serialize_with = "units::mm_each")]
    #[cfg_attr(feature = "schema", schemars(with = "Vec<f64>"))]
    pub delta_b: &'a [f64],
}

impl<'a> Document<'a> {
    /// The view of `report` ([`Report::document`]).
    pub(crate) fn new(report: &'a Report) -> Self {
        let f = &report.fit;
        let variance = report.noise.displacement_variance();
        Document {
            setup: &report.setup,
            data: &report.data_name,
            method: report.method.name(),
            rows: f.rows,
            postures: f.postures,
            fit: fit_doc(f, variance),
            chi2_p_value: f.adequacy_p_value(variance),
            nonnegative_stop_reason: f.nonnegative_stop,
            noise_std: variance.sqrt(),
            residuals: Residual::all(&report.origin, &f.residuals, &f.predicted),
            robust: f
                .robust
                .as_ref()
                .map(|r| Robust::new(r, &report.origin, &f.residuals)),
            cross_validation: report
                .cross_validation
                .as_ref()
                .map(|cv| cross_validation(report, cv)),
            prediction: prediction(
                report.prediction.as_ref(),
                report.cross_validation.as_ref(),
                &report.origin,
            ),
            region: region(&report.origin),
            model_form: report.model_form.as_ref(),
            warnings: &report.warnings,
        }
    }
}

/// Stiffness (SI) in each parameter's unit, `null` unless finite.
fn in_units(parameters: &[Parameter], k: &DVector<f64>) -> Vec<Option<f64>> {
    parameters
        .iter()
        .zip(k.iter())
        .map(|(p, k)| finite(k * p.unit.per_si()))
        .collect()
}

fn cross_validation<'a>(report: &'a Report, cv: &'a CrossValidation) -> CrossValidationDoc<'a> {
    let parameters = &report.fit.parameters;
    let [mean, std, min, max] = [
        &cv.stiffness_mean,
        &cv.stiffness_std,
        &cv.stiffness_range[0],
        &cv.stiffness_range[1],
    ]
    .map(|v| in_units(parameters, v));
    CrossValidationDoc {
        folds: cv.folds.len(),
        spread: parameters
            .iter()
            .enumerate()
            .map(|(j, p)| Spread {
                name: &p.name,
                unit: p.unit.symbol(),
                mean: mean[j],
                std: std[j],
                min: min[j],
                max: max[j],
            })
            .collect(),
        rms_delta_b: cv.rms_delta_b,
        rms_measured: cv.rms_measured,
        explained: cv.explained(),
        explained_std_error: cv.explained_std_error,
        explained_pct: 100.0 * cv.explained(),
        explained_std_error_pct: 100.0 * cv.explained_std_error,
        per_fold: cv
            .folds
            .iter()
            .map(|fold| FoldDoc {
                postures: labels(&report.origin, &fold.postures),
                stiffness: in_units(parameters, &fold.stiffness),
                influential: parameters
                    .iter()
                    .zip(&fold.influential)
                    .filter(|(_, i)| **i)
                    .map(|(p, _)| p.name.as_str())
                    .collect(),
                rms_delta_b: fold.rms_delta_b,
                delta_b: &fold.delta_b,
            })
            .collect(),
    }
}
