//! How many postures an experiment needs: the smallest group size whose chosen group predicts a
//! deviation rate of at most a target on every joint (and every virtual spring of the setup's
//! model), at noise level multiple 1.
//!
//! The prediction is the first-order one of [`super::Evaluation::predicted_deviation_pct`]:
//! `100 sqrt(2/pi) sqrt([(S^T S)^-1]_jj)` percent for joint j at multiple 1.

use super::criteria::predicted_deviation_pct;
use super::Evaluator;
use crate::setup::Setup;
use crate::Error;
use nalgebra::Vector6;

/// The smallest group size tried.
pub const MIN_POSTURES: usize = 2;

/// The largest group size tried.
pub const MAX_POSTURES: usize = 60;

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
    pub fn worst_pct(&self) -> f64 {
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
    /// One step per group size from [`MIN_POSTURES`] up: to the first that reaches the target, or
    /// to the largest allowed.
    pub steps: Vec<TargetStep>,
    /// Whether the last step's worst joint is at most the target.
    pub reached: bool,
}

impl TargetOutcome {
    /// The step that reached the target, if any.
    pub fn chosen(&self) -> Option<&TargetStep> {
        self.steps.last().filter(|_| self.reached)
    }
}

/// Tries group sizes `n` = [`MIN_POSTURES`], 3, ... up to `max_postures` (at most
/// [`MAX_POSTURES`]), choosing each group with `choose(n)` (a search or a pool choice by some
/// criterion), and stops at the first whose worst predicted deviation rate at noise multiple 1
/// (of the joints and the model's virtual springs) is at most `target_pct` (%).
///
/// # Errors
/// [`Error::InvalidField`] (`target_pct`) for a target that is not a finite number > 0,
/// (`postures`) for `max_postures` below [`MIN_POSTURES`]; [`Error::MissingField`] for a setup
/// without a nominal stiffness (the predicted deviation rates need it); whatever `choose` returns.
pub fn smallest_group<E: From<Error>>(
    setup: &Setup,
    target_pct: f64,
    max_postures: usize,
    mut choose: impl FnMut(usize) -> std::result::Result<Vec<Vector6<f64>>, E>,
) -> std::result::Result<TargetOutcome, E> {
    if !(target_pct.is_finite() && target_pct > 0.0) {
        return Err(Error::InvalidField {
            field: "target_pct".into(),
            message: format!("{target_pct} given: expected a finite percentage > 0"),
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
    let mut steps = Vec::new();
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
            return Ok(TargetOutcome {
                target_pct,
                steps,
                reached,
            });
        }
    }
    Ok(TargetOutcome {
        target_pct,
        steps,
        reached: false,
    })
}
