//! The group chosen by a search or from a pool, the smallest group for a target, and the same
//! search without the cell's checks.

use super::{Candidates, Method, Request, Unconstrained};
use crate::app::purpose::Purpose;
use nalgebra::Vector6;
use stiffid_core::cell::Checker;
use stiffid_core::common::error::JobOption;
use stiffid_core::{Error, Result, Setup};
use stiffid_design::target::{smallest_group, TargetOutcome};
use stiffid_design::{self as design, evaluate, Goal, PoolMethod, SearchOutcome, Termination};

/// What one search or pool choice found.
pub(super) struct Found {
    pub(super) postures: Vec<Vector6<f64>>,
    pub(super) start_value: Option<f64>,
    pub(super) value: f64,
    pub(super) evaluations: usize,
    pub(super) termination: Termination,
    pub(super) terminations: Vec<Termination>,
    /// A pool choice's postures (1-based) and how they were chosen.
    pub(super) chosen: Option<(Vec<usize>, PoolMethod)>,
}

impl From<SearchOutcome> for Found {
    fn from(o: SearchOutcome) -> Self {
        Found {
            postures: o.postures,
            start_value: Some(o.start_value),
            value: o.value,
            evaluations: o.evaluations,
            termination: o.termination,
            terminations: o.terminations,
            chosen: None,
        }
    }
}

/// The group of `n` postures on `setup` by the request's method.
pub(super) fn choose(
    r: &Request,
    goal: &Goal,
    setup: &Setup,
    pool: Option<&Candidates>,
    n: usize,
) -> Result<Found> {
    if let Some(p) = pool {
        return p.choose(r, goal, n);
    }
    let name = match (r.purpose, goal.calibration) {
        (Purpose::Stiffness, _) | (_, None) => r.criterion.to_string(),
        (Purpose::Calibration, Some(c)) => format!("calibration {}", choice_name(c.criterion)),
        (Purpose::Check, Some(c)) => format!("check {}", choice_name(c.criterion)),
        (Purpose::Both, Some(c)) => {
            format!(
                "{} and calibration {}",
                r.criterion,
                choice_name(c.criterion)
            )
        }
    };
    let outcome = match r.method {
        Method::Global => {
            r.progress
                .begin(&format!("global search ({name})"), r.options.starts);
            design::global_for(setup, goal, n, &r.options, r.progress)
        }
        _ => {
            r.progress.begin(&format!("local search ({name})"), 0);
            let start = match &r.start {
                Some(s) => s.clone(),
                None => design::random_group(setup, n, r.options.seed),
            };
            design::local_for(setup, goal, &start, &r.options)
        }
    };
    r.progress.end();
    Ok(outcome?.into())
}

/// The name of a choice.
pub(super) fn choice_name<C: stiffid_core::common::choice::Choice>(c: C) -> &'static str {
    c.name()
}

/// The smallest group that reaches `pct` (its evaluations those of every group size tried), and
/// every group size tried.
pub(super) fn smallest(
    r: &Request,
    pool: Option<&Candidates>,
    pct: f64,
) -> Result<(Found, TargetOutcome)> {
    let max = pool.map_or(design::target::MAX_POSTURES, Candidates::usable);
    let (mut last, mut evaluations) = (None, 0);
    let goal = Goal::stiffness(r.criterion);
    let outcome = smallest_group(r.setup, pct, max, |n| -> Result<_> {
        let found = choose(r, &goal, r.setup, pool, n)?;
        let postures = found.postures.clone();
        evaluations += found.evaluations;
        last = Some(found);
        Ok(postures)
    })?;
    let (Some(mut found), Some(step)) = (last, outcome.steps.last()) else {
        unreachable!("smallest_group tries at least one size or fails");
    };
    found.evaluations = evaluations;
    if outcome.reached {
        return Ok((found, outcome));
    }
    let (j, worst) = step.worst_joint();
    let max = outcome.max_postures;
    let tried = match pool {
        Some(_) => format!("the pool's {max} usable postures"),
        None => format!("{max} postures"),
    };
    let found = match outcome.extrapolated_pct {
        None => format!(
            "with {tried} the predicted mean deviation rate of joint {} is still {worst:.3} %",
            j + 1
        ),
        Some(best) => format!(
            "with {} postures the predicted mean deviation rate of joint {} is {worst:.3} %; it falls about as 1/sqrt(N), so the best reachable with {tried} is about {best:.3} % (stopped after {} group sizes)",
            step.postures.len(),
            j + 1,
            outcome.steps.len()
        ),
    };
    Err(Error::InvalidOption {
        option: JobOption::TargetPct,
        message: format!(
            "{pct} % is not reachable: {found} at noise level multiple 1 (add postures to the pool, lower the noise or raise the target)"
        ),
    })
}

/// With cell checks: the same search of `n` postures without them.
pub(super) fn unconstrained(r: &Request, goal: &Goal, n: usize) -> Result<Option<Unconstrained>> {
    if !Checker::new(r.setup).constrains() {
        return Ok(None);
    }
    let free = choose(r, goal, &r.setup.without_cell(), None, n)?;
    Ok(Some(Unconstrained {
        evaluation: evaluate(r.setup, &free.postures),
        postures: free.postures,
        value: free.value,
        termination: free.termination,
    }))
}
