//! The document of a model comparison (`stiffid identify --compare-models --json`): every
//! parameter named with its unit, mm and the parameters' own units at the edge, `null` for what
//! is not defined.

use super::{Bootstrap, Comparison, Row};
use crate::adequacy::Verdict;
use crate::svd::Fit;
use serde::Serialize;
use stiffid_core::model::Parameter;

/// `stiffid identify --compare-models --json`.
#[derive(Debug, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "identify-comparison")]
#[cfg_attr(feature = "schema", schemars(transform = stiffid_core::common::kind::Kind("identify-comparison")))]
pub struct Document {
    /// The setup as given.
    pub setup: String,
    /// The measurements file.
    pub data: String,
    /// Whether the setup's model already fits the data to the tracker noise (chi-square
    /// p >= 0.01): then no extension is needed.
    pub model_fits: bool,
    /// What the comparison recommends, in words.
    pub conclusion: String,
    /// The selection path: the setup's model, then the model after each step.
    pub models: Vec<ModelDoc>,
    /// Every step: every candidate tried and the one added.
    pub steps: Vec<StepDoc>,
    /// The recommended model fitted to every posture.
    pub recommended_fit: FitDoc,
    /// The nested estimate (outer leave-one-posture-out over the whole selection).
    pub nested: Option<NestedDoc>,
    /// The candidates left out of the pool because the data could never identify them.
    pub dropped: Vec<DroppedDoc>,
    /// The most load levels any posture holds (1 without load steps).
    pub load_levels: usize,
    /// When lost motion or load-dependent candidates were compared: whether these data can
    /// separate them from the springs, in words.
    pub nonlinear_separation: Option<String>,
    /// The posture bootstrap of the whole selection (`--bootstrap`; absent without it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bootstrap: Option<BootstrapDoc>,
}

/// The posture bootstrap ([`super::bootstrap()`]): postures drawn with replacement, the selection
/// and the recommendation redone on each resample; the spread of each stiffness over the models
/// chosen, not a confidence interval conditional on one model.
#[derive(Debug, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct BootstrapDoc {
    /// The number of resamples.
    pub resamples: usize,
    /// The seed of the draws.
    pub seed: u64,
    /// Resamples whose data cannot identify their recommended model, left out of the shares
    /// and spreads.
    pub unidentified: usize,
    /// The share of the other resamples whose recommended model is exactly the data's.
    pub recommended_share: f64,
    /// Every parameter chosen in at least one resample, the setup's model's first.
    pub parameters: Vec<SpreadDoc>,
}

/// One parameter over the bootstrap's resamples.
#[derive(Debug, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct SpreadDoc {
    /// `k1` .. `k6` or the spring's name.
    pub name: String,
    /// `drive`, `rotation`, `translation`, `lost-motion` or `load-dependent`.
    pub kind: stiffid_core::model::ParameterKind,
    /// `Nm/rad`, `N/mm`, `urad` or `urad/kNm^2`.
    pub unit: &'static str,
    /// The share of the usable resamples whose recommended model holds it.
    pub chosen_share: f64,
    /// The median of its stiffness in `unit` over the resamples that chose it (for a lost
    /// motion its size `b`, for a load-dependent compliance its `c1`); `null` if not finite.
    pub median: Option<f64>,
    /// The 2.5% percentile of the same, in `unit` (linear interpolation between order
    /// statistics); `null` if not finite.
    pub percentile_2_5: Option<f64>,
    /// The 97.5% percentile of the same, in `unit`; `null` if not finite.
    pub percentile_97_5: Option<f64>,
}

/// A candidate left out of the pool.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct DroppedDoc {
    /// The candidate's name.
    pub name: String,
    /// Why: its axis is a joint's own, or it gives the same column as another spring.
    pub reason: String,
}

impl From<&super::Dropped> for DroppedDoc {
    fn from(d: &super::Dropped) -> Self {
        Self {
            name: d.name.clone(),
            reason: d.reason.clone(),
        }
    }
}

/// One model.
#[derive(Debug, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct ModelDoc {
    /// The virtual springs of the model, by name.
    pub springs: Vec<String>,
    /// The candidate added at this step (`null` for the setup's model).
    pub added: Option<String>,
    /// The number of parameters.
    pub parameters: usize,
    /// `1 - RMS(|r|) / RMS(|delta|)` of the fit to every posture.
    pub in_sample_explained: f64,
    /// `1 - RMS(delta_b) / RMS(|delta|)` with each posture left out.
    pub held_out_explained: Option<f64>,
    /// Its standard error over the postures (a share, as it is).
    pub held_out_explained_std_error: Option<f64>,
    /// `RMS(delta_b)` held out, mm.
    pub held_out_rms_delta_b_mm: Option<f64>,
    /// The standard error of the held-out mean square `delta_b`, mm^2.
    pub held_out_mse_std_error_mm2: Option<f64>,
    /// Akaike's information criterion.
    pub aic: Option<f64>,
    /// The Bayesian information criterion.
    pub bic: Option<f64>,
    /// Residual standard deviation over the tracker noise.
    pub noise_ratio: Option<f64>,
    /// The model check's verdict against the tracker noise (`null` without degrees of freedom).
    pub model_check: Option<Verdict>,
    /// Every compliance `> 0`.
    pub physical: bool,
    /// The data identify every parameter.
    pub identified: bool,
    /// Whether this is the recommended model.
    pub recommended: bool,
    /// The stiffness of every parameter.
    pub stiffness: Vec<ParameterDoc>,
}

/// One step of the forward selection.
#[derive(Debug, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct StepDoc {
    /// The current model with each remaining candidate added.
    pub candidates: Vec<ModelDoc>,
    /// The candidate added (`null`: the selection stopped).
    pub chosen: Option<String>,
}

/// One parameter's stiffness.
#[derive(Debug, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct ParameterDoc {
    /// `k1` .. `k6` or the spring's name.
    pub name: String,
    /// `drive`, `rotation`, `translation`, `lost-motion` or `load-dependent`.
    pub kind: stiffid_core::model::ParameterKind,
    /// `Nm/rad`, `N/mm`, `urad` or `urad/kNm^2`.
    pub unit: &'static str,
    /// The stiffness in `unit` (`null` if not finite); for a lost motion its size `b` (urad),
    /// for a load-dependent compliance its `c1` (urad/kNm^2).
    pub stiffness: Option<f64>,
    /// Its 95% interval in `unit` (the compliance's interval inverted, or the parameter's own
    /// for a lost motion and a load-dependent compliance; `null` ends unbounded); `null` when the
    /// data cannot identify the parameter.
    pub ci95: Option<[Option<f64>; 2]>,
    /// Whether the data identify it.
    pub identified: bool,
}

/// A fit of a model.
#[derive(Debug, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct FitDoc {
    /// Every parameter, drives first.
    pub parameters: Vec<ParameterDoc>,
    /// The rank of the column-scaled observation matrix.
    pub rank: usize,
    /// Its condition number (`null` when rank deficient).
    pub scaled_cond: Option<f64>,
    /// The combinations of parameters the data cannot separate, written out.
    pub unidentifiable: Vec<String>,
    /// Residual standard deviation over the tracker noise.
    pub noise_ratio: Option<f64>,
    /// The model check's verdict against the tracker noise (`null` without degrees of freedom).
    pub model_check: Option<Verdict>,
    /// `Cov(h)` of the compliance of every parameter, SI (rad/Nm, m/N), row-major n x n (for a
    /// bounded fit, that of the free parameters, zero for those at the bound); `null` without
    /// degrees of freedom. With `parameters`, what a stiffness file holds.
    pub compliance_covariance_si: Option<Vec<Vec<f64>>>,
    /// Rows minus rank.
    pub degrees_of_freedom: usize,
    /// RMS of the residuals, mm.
    pub residual_rms_mm: f64,
}

/// The nested estimate.
#[derive(Debug, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct NestedDoc {
    /// `1 - RMS(delta_b) / RMS(|delta|)`, each posture predicted by the model chosen without it.
    pub held_out_explained: f64,
    /// Its standard error over the postures (a share, as it is).
    pub held_out_explained_std_error: f64,
    /// That `RMS(delta_b)`, mm.
    pub rms_delta_b_mm: f64,
    /// The parameters chosen in each outer fold.
    pub parameters: Vec<usize>,
    /// How many outer folds chose each candidate.
    pub chosen: Vec<ChosenDoc>,
}

/// A candidate and how often the outer folds chose it.
#[derive(Debug, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct ChosenDoc {
    /// The candidate.
    pub name: String,
    /// Outer folds that chose it.
    pub folds: usize,
}

fn finite(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

/// The parameters of a fit with their stiffness and intervals in their units.
pub fn parameter_docs(fit: &Fit) -> Vec<ParameterDoc> {
    fit.parameters
        .iter()
        .enumerate()
        .map(|(j, p)| {
            let unit = p.unit.per_si();
            ParameterDoc {
                name: p.name.clone(),
                kind: p.kind,
                unit: p.unit.symbol(),
                stiffness: finite(p.unit.reported(fit.compliance[j])),
                ci95: fit.intervals[j].map(|i| match p.unit.is_stiffness() {
                    true => i.stiffness_ci95.map(|v| finite(v * unit)),
                    false => i.compliance_ci95.map(|v| finite(v * unit)),
                }),
                identified: fit.identifiability.identified[j],
            }
        })
        .collect()
}

/// The document of a fit, `noise_variance` the setup's (m^2).
pub fn fit_doc(fit: &Fit, noise_variance: f64) -> FitDoc {
    FitDoc {
        parameters: parameter_docs(fit),
        rank: fit.identifiability.rank,
        scaled_cond: finite(fit.identifiability.scaled_cond),
        unidentifiable: fit
            .identifiability
            .unidentifiable
            .iter()
            .map(|c| c.describe(&fit.parameters))
            .collect(),
        noise_ratio: fit.noise_ratio(noise_variance),
        model_check: fit.verdict(noise_variance),
        compliance_covariance_si: fit
            .covariance
            .as_ref()
            .map(|c| c.row_iter().map(|r| r.iter().copied().collect()).collect()),
        degrees_of_freedom: fit.dof,
        residual_rms_mm: fit.residual_rms() * 1e3,
    }
}

fn model_doc(row: &Row, all: &[Parameter], recommended: bool) -> ModelDoc {
    let stiffness = row
        .stiffness
        .iter()
        .zip(row.parameter_indices.iter().map(|&j| &all[j]))
        .map(|(k, p)| ParameterDoc {
            name: p.name.clone(),
            kind: p.kind,
            unit: p.unit.symbol(),
            stiffness: finite(p.unit.reported(1.0 / k)),
            ci95: None,
            identified: row.identified,
        })
        .collect();
    ModelDoc {
        springs: row.springs.clone(),
        added: row.added.clone(),
        parameters: row.parameters,
        in_sample_explained: row.in_sample_explained,
        held_out_explained: row.held_out_explained,
        held_out_explained_std_error: row.held_out_explained_std_error,
        held_out_rms_delta_b_mm: row.held_out_rms_delta_b.map(|v| v * 1e3),
        held_out_mse_std_error_mm2: row.held_out_mse.map(|m| m.1 * 1e6),
        aic: finite(row.aic),
        bic: finite(row.bic),
        noise_ratio: row.noise_ratio,
        model_check: row.model_check,
        physical: row.physical,
        identified: row.identified,
        recommended,
        stiffness,
    }
}

impl Comparison {
    /// When lost motion or load-dependent candidates were compared, whether the data's loads can
    /// separate them from the springs ([`stiffid_core::model::Law`]).
    pub fn nonlinear_separation(&self) -> Option<String> {
        use stiffid_core::model::ParameterKind::{LoadDependent, LostMotion};
        let any = self
            .parameters
            .iter()
            .any(|p| matches!(p.kind, LostMotion | LoadDependent));
        if !any {
            return None;
        }
        Some(super::pool::nonlinear_separation(self.load_levels))
    }

    /// What the comparison recommends, in words.
    pub fn conclusion(&self) -> String {
        let rec = &self.models[self.recommended];
        let best = self
            .models
            .iter()
            .filter_map(|r| r.held_out_explained)
            .fold(f64::NEG_INFINITY, f64::max);
        let share = |v: Option<f64>| v.map_or("n/a".into(), |v| format!("{:.1}%", 100.0 * v));
        if self.model_fits && self.recommended == 0 {
            return "the setup's model fits the data to the tracker noise: no extension is needed"
                .into();
        }
        if self.recommended == 0 {
            return format!(
                "keep the setup's model: no candidate lowers the held-out error by more than its standard error (held out {})",
                share(rec.held_out_explained)
            );
        }
        format!(
            "recommended: {} parameters (+ {}), held out {} of the deflection explained against {} for the setup's model; the smallest model within one standard error of the best held-out error ({})",
            rec.parameters,
            rec.springs.join(", "),
            share(rec.held_out_explained),
            share(self.models[0].held_out_explained),
            share(Some(best)),
        )
    }

    /// The document, `setup` and `data` as given, `noise_variance` the setup's (m^2), `dropped`
    /// the candidates left out of the pool ([`super::Pool::dropped`]), `bootstrap` the posture
    /// bootstrap if it was run.
    pub fn document(
        &self,
        setup: &str,
        data: &str,
        noise_variance: f64,
        dropped: &[super::Dropped],
        bootstrap: Option<&Bootstrap>,
    ) -> Document {
        let all = &self.parameters;
        Document {
            setup: setup.into(),
            data: data.into(),
            model_fits: self.model_fits,
            conclusion: self.conclusion(),
            models: self
                .models
                .iter()
                .enumerate()
                .map(|(i, r)| model_doc(r, all, i == self.recommended))
                .collect(),
            steps: self
                .steps
                .iter()
                .map(|s| StepDoc {
                    candidates: s
                        .candidates
                        .iter()
                        .map(|r| model_doc(r, all, false))
                        .collect(),
                    chosen: s.chosen.and_then(|i| s.candidates[i].added.clone()),
                })
                .collect(),
            recommended_fit: fit_doc(&self.recommended_fit, noise_variance),
            nested: self.nested.as_ref().map(|n| NestedDoc {
                held_out_explained: n.held_out_explained,
                held_out_explained_std_error: n.held_out_explained_std_error,
                rms_delta_b_mm: n.rms_delta_b * 1e3,
                parameters: n.parameters.clone(),
                chosen: n
                    .chosen
                    .iter()
                    .map(|(name, folds)| ChosenDoc {
                        name: name.clone(),
                        folds: *folds,
                    })
                    .collect(),
            }),
            load_levels: self.load_levels,
            nonlinear_separation: self.nonlinear_separation(),
            bootstrap: bootstrap.map(|b| self.bootstrap_doc(b)),
            dropped: dropped.iter().map(DroppedDoc::from).collect(),
        }
    }

    /// The document of the posture bootstrap `b` of this comparison, in the parameters' units.
    pub(crate) fn bootstrap_doc(&self, b: &Bootstrap) -> BootstrapDoc {
        let share = |n: usize| n as f64 / b.usable().max(1) as f64;
        BootstrapDoc {
            resamples: b.resampling.resamples,
            seed: b.resampling.seed,
            unidentified: b.unidentified,
            recommended_share: share(b.recommended),
            parameters: b
                .parameters
                .iter()
                .map(|s| {
                    let p = &self.parameters[s.parameter];
                    let unit = |v: f64| finite(v * p.unit.per_si());
                    SpreadDoc {
                        name: p.name.clone(),
                        kind: p.kind,
                        unit: p.unit.symbol(),
                        chosen_share: share(s.chosen),
                        median: unit(s.median),
                        percentile_2_5: unit(s.lower),
                        percentile_97_5: unit(s.upper),
                    }
                })
                .collect(),
        }
    }
}
