//! Local search: SQP ([`super::sqp`]) from a start group, with exact gradients or forward finite
//! differences.

mod problem;

use super::constraints::{design_checker, most_failed};
use super::{Goal, Gradient, SearchOptions, SearchOutcome};
use crate::Criterion;
use nalgebra::Vector6;
use problem::Problem;
use stiffid_core::cell::{CheckKind, Checker};
use stiffid_core::setup::Setup;
use stiffid_core::{Error, Result};

/// What the SQP minimises for a criterion value `v`: `ln v`, and this penalty for `+infinity`
/// (rank-deficient groups), above `ln f64::MAX ~ 709.8` so any finite value is better.
const PENALTY: f64 = 1e3;

/// Minimises `criterion` by SQP (the counterpart of the MATLAB `fmincon` of Zhang et al. 2021,
/// Section III-B step 5: [`SearchOptions::solver`], by default chosen per criterion by
/// [`Solver::resolve`](crate::Solver::resolve)) over the `6n` axis angles of the `n` postures of `start` (rad), within the setup's
/// bounds.
///
/// - The objective is `ln(criterion)` (scale-free steps; a rank-deficient group, `+infinity`,
///   counts as a large finite penalty, never NaN, with a zero gradient). Its gradient is exact
///   ([`crate::Evaluator::value_and_gradient`], [`Gradient::Exact`], the default) or by
///   forward differences of step [`SearchOptions::fd_step`] ([`Gradient::FiniteDifference`]),
///   backwards where the forward probe would leave the bounds; a probe that hits a rank-deficient
///   group takes the other side, or a zero component.
/// - Every point evaluated is clamped into the bounds; the best point evaluated is returned, so the
///   result never leaves the bounds and is never worse than the start.
/// - The cell's feasibility checks ([`stiffid_core::cell::Checker`]: floor, obstacles, self-collision,
///   rope, line of sight, incidence, `[constraints]`) become one smooth inequality constraint per
///   check and posture (the smooth minimum of the check's pair margins, never above the exact
///   minimum); a point that violates the exact checks less always beats one that violates them
///   more, so the best exactly feasible point seen is returned.
/// - Stops at [`SearchOptions::ftol`] / [`SearchOptions::xtol`] (confirmed once from a fresh
///   Hessian approximation) or after at most [`SearchOptions::max_evals`] criterion evaluations
///   (finite differences included); [`SearchOutcome::termination`] says which.
///
/// # Errors
/// [`Error::InvalidField`] for `options` outside their limits ([`SearchOptions::validate`]), fewer
/// than 2 postures, or the `test-pose` criterion on a setup without test postures;
/// [`Error::OutsideBox`] for a start angle outside the bounds or not finite (naming the posture,
/// the axis and the value); [`Error::MissingField`] for a criterion the setup lacks a field for
/// ([`Criterion::check`]);
/// [`Error::Infeasible`] naming the check failed by the most postures when no point seen passes
/// every check.
///
/// # Examples
/// From a seeded start group of 8 postures on the paper's setup, SQP on `relative-a` ends lower,
/// within the bounds.
/// ```
/// use stiffid_design::{local, random_group, Criterion, SearchOptions};
/// let setup = stiffid_core::setup::builtin("zhang2021-comau-nj165")?;
/// let start = random_group(&setup, 8, 1);
/// let options = SearchOptions { max_evals: 200, ..SearchOptions::default() };
/// let out = local(&setup, Criterion::RelativeA, &start, &options)?;
/// assert!(out.value < out.start_value);
/// assert!(out.postures.iter().all(|q| setup.bounds().contains(q)));
/// # Ok::<(), stiffid_core::Error>(())
/// ```
pub fn local(
    setup: &Setup,
    criterion: Criterion,
    start: &[Vector6<f64>],
    options: &SearchOptions,
) -> Result<SearchOutcome> {
    local_for(setup, &Goal::stiffness(criterion), start, options)
}

/// [`local`] of any [`Goal`]: a stiffness criterion, a calibration criterion, or both.
///
/// # Errors
/// Those of [`local`]; [`Error::InvalidField`] (`postures`) for a group too small to separate
/// the calibration's kept parameters.
pub(crate) fn local_for(
    setup: &Setup,
    goal: &Goal,
    start: &[Vector6<f64>],
    options: &SearchOptions,
) -> Result<SearchOutcome> {
    options.validate()?;
    check_start(setup, goal, start)?;
    let checker = design_checker(setup, options.margin);
    let outcome = local_in(&checker, goal, start, options);
    infeasible(&checker, std::iter::once(&outcome))?;
    Ok(outcome)
}

/// [`local`] with a checker built once, from a checked start; the result may be infeasible.
pub(super) fn local_in(
    checker: &Checker,
    goal: &Goal,
    start: &[Vector6<f64>],
    options: &SearchOptions,
) -> SearchOutcome {
    Problem::new(checker, *goal, start.len(), options).run(start)
}

/// [`Error::Infeasible`] if the best of `outcomes` (the least violating) fails a check, naming the
/// check failed by the most postures of all of them.
pub(super) fn infeasible<'o>(
    checker: &Checker,
    outcomes: impl Iterator<Item = &'o SearchOutcome> + Clone,
) -> Result<()> {
    let feasible = |o: &SearchOutcome| o.postures.iter().all(|q| checker.violation(q) == 0.0);
    if !checker.constrains() || outcomes.clone().any(feasible) {
        return Ok(());
    }
    let groups = outcomes.map(|o| o.postures.as_slice());
    let (check, failed, postures) =
        most_failed(checker, groups).unwrap_or((CheckKind::Bounds, 0, 0));
    Err(infeasible_error(checker, check, failed, postures))
}

/// [`Error::Infeasible`] for the check `kind` failed in `failed` of `postures` postures, with the
/// checker's margin and the setup fields that decide the check.
pub(super) fn infeasible_error(
    checker: &Checker,
    kind: CheckKind,
    failed: usize,
    postures: usize,
) -> Error {
    let check = match checker.keep() > 0.0 {
        false => kind.key().to_string(),
        true => format!("{} with its {} mm margin", kind.key(), checker.keep() * 1e3),
    };
    Error::Infeasible {
        check,
        failed,
        postures,
        remedy: kind.remedy(checker.setup()),
    }
}

/// Criterion evaluations of one SQP call for `n` postures: 1 with the exact gradient, `6n + 1`
/// with finite differences.
pub(super) fn evals_per_step(options: &SearchOptions, n: usize) -> usize {
    match options.gradient {
        Gradient::Exact => 1,
        Gradient::FiniteDifference => 6 * n + 1,
    }
}

/// Checks a start group: at least 2 postures, finite, within the bounds.
pub(super) fn check_start(setup: &Setup, goal: &Goal, start: &[Vector6<f64>]) -> Result<()> {
    check_count(setup, goal, start.len())?;
    for (i, q) in start.iter().enumerate() {
        let field = |a: usize| format!("start posture {}, q{}_deg", i + 1, a + 1);
        setup.bounds().check(q, "the setup's bounds", field)?;
    }
    Ok(())
}

/// Checks a group size and that the setup can evaluate the goal's criteria
/// ([`Criterion::check`]; a calibration needs at least as many coordinates as kept parameters).
pub(crate) fn check_count(setup: &Setup, goal: &Goal, n: usize) -> Result<()> {
    if let Some(c) = goal.calibration {
        let (rows, kept) = (3 * c.design.model().points(), c.design.kept().len());
        if n >= 2 && n * rows < kept {
            return Err(Error::InvalidField {
                field: "postures".into(),
                message: format!(
                    "{n} given: the calibration's {kept} parameters need at least {} postures ({rows} coordinates each)",
                    kept.div_ceil(rows)
                ),
            });
        }
        if !goal.has_stiffness() {
            return check_size(n);
        }
    }
    let criterion = goal.stiffness;
    criterion.check(setup)?;
    check_size(n)?;
    // A posture gives at most min(3p, 6) independent rows of Psi.
    let rows = (3 * setup.tool().measuring_points.len()).min(6);
    let parameters = setup.model().len();
    if n * rows < parameters {
        return Err(Error::InvalidField {
            field: "postures".into(),
            message: format!(
                "{n} given: the model's {parameters} parameters need at least {} postures ({rows} independent rows each)",
                parameters.div_ceil(rows)
            ),
        });
    }
    if criterion == Criterion::TestPose && setup.test_postures().is_empty() {
        return Err(Error::InvalidField {
            field: "test.postures_deg".into(),
            message: "the test-pose criterion needs test postures in the setup".into(),
        });
    }
    Ok(())
}

/// At least 2 postures.
fn check_size(n: usize) -> Result<()> {
    match n < 2 {
        true => Err(Error::InvalidField {
            field: "postures".into(),
            message: format!("{n} given: a search needs at least 2 postures"),
        }),
        false => Ok(()),
    }
}
