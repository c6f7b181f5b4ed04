//! Which orders of a carrier's error motions a calibration fits: chosen by cross-validation over
//! the postures inside the fitted readings, as the joint error maps are ([`super::maps`]).
//!
//! A linear axis's six error motions are polynomials of orders `1..K` in its normalised position
//! ([`stiffid_core::robot::external::ErrorMotions`]). The candidates are `K = 0..K_max`, `K_max`
//! the smaller of 6 and the axis's distinct positions in the readings less two (a polynomial of
//! order `K` through fewer positions would only follow the noise). The postures are dealt into 5
//! folds (posture `p` of the readings in fold `p mod K`); a candidate's held-out error is the sum
//! over folds of the errors of the fold's postures predicted by the fit of the others, refitted
//! from the fit of all the readings (the same model, the same Levenberg-Marquardt). From `K = 0`
//! for every axis, each axis in turn tries each higher order and keeps it when it lowers the
//! held-out error by more than `ACCEPT` standard errors of the paired per-posture differences and
//! by 2 % of it (a one-sided test at about 0.1 %): a straight, stiff rail keeps `K = 0`, its
//! direction alone.
//!
//! Equations and sources: docs/model.md, section "Calibration", "External axes".

pub(crate) use super::maps::ACCEPT;
pub(crate) use super::maps::FOLDS;

use super::error_model::{ErrorModel, Observation};
use super::fit::{self, Fit, Options};
use super::validation;
use rayon::prelude::*;
use stiffid_core::common::error::JobOption;
use stiffid_core::robot::external::AxisKind;
use stiffid_core::{Error, Result};

/// The highest order `--error-motions auto` tries per linear axis.
pub(crate) const MAX_ORDER_TRIED: usize = 6;

/// Which orders a calibration fits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Spec {
    /// Chosen by cross-validation (module docs).
    #[default]
    Auto,
    /// This order for every linear axis (0: the directions alone).
    Fixed(usize),
}

impl Spec {
    /// Parses `auto` or an order `0` to [`stiffid_core::robot::external::MAX_ORDER`].
    ///
    /// # Errors
    /// [`Error::InvalidOption`] ([`JobOption::ErrorMotions`]) naming what was given.
    pub fn parse(text: &str) -> Result<Self> {
        let text = text.trim();
        if text == "auto" {
            return Ok(Spec::Auto);
        }
        match text.parse::<usize>() {
            Ok(k) if k <= super::error_model::MAX_FITTED_ORDER => Ok(Spec::Fixed(k)),
            _ => Err(Error::InvalidOption {
                option: JobOption::ErrorMotions,
                message: format!(
                    "expected auto or an order 0 to {}, got {text:?}",
                    super::error_model::MAX_FITTED_ORDER
                ),
            }),
        }
    }
}

/// One candidate the choice evaluated.
#[derive(Debug, Clone, PartialEq)]
pub struct Tried {
    /// The orders of each external axis (0 for a rotary one).
    pub orders: Vec<usize>,
    /// Its held-out RMS error, m.
    pub rms: f64,
    /// Whether the choice kept it.
    pub kept: bool,
}

/// The orders chosen.
#[derive(Debug, Clone, PartialEq)]
pub struct Choice {
    /// The orders of each external axis (0 for a rotary one).
    pub orders: Vec<usize>,
    /// The held-out RMS error of the choice, m (`None` when the orders were given).
    pub rms: Option<f64>,
    /// Every candidate evaluated, in order.
    pub tried: Vec<Tried>,
}

/// A candidate's held-out errors.
struct Scored {
    /// Per posture (all folds, in order), the sum of squared errors, m^2.
    errors: Vec<f64>,
    total: f64,
    readings: usize,
}

impl Scored {
    fn rms(&self) -> f64 {
        (self.total / self.readings.max(1) as f64).sqrt()
    }
}

/// Whether `candidate` lowers the held-out error of `current` by `ACCEPT` standard errors
/// (`acceptance::lowers`).
fn better(current: &Scored, candidate: &Scored) -> bool {
    super::acceptance::lowers(
        (&current.errors, current.total),
        (&candidate.errors, candidate.total),
        ACCEPT,
    )
}

/// The highest order tried on each external axis: [`MAX_ORDER_TRIED`], at most the axis's
/// distinct positions in `observations` less two; 0 for a rotary axis.
fn highest(model: &ErrorModel, observations: &[Observation]) -> Vec<usize> {
    let Some(axes) = model.robot().external() else {
        return Vec::new();
    };
    (axes.axes().iter().enumerate())
        .map(|(i, a)| match a.kind {
            AxisKind::Rotary => 0,
            AxisKind::Linear => {
                let mut s: Vec<f64> = (observations.iter())
                    .filter(|o| !o.table)
                    .filter_map(|o| o.e.as_slice().get(i).copied())
                    .collect();
                s.sort_by(f64::total_cmp);
                let width = (a.upper - a.lower) * 1e-6;
                s.dedup_by(|b, a| (*b - *a).abs() <= width);
                s.len().saturating_sub(2).min(MAX_ORDER_TRIED)
            }
        })
        .collect()
}

/// The model `base` (without external axes) with the external axes of its robot at `orders` and
/// `tables` reflectors on the positioner's table, fitted to `observations` from its start.
///
/// # Errors
/// Those of [`ErrorModel::with_external`], [`fit::start`] and [`fit::fit`].
pub(crate) fn fitted(
    base: &ErrorModel,
    orders: &[usize],
    tables: usize,
    observations: &[Observation],
    options: &Options,
) -> Result<(ErrorModel, Fit)> {
    let model = base.clone().with_external(orders, tables)?;
    let start = fit::start(&model, observations)?;
    let fit = fit::fit(&model, observations, &start, options)?;
    Ok((model, fit))
}

/// The held-out errors of `model` (fitted to `observations` as `full`) over [`FOLDS`] folds of
/// the postures, each fold refitted from `full`.
fn score(
    model: &ErrorModel,
    full: &Fit,
    observations: &[Observation],
    options: &Options,
) -> Result<Scored> {
    let mut postures: Vec<usize> = observations.iter().map(|o| o.posture).collect();
    postures.sort_unstable();
    postures.dedup();
    let k = FOLDS.min(postures.len());
    let per_fold = (0..k)
        .into_par_iter()
        .map(|f| {
            let out =
                |o: &Observation| postures.binary_search(&o.posture).is_ok_and(|i| i % k == f);
            let (test, train): (Vec<Observation>, Vec<Observation>) =
                observations.iter().cloned().partition(|o| out(o));
            let refit = fit::fit(model, &train, &full.estimate, options)?;
            let held = validation::validate(model, &refit.estimate, &test)?;
            let mut per = std::collections::BTreeMap::<usize, f64>::new();
            for e in &held.errors {
                *per.entry(e.posture).or_default() += e.error.norm_squared();
            }
            Ok(per)
        })
        .collect::<Result<Vec<_>>>()?;
    let mut errors = vec![0.0; postures.len()];
    for per in per_fold {
        for (p, v) in per {
            if let Ok(i) = postures.binary_search(&p) {
                errors[i] += v;
            }
        }
    }
    let total = errors.iter().sum();
    Ok(Scored {
        errors,
        total,
        readings: observations.len(),
    })
}

/// The orders of `spec` for the external axes of `base`'s robot, the model with them and its
/// fit to `observations` (module docs): [`Spec::Fixed`] gives every linear axis its order,
/// [`Spec::Auto`] chooses by cross-validation.
///
/// # Errors
/// [`Error::InvalidField`] (`external_axis`) when the robot has no external axes; those of
/// `fitted` for every candidate and fold.
pub fn choose(
    base: &ErrorModel,
    tables: usize,
    observations: &[Observation],
    options: &Options,
    spec: Spec,
) -> Result<(ErrorModel, Fit, Choice)> {
    let Some(axes) = base.robot().external() else {
        return Err(Error::InvalidField {
            field: "external_axis".into(),
            message: "the robot has no external axes".into(),
        });
    };
    let linear = |i: usize| axes.axes()[i].kind == AxisKind::Linear;
    if let Spec::Fixed(k) = spec {
        let orders: Vec<usize> = (0..axes.len())
            .map(|i| if linear(i) { k } else { 0 })
            .collect();
        let (model, fit) = fitted(base, &orders, tables, observations, options)?;
        let choice = Choice {
            orders,
            rms: None,
            tried: Vec::new(),
        };
        return Ok((model, fit, choice));
    }
    let highest = highest(base, observations);
    let mut tried = Vec::new();
    let mut current = vec![0; axes.len()];
    let (mut model, mut fit) = fitted(base, &current, tables, observations, options)?;
    let mut scored = score(&model, &fit, observations, options)?;
    tried.push(Tried {
        orders: current.clone(),
        rms: scored.rms(),
        kept: true,
    });
    for axis in (0..axes.len()).filter(|&i| linear(i)) {
        for k in 1..=highest[axis] {
            let mut orders = current.clone();
            orders[axis] = k;
            let (m, f) = fitted(base, &orders, tables, observations, options)?;
            let s = score(&m, &f, observations, options)?;
            let kept = better(&scored, &s);
            tried.push(Tried {
                orders: orders.clone(),
                rms: s.rms(),
                kept,
            });
            if kept {
                (current, model, fit, scored) = (orders, m, f, s);
            }
        }
    }
    let choice = Choice {
        orders: current,
        rms: Some(scored.rms()),
        tried,
    };
    Ok((model, fit, choice))
}
