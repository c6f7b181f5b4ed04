//! The group chosen by a search or from a screened pool ([`choose`]), the smallest group for a
//! target accuracy ([`smallest`]), and the same search without the cell's checks
//! ([`unconstrained`]), and how the cell holds the group chosen ([`in_cell`]).

use super::pool::Screened;
use super::station;
use crate::distinct::{near_pairs_by, Distinctness, Near};
use crate::search::{design_checker, design_margin};
use crate::target::{smallest_group, TargetOutcome};
use crate::{self as design, evaluate, Evaluation, Goal, PoolMethod, PoolOptions};
use crate::{SearchOptions, SearchOutcome, Termination};
use nalgebra::Vector6;
use stiffid_core::cell::Checker;
use stiffid_core::common::error::JobOption;
use stiffid_core::common::progress::Progress;
use stiffid_core::robot::external::ExternalValues;
use stiffid_core::{Error, Result, Setup};

/// How a group is chosen.
#[derive(Clone, Copy)]
pub enum How<'a> {
    /// One SQP search from a start group (axis angles, rad), or from a seeded random group
    /// ([`design::random_group`]) with `None`.
    Local(Option<&'a [Vector6<f64>]>),
    /// Local searches from seeded start groups, the best kept ([`design::global_for`]).
    Global,
    /// The best group of a screened pool, by `restarts` exchange runs where it cannot enumerate
    /// (`None`: [`PoolOptions`]' default).
    Pool(&'a Screened<'a>, Option<usize>),
}

/// The search's budget and where it reports.
#[derive(Clone, Copy)]
pub struct Searching<'a> {
    /// The budget and tolerances of the searches; its seed seeds the random start group, the
    /// global starts and the pool's exchange runs.
    pub options: &'a SearchOptions,
    /// Where the searches report their progress: each begins a stage (`global search (NAME)`
    /// with its starts as the total; a local search and the choice from a pool with total 0).
    pub progress: &'a dyn Progress,
    /// The name of what is minimised in the stages (`relative-a`, `calibration test-pose`).
    pub name: &'a str,
}

/// What one search or pool choice found.
#[derive(Debug, Clone)]
pub struct Found {
    /// The group (axis angles, rad).
    pub postures: Vec<Vector6<f64>>,
    /// The value minimised for the start group; `None` for a pool choice.
    pub start_value: Option<f64>,
    /// The value minimised for the group.
    pub value: f64,
    /// Criterion evaluations.
    pub evaluations: usize,
    /// Why the search that found the group stopped ([`Termination::Converged`] for a pool).
    pub termination: Termination,
    /// Why every local search stopped; empty for a pool choice.
    pub terminations: Vec<Termination>,
    /// A pool choice's postures (numbers in the pool, 1-based) and how they were chosen.
    pub chosen: Option<(Vec<usize>, PoolMethod)>,
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

/// The group of `n` postures on `setup` for `goal`, chosen `how`.
///
/// # Errors
/// Those of the search (`design::local_for`, [`design::global_for`]) or of
/// `Screened::best`.
pub fn choose(setup: &Setup, goal: &Goal, how: How, n: usize, s: Searching) -> Result<Found> {
    let (options, progress) = (s.options, s.progress);
    let outcome = match how {
        How::Pool(pool, restarts) => {
            let options = PoolOptions {
                seed: options.seed,
                restarts: restarts.unwrap_or(PoolOptions::default().restarts),
                ..PoolOptions::default()
            };
            let c = pool.best(goal, n, &options, progress)?;
            return Ok(Found {
                postures: c.postures,
                start_value: None,
                value: c.value,
                evaluations: c.evaluations,
                termination: Termination::Converged,
                terminations: Vec::new(),
                chosen: Some((c.numbers, c.method)),
            });
        }
        How::Global => {
            progress.begin(&format!("global search ({})", s.name), options.starts);
            design::global_for(setup, goal, n, options, progress)
        }
        How::Local(start) => {
            progress.begin(&format!("local search ({})", s.name), 0);
            let start = match start {
                Some(s) => s.to_vec(),
                None => design::random_group(setup, n, options.seed),
            };
            design::local_for(setup, goal, &start, options)
        }
    };
    progress.end();
    Ok(outcome?.into())
}

/// The smallest group on `setup` whose predicted mean deviation rate at noise level multiple 1
/// is at most `pct` % on every parameter, each size's group chosen `how` for the stiffness
/// `criterion` (its evaluations those of every group size tried), and every group size tried
/// ([`smallest_group`]).
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::TargetPct`]) when no group size reaches it, naming the
/// best rate reachable; those of [`smallest_group`] and [`choose`].
pub fn smallest(
    setup: &Setup,
    criterion: crate::Criterion,
    how: How,
    s: Searching,
    pct: f64,
) -> Result<(Found, TargetOutcome)> {
    let pool = match how {
        How::Pool(p, _) => Some(p),
        _ => None,
    };
    let max = pool.map_or(design::target::MAX_POSTURES, Screened::usable);
    let (mut last, mut evaluations) = (None, 0);
    let goal = Goal::stiffness(criterion);
    let outcome = smallest_group(setup, pct, max, |n| -> Result<_> {
        let found = choose(setup, &goal, how, n, s)?;
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

/// The same search without the cell's checks.
#[derive(Debug, Clone)]
pub struct Unconstrained {
    /// Its group (axis angles, rad).
    pub postures: Vec<Vector6<f64>>,
    /// Its criterion.
    pub value: f64,
    /// Why its search stopped.
    pub termination: Termination,
    /// Every criterion of its group (on the setup: the criteria do not depend on the cell).
    pub evaluation: Evaluation,
}

/// With cell checks on `setup`: the same search of `n` postures without them; `None` without
/// checks.
///
/// # Errors
/// Those of [`choose`].
pub fn unconstrained(
    setup: &Setup,
    goal: &Goal,
    how: How,
    n: usize,
    s: Searching,
) -> Result<Option<Unconstrained>> {
    if !Checker::new(setup).constrains() {
        return Ok(None);
    }
    let free = choose(&setup.without_cell(), goal, how, n, s)?;
    Ok(Some(Unconstrained {
        evaluation: evaluate(setup, &free.postures),
        postures: free.postures,
        value: free.value,
        termination: free.termination,
    }))
}

/// How the cell holds a chosen group ([`in_cell`]).
#[derive(Debug, Clone, PartialEq)]
pub struct InCell {
    /// The pairs of postures that are not distinct, indices into the whole group.
    pub near: Vec<Near>,
    /// The margin the design kept the cell's lengths beyond, m (`design_margin`).
    pub margin: f64,
    /// Each posture's smallest margin to a constraint of the cell's lengths, m, as the design
    /// with the margin kept it (the tool, where the rope and the lines of sight start, beyond the
    /// margin: `design_checker`); `None` where no constraint applies.
    pub min_margins: Vec<Option<f64>>,
}

/// How the cell holds `groups`, chosen on `setup` with the design's `margin` (m; `None`: the
/// setup's): group `k` with the arm standing at `stations[k]` ([`station::setup_at`]), or as
/// the setup stands where no station is given; the pairs of postures within `distances` of each
/// other (`near_pairs_by`), counted over the whole group.
///
/// # Errors
/// Those of [`station::setup_at`].
pub fn in_cell(
    setup: &Setup,
    groups: &[Vec<Vector6<f64>>],
    stations: &[ExternalValues],
    margin: Option<f64>,
    distances: &Distinctness,
) -> Result<InCell> {
    let (mut near, mut min_margins, mut offset) = (Vec::new(), Vec::new(), 0);
    for (k, group) in groups.iter().enumerate() {
        let owned;
        let at = match stations.get(k) {
            Some(e) => {
                owned = station::setup_at(setup, e)?;
                &owned
            }
            None => setup,
        };
        near.extend(
            (near_pairs_by(at.robot(), group, distances).into_iter()).map(|p| Near {
                a: p.a + offset,
                b: p.b + offset,
                ..p
            }),
        );
        let checker = design_checker(at, margin);
        let keep = checker.keep();
        let of = |q| checker.feasibility(q).min_margin().map(|c| c.margin + keep);
        min_margins.extend(group.iter().map(of));
        offset += group.len();
    }
    Ok(InCell {
        near,
        margin: design_margin(setup, margin),
        min_margins,
    })
}
