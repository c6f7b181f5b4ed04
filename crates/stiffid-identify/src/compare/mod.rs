//! Model choice by the data: forward selection of virtual springs on the leave-one-posture-out
//! error, nested in an outer cross-validation for an honest estimate of the chosen model's error.
//!
//! From the setup's model, each step fits the model with every remaining candidate spring added
//! ([`super::svd::fit`]) and its leave-one-posture-out error ([`super::svd::held_out`]), and
//! adds the candidate with the smallest held-out mean square `delta_b` among those whose fit is
//! physical (every compliance `> 0`; a load-dependent compliance `c0 + c1 |tau| > 0` at the
//! largest load of the data, [`stiffid_core::model::Law`]) and identified. It stops when no candidate lowers the
//! held-out error. The recommended model is the smallest on that path whose held-out mean square
//! is within one standard error of the best one (the one-standard-error rule; Hastie, Tibshirani,
//! Friedman, "The Elements of Statistical Learning", 2nd ed., 2009, Section 7.10): a spring must
//! pay for itself beyond the noise of the estimate.
//!
//! The held-out error of the chosen model is optimistic (the choice saw every posture). The
//! nested estimate repeats the whole selection without each posture in turn and predicts that
//! posture with the model it chose (outer leave-one-posture-out): the error to expect from
//! choosing by the data.

pub mod bootstrap;
pub mod document;
pub(crate) mod pool;

pub use bootstrap::{bootstrap, Bootstrap, Resampling};
pub use document::{parameter_docs, Document};
pub use pool::{default_pool, nonlinear_separation, pool_by_name, Dropped, Pool};

use super::explained_share;
use super::svd::{fit, held_out, Fit, HeldOut};
use crate::adequacy::Verdict;
use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;
use stiffid_core::model::{Law, Model, Spring};
use stiffid_core::observation::{Measurement, Observations};
use stiffid_core::{Result, Setup};

/// The default candidates ([`pool::default_pool`]): every family's springs on the setup's robot
/// and the setup's declared candidates, minus those dropped and those in the setup's model.
pub fn default_candidates(setup: &Setup) -> Vec<Spring> {
    pool::default_pool(setup).candidates
}

/// One model of the comparison.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// The candidate added to the previous model (`None` for the setup's model).
    pub added: Option<String>,
    /// The virtual springs of the model (the setup's, then those added), by name.
    pub springs: Vec<String>,
    /// The number of parameters.
    pub parameters: usize,
    /// The parameters' indices among the setup's model's and the candidates' ([`Comparison::parameters`]).
    pub parameter_indices: Vec<usize>,
    /// `1 - RMS(|r|) / RMS(|delta|)` of the fit to every posture.
    pub in_sample_explained: f64,
    /// `1 - RMS(delta_b) / RMS(|delta|)` with each posture left out; `None` when some posture is
    /// needed to identify the model.
    pub held_out_explained: Option<f64>,
    /// The standard error of `held_out_explained` over the postures.
    pub held_out_explained_std_error: Option<f64>,
    /// `RMS(delta_b)` held out, m.
    pub held_out_rms_delta_b: Option<f64>,
    /// The held-out mean square `delta_b` over postures and its standard error, m^2.
    pub held_out_mse: Option<(f64, f64)>,
    /// AIC and BIC of the Gaussian fit.
    pub aic: f64,
    /// The Bayesian information criterion.
    pub bic: f64,
    /// `s / sigma` against the setup's tracker noise.
    pub noise_ratio: Option<f64>,
    /// The model check's verdict against the setup's tracker noise; `None` without degrees of
    /// freedom.
    pub model_check: Option<Verdict>,
    /// Every compliance `> 0`.
    pub physical: bool,
    /// The data identify every parameter.
    pub identified: bool,
    /// The stiffness of every parameter, SI (Nm/rad, N/m), drives first.
    pub stiffness: Vec<f64>,
}

/// One step of the forward selection: every candidate tried, and the one added.
#[derive(Debug, Clone, PartialEq)]
pub struct Step {
    /// The current model plus each remaining candidate.
    pub candidates: Vec<Row>,
    /// The index in `candidates` of the one added (`None`: the selection stopped here).
    pub chosen: Option<usize>,
}

/// The nested (outer leave-one-posture-out) estimate of choosing by the data.
#[derive(Debug, Clone, PartialEq)]
pub struct Nested {
    /// `1 - RMS(delta_b) / RMS(|delta|)` over every posture predicted by the model chosen without it.
    pub held_out_explained: f64,
    /// Its standard error over the postures (the delta method on the ratio of the postures'
    /// sums, `explained_share`).
    pub held_out_explained_std_error: f64,
    /// That `RMS(delta_b)`, m.
    pub rms_delta_b: f64,
    /// The number of parameters chosen in each outer fold.
    pub parameters: Vec<usize>,
    /// How many outer folds chose each candidate, by name, in candidate order.
    pub chosen: Vec<(String, usize)>,
}

/// The result of [`compare`].
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    /// The selection path: the setup's model, then the model after each step.
    pub models: Vec<Row>,
    /// Every step with every candidate.
    pub steps: Vec<Step>,
    /// The index in `models` of the recommended model.
    pub recommended: usize,
    /// The recommended model's virtual springs (the setup's and those added).
    pub recommended_springs: Vec<Spring>,
    /// The recommended model's fit to every posture.
    pub recommended_fit: Fit,
    /// The nested estimate (with at least three postures).
    pub nested: Option<Nested>,
    /// The setup's model passes the model check against the tracker noise (p >= 0.01): no
    /// extension is needed.
    pub model_fits: bool,
    /// The setup's model's fit to every posture.
    pub setup_fit: Fit,
    /// The parameters of the setup's model followed by the candidates.
    pub parameters: Vec<stiffid_core::model::Parameter>,
    /// The most load levels (distinct wrenches) any posture of the data holds: 1 without load
    /// steps.
    pub load_levels: usize,
}

/// Column sets over the observations of the setup's model plus every candidate.
struct Problem<'a> {
    obs: &'a Observations,
    base: usize,
    candidates: usize,
    noise_variance: f64,
    model: &'a Model,
    /// The largest `|J_s(p_f)^T W|` over the data of each virtual spring (Nm or N).
    max_load: Vec<f64>,
}

/// The largest `|J_s(p_f)^T W|` of each virtual spring of `setup`'s model over `measurements`.
fn max_loads(setup: &Setup, measurements: &[Measurement]) -> Vec<f64> {
    let springs = setup.model().springs();
    let mut out = vec![0.0_f64; springs.len()];
    for m in measurements {
        let frames = setup.robot().frames_at(&m.q, m.e.as_slice());
        let loading = frames.point(&setup.tool().loading_point);
        for (s, max) in springs.iter().zip(out.iter_mut()) {
            let load = s.placed(&frames).load(&loading, &m.wrench);
            *max = max.max(load.abs());
        }
    }
    out
}

/// The most distinct wrenches among the measurements of one posture.
fn load_levels(measurements: &[Measurement]) -> usize {
    let mut seen: Vec<(usize, [u64; 6])> = measurements
        .iter()
        .map(|m| (m.posture, m.wrench.map(f64::to_bits).into()))
        .collect();
    seen.sort_unstable();
    seen.dedup();
    let mut most = 0;
    for chunk in seen.chunk_by(|a, b| a.0 == b.0) {
        most = most.max(chunk.len());
    }
    most
}

/// Fewest postures a comparison takes: every model is judged by its error on postures left out
/// one at a time, and the nested estimate leaves one out of the selection too, so the selection
/// in each outer fold still has a posture to hold out.
pub(crate) const MIN_POSTURES: usize = 3;

/// Compares models by forward selection of `candidates` (module docs) on `measurements`,
/// starting from `setup`'s model; `nested` runs the outer cross-validation.
///
/// # Errors
/// Those of [`Observations::from_measurements`] and of [`super::svd::fit`] for the setup's
/// model; [`stiffid_core::Error::InvalidField`] for candidates that clash with the model's springs, and
/// (`postures`) for fewer than `MIN_POSTURES` postures, postures whose every subset without
/// one cannot identify the setup's model (no held-out error to compare models by), or postures
/// no model on the path fits physically and identified (a recommendation would be a negative
/// stiffness).
pub fn compare(
    setup: &Setup,
    measurements: &[Measurement],
    candidates: &[Spring],
    nested: bool,
) -> Result<Comparison> {
    let model = setup.model().with(candidates)?;
    let all = setup
        .to_builder()
        .with_virtual_springs(model.springs().to_vec())
        .with_candidate_springs(Vec::new())
        .build()?;
    let obs = Observations::from_measurements(all.arm(), measurements)?;
    let too_few = |why: &str| {
        stiffid_core::Error::InvalidField {
        field: "postures".into(),
        message: format!(
            "{} given: comparing models needs at least {MIN_POSTURES} postures{why} (each model is judged by its error on postures left out one at a time): measure more postures",
            obs.postures
        ),
    }
    };
    if obs.postures < MIN_POSTURES {
        return Err(too_few(""));
    }
    let p = Problem {
        obs: &obs,
        base: setup.model().len(),
        candidates: candidates.len(),
        noise_variance: setup.noise().displacement_variance(),
        model: &model,
        max_load: max_loads(&all, measurements),
    };
    let base_fit = fit(
        &p.sub(&(0..p.base).collect::<Vec<_>>()),
        &p.parameters(&(0..p.base).collect::<Vec<_>>()),
    )?;
    let model_fits = base_fit
        .adequacy_p_value(p.noise_variance)
        .is_some_and(|pv| pv >= crate::adequacy::SIGNIFICANCE);
    let (models, steps, path) = p.select(&obs);
    if models.first().is_none_or(|m| m.held_out_mse.is_none()) {
        return Err(too_few(
            ", and the others must identify the setup's model without any one of them",
        ));
    }
    let recommended = recommend(&models);
    if !(models[recommended].physical && models[recommended].identified) {
        return Err(too_few(
            ", and no model on the path fits them with every stiffness positive and every parameter identified (the setup's model neither)",
        ));
    }
    let columns = &path[recommended];
    let recommended_fit = fit(&p.sub(columns), &p.parameters(columns))?;
    let recommended_springs = columns[6..]
        .iter()
        .map(|&c| model.springs()[c - 6].clone())
        .collect();
    let nested = (nested && obs.postures >= 3).then(|| p.nested(candidates));
    Ok(Comparison {
        models,
        steps,
        recommended,
        recommended_springs,
        recommended_fit,
        nested,
        model_fits,
        setup_fit: base_fit,
        parameters: model.parameters(),
        load_levels: load_levels(measurements),
    })
}

/// The smallest model on the path within one standard error of the best held-out mean square
/// (physical and identified), else the setup's model.
fn recommend(models: &[Row]) -> usize {
    supported(models).first().copied().unwrap_or(0)
}

/// The models the data support: the indices of the models on the path (physical and
/// identified) whose held-out mean square is within one standard error of the best one's, the
/// margin of the one-standard-error rule (module docs), smallest first.
pub(crate) fn supported(models: &[Row]) -> Vec<usize> {
    let ok = |r: &Row| r.physical && r.identified;
    let best = models
        .iter()
        .filter(|r| ok(r))
        .filter_map(|r| r.held_out_mse)
        .min_by(|a, b| a.0.total_cmp(&b.0));
    let Some((mse, se)) = best else {
        return Vec::new();
    };
    (0..models.len())
        .filter(|&i| ok(&models[i]) && models[i].held_out_mse.is_some_and(|m| m.0 <= mse + se))
        .collect()
}

impl Problem<'_> {
    /// Every compliance finite and positive, but a load-dependent compliance's `c1`, which may
    /// be negative while `c0 + c1 |tau| > 0` at the largest load of the data, `c0` its joint's
    /// drive.
    fn physical(&self, f: &Fit, columns: &[usize]) -> bool {
        columns.iter().enumerate().all(|(i, &c)| {
            let h = f.compliance[i];
            let spring = c.checked_sub(6).map(|s| &self.model.springs()[s]);
            match spring {
                Some(s) if s.law == Law::LoadDependent => {
                    let c0 = f.compliance[s.link - 1];
                    h.is_finite() && c0 + h * self.max_load[c - 6] > 0.0
                }
                _ => h.is_finite() && h > 0.0,
            }
        })
    }

    fn parameters(&self, columns: &[usize]) -> Vec<stiffid_core::model::Parameter> {
        let all = self.model.parameters();
        columns.iter().map(|&c| all[c].clone()).collect()
    }

    fn sub(&self, columns: &[usize]) -> Observations {
        Observations {
            psi: self.obs.psi.select_columns(columns),
            ..self.obs.clone()
        }
    }

    /// The row of the model with `columns` on `obs` (rows of some postures).
    fn row(&self, obs: &Observations, columns: &[usize], added: Option<usize>) -> Option<Row> {
        let sub = Observations {
            psi: obs.psi.select_columns(columns),
            ..obs.clone()
        };
        let f = fit(&sub, &self.parameters(columns)).ok()?;
        let held = held_out(&sub);
        let names = self.model.parameters();
        Some(Row {
            added: added.map(|c| names[c].name.clone()),
            springs: columns[6..]
                .iter()
                .map(|&c| names[c].name.clone())
                .collect(),
            parameters: columns.len(),
            parameter_indices: columns.to_vec(),
            in_sample_explained: explained(&f.residuals, &sub.delta),
            held_out_explained: held.as_ref().map(HeldOut::explained),
            held_out_explained_std_error: held.as_ref().map(HeldOut::explained_std_error),
            held_out_rms_delta_b: held.as_ref().map(|h| h.rms_delta_b),
            held_out_mse: held.as_ref().map(HeldOut::mse_and_se),
            aic: f.aic(),
            bic: f.bic(),
            noise_ratio: f.noise_ratio(self.noise_variance),
            model_check: f.verdict(self.noise_variance),
            physical: self.physical(&f, columns),
            identified: f.identifiability.unidentifiable.is_empty(),
            stiffness: f.stiffness.iter().copied().collect(),
        })
    }

    /// Forward selection on `obs`: the path's rows, the steps, and the path's column sets.
    fn select(&self, obs: &Observations) -> (Vec<Row>, Vec<Step>, Vec<Vec<usize>>) {
        let mut columns: Vec<usize> = (0..self.base).collect();
        let mut remaining: Vec<usize> = (self.base..self.base + self.candidates).collect();
        let Some(first) = self.row(obs, &columns, None) else {
            return (Vec::new(), Vec::new(), vec![columns]);
        };
        let mut models = vec![first];
        let mut path = vec![columns.clone()];
        let mut steps = Vec::new();
        while !remaining.is_empty() {
            let rows: Vec<Option<Row>> = remaining
                .iter()
                .map(|&c| {
                    let mut with = columns.clone();
                    with.push(c);
                    self.row(obs, &with, Some(c))
                })
                .collect();
            let current = models
                .last()
                .and_then(|r| r.held_out_mse)
                .map_or(f64::INFINITY, |m| m.0);
            let best = rows
                .iter()
                .enumerate()
                .filter_map(|(i, r)| Some((i, r.as_ref()?)))
                .filter(|(_, r)| r.physical && r.identified)
                .filter_map(|(i, r)| Some((i, r.held_out_mse?.0)))
                .filter(|(_, m)| *m < current)
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .map(|(i, _)| i);
            let candidates: Vec<Row> = rows.iter().flatten().cloned().collect();
            let chosen_row = best.map(|i| rows[i].clone().expect("a chosen row exists"));
            let chosen = chosen_row
                .as_ref()
                .and_then(|c| candidates.iter().position(|r| r == c));
            steps.push(Step { candidates, chosen });
            let (Some(i), Some(row)) = (best, chosen_row) else {
                break;
            };
            columns.push(remaining.remove(i));
            models.push(row);
            path.push(columns.clone());
        }
        (models, steps, path)
    }

    /// The outer leave-one-posture-out estimate (module docs), folds in parallel, the same result
    /// whatever the threads.
    fn nested(&self, candidates: &[Spring]) -> Nested {
        let obs = self.obs;
        let folds: Vec<(Vec<usize>, Vec<f64>, [f64; 2])> = (0..obs.postures)
            .into_par_iter()
            .map(|p| {
                let (train, test) = split(obs, p);
                let (models, _, path) = self.select(&train);
                let columns = &path[recommend(&models).min(path.len() - 1)];
                let sub = Observations {
                    psi: train.psi.select_columns(columns),
                    ..train.clone()
                };
                let delta_b = match fit(&sub, &self.parameters(columns)) {
                    Ok(f) => {
                        let r = &test.delta - test.psi.select_columns(columns) * &f.compliance;
                        (0..r.len() / 3).map(|k| r.rows(3 * k, 3).norm()).collect()
                    }
                    Err(_) => vec![f64::NAN; test.delta.len() / 3],
                };
                let sums = [
                    delta_b.iter().map(|d| d * d).sum(),
                    test.delta.norm_squared(),
                ];
                (columns.clone(), delta_b, sums)
            })
            .collect();
        let all: Vec<f64> = folds.iter().flat_map(|f| f.1.iter().copied()).collect();
        let rms = (all.iter().map(|d| d * d).sum::<f64>() / all.len() as f64).sqrt();
        let [explained, std_error] =
            explained_share(&folds.iter().map(|f| f.2).collect::<Vec<_>>());
        let names = self.model.parameters();
        Nested {
            held_out_explained: explained,
            held_out_explained_std_error: std_error,
            rms_delta_b: rms,
            parameters: folds.iter().map(|f| f.0.len()).collect(),
            chosen: (0..candidates.len())
                .map(|c| {
                    let col = self.base + c;
                    let n = folds.iter().filter(|f| f.0.contains(&col)).count();
                    (names[col].name.clone(), n)
                })
                .collect(),
        }
    }
}

/// `1 - RMS(|r_i|) / RMS(|delta_i|)` over the measurements (three rows each).
fn explained(residuals: &DVector<f64>, delta: &DVector<f64>) -> f64 {
    1.0 - (residuals.norm_squared() / delta.norm_squared()).sqrt()
}

/// The observations without posture `p` (postures renumbered) and those of `p` alone.
fn split(obs: &Observations, p: usize) -> (Observations, Observations) {
    let part = |keep: &dyn Fn(usize) -> bool| {
        let ids: Vec<usize> = (0..obs.posture_index.len())
            .filter(|&i| keep(obs.posture_index[i]))
            .collect();
        let rows: Vec<usize> = ids.iter().flat_map(|&i| 3 * i..3 * i + 3).collect();
        let psi: DMatrix<f64> = obs.psi.select_rows(&rows);
        let delta = DVector::from_iterator(rows.len(), rows.iter().map(|&r| obs.delta[r]));
        let mut index: Vec<usize> = ids.iter().map(|&i| obs.posture_index[i]).collect();
        let mut distinct = index.clone();
        distinct.sort_unstable();
        distinct.dedup();
        for x in &mut index {
            *x = distinct.binary_search(x).expect("present");
        }
        Observations {
            psi,
            delta,
            postures: distinct.len(),
            posture_index: index,
        }
    };
    (part(&|q| q != p), part(&|q| q == p))
}
