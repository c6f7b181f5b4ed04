//! How many postures an experiment needs: the smallest group size whose chosen group predicts a
//! deviation rate of at most a target on every joint (and every virtual spring of the setup's
//! model), at noise level multiple 1.
//!
//! The prediction is the first-order one of [`super::Evaluation::predicted_deviation_pct`]:
//! `100 sqrt(2/pi) sqrt([(S^T S)^-1]_jj)` percent for joint j at multiple 1.
//!
//! A target out of reach is seen early: the information of a well-chosen group grows about in
//! proportion to its size N, so its predicted rate falls about as `1/sqrt(N)` (on the paper's setup
//! `rate * sqrt(N)` stays within 5% from 2 to 60 postures). The search stops as soon as 2 sizes in
//! a row extrapolate, by that law, to a rate at the largest size allowed above `STOP_MARGIN`
//! times the target ([`TargetOutcome::extrapolated_pct`]), instead of trying every size up to
//! [`MAX_POSTURES`].

use super::criteria::predicted_deviation_pct;
use super::Evaluator;
use nalgebra::Vector6;
use stiffid_core::common::error::JobOption;
use stiffid_core::setup::Setup;
use stiffid_core::Error;

/// The smallest group size tried.
pub(crate) const MIN_POSTURES: usize = 2;

/// The largest group size tried.
pub const MAX_POSTURES: usize = 60;

/// How far above the target the `1/sqrt(N)` extrapolation to the largest size must be before the
/// search stops early: 1.25 (the law is approximate; a target within 25% of the extrapolation is
/// still searched for size by size).
pub(crate) const STOP_MARGIN: f64 = 1.25;

/// Consecutive sizes whose extrapolation must say "out of reach" before the search stops early (one
/// poorly chosen group must not end it).
pub(crate) const STOP_STEPS: usize = 2;

/// One group size tried.
#[derive(Debug, Clone, PartialEq)]
pub struct TargetStep {
    /// The chosen group (axis angles, rad); its size is the step's group size.
    pub postures: Vec<Vector6<f64>>,
    /// Predicted mean deviation rate of each joint at noise multiple 1, % (`+infinity` for a
    /// rank-deficient group).
    pub deviation_pct: [f64; 6],
    /// The same for each virtual spring of the setup's model, in its order (empty for the drives
    /// alone).
    pub spring_deviation_pct: Vec<f64>,
}

impl TargetStep {
    /// The worst parameter's predicted deviation rate, %: of the joints and virtual springs.
    pub(crate) fn worst_pct(&self) -> f64 {
        let springs = self.spring_deviation_pct.iter().copied();
        springs.fold(self.worst_joint().1, f64::max)
    }

    /// The worst joint (0-based) and its predicted deviation rate, %.
    pub fn worst_joint(&self) -> (usize, f64) {
        (0..6).fold((0, f64::NEG_INFINITY), |(jw, w), j| {
            match self.deviation_pct[j] > w {
                true => (j, self.deviation_pct[j]),
                false => (jw, w),
            }
        })
    }
}

/// The group sizes tried, in order, and whether the last one reached the target.
#[derive(Debug, Clone, PartialEq)]
pub struct TargetOutcome {
    /// The target, %.
    pub target_pct: f64,
    /// One step per group size from 2 up: to the first that reaches the target, or
    /// to the largest allowed.
    pub steps: Vec<TargetStep>,
    /// Whether the last step's worst joint is at most the target.
    pub reached: bool,
    /// The largest group size allowed.
    pub max_postures: usize,
    /// When the search stopped early: the worst rate (%) the last step extrapolates to at
    /// [`TargetOutcome::max_postures`] by the `1/sqrt(N)` law (`extrapolate`), above
    /// `STOP_MARGIN` times the target. `None` when every size up to the largest was tried or
    /// the target was reached.
    pub extrapolated_pct: Option<f64>,
}

impl TargetOutcome {
    /// The step that reached the target, if any.
    pub fn chosen(&self) -> Option<&TargetStep> {
        self.steps.last().filter(|_| self.reached)
    }
}

/// Tries group sizes `n` = 2, 3, ... up to `max_postures` (at most
/// [`MAX_POSTURES`]), choosing each group with `choose(n)` (a search or a pool choice by some
/// criterion), and stops at the first whose worst predicted deviation rate at noise multiple 1
/// (of the joints and the model's virtual springs) is at most `target_pct` (%).
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::TargetPct`]) for a target that is not a finite number > 0,
/// (`postures`) for `max_postures` below 2; [`Error::MissingField`] for a setup
/// without a nominal stiffness (the predicted deviation rates need it); whatever `choose` returns.
pub fn smallest_group<E: From<Error>>(
    setup: &Setup,
    target_pct: f64,
    max_postures: usize,
    mut choose: impl FnMut(usize) -> std::result::Result<Vec<Vector6<f64>>, E>,
) -> std::result::Result<TargetOutcome, E> {
    if !(target_pct.is_finite() && target_pct > 0.0) {
        return Err(Error::InvalidOption {
            option: JobOption::TargetPct,
            message: format!(
                "{} given: expected a finite percentage > 0",
                stiffid_core::common::words::number(target_pct)
            ),
        }
        .into());
    }
    setup.try_nominal_stiffness("a target deviation rate (the predicted deviation rates)")?;
    let max = max_postures.min(MAX_POSTURES);
    if max < MIN_POSTURES {
        return Err(Error::InvalidField {
            field: "postures".into(),
            message: format!("{max_postures} available: at least {MIN_POSTURES} are needed"),
        }
        .into());
    }
    let evaluator = Evaluator::new(setup);
    let mut steps: Vec<TargetStep> = Vec::new();
    let outcome = |steps, reached, extrapolated_pct| TargetOutcome {
        target_pct,
        steps,
        reached,
        max_postures: max,
        extrapolated_pct,
    };
    for n in MIN_POSTURES..=max {
        let postures = choose(n)?;
        let e = evaluator.evaluation(&postures);
        let step = TargetStep {
            postures,
            deviation_pct: predicted_deviation_pct(&e.relative_std, 1.0),
            spring_deviation_pct: e.parameters(setup)[6..]
                .iter()
                .map(|p| p.predicted_deviation_pct)
                .collect(),
        };
        let reached = step.worst_pct() <= target_pct;
        steps.push(step);
        if reached {
            return Ok(outcome(steps, true, None));
        }
        if let Some(pct) = out_of_reach(&steps, target_pct, max) {
            return Ok(outcome(steps, false, Some(pct)));
        }
    }
    Ok(outcome(steps, false, None))
}

/// The worst rate (%) at `n` postures extrapolated from `step` by the `1/sqrt(N)` law:
/// `worst_pct * sqrt(len / n)`; `+infinity` for a rank-deficient step.
pub(crate) fn extrapolate(step: &TargetStep, n: usize) -> f64 {
    step.worst_pct() * (step.postures.len() as f64 / n as f64).sqrt()
}

/// The last step's extrapolation to `max` postures when each of the last [`STOP_STEPS`] steps
/// extrapolates above [`STOP_MARGIN`] times the target (finite values only), else `None`.
fn out_of_reach(steps: &[TargetStep], target_pct: f64, max: usize) -> Option<f64> {
    let last = steps.len().checked_sub(STOP_STEPS).map(|i| &steps[i..])?;
    let beyond = |s: &TargetStep| {
        let pct = extrapolate(s, max);
        pct.is_finite() && pct > STOP_MARGIN * target_pct
    };
    last.iter()
        .all(beyond)
        .then(|| extrapolate(&steps[steps.len() - 1], max))
}
