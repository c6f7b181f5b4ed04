//! The request's checks: its parts fit its method, and its counts are in range.

use super::{in_pool, Method, Request};
use super::{DISTINCT_DEG, DISTINCT_MM};
use crate::app::purpose::{self, Purpose};
use stiffid_core::cell::Checker;
use stiffid_core::common::error::JobOption;
use stiffid_core::common::limits::{self, check_count};
use stiffid_core::{Error, Result};
use stiffid_design::pool::MAX_POOL;

/// The request's parts fit its method, and its counts are in range.
pub(super) fn check(r: &Request) -> Result<()> {
    r.setup.check_bodies()?;
    if !r.purpose.calibration_only() {
        r.setup
            .require_loading("select (the rope load of every posture)")?;
    }
    check_method(r)?;
    r.options.validate()?;
    if r.options.margin.is_some() && !Checker::new(r.setup).constrains() {
        return invalid_option(
            JobOption::MarginMm,
            "the setup has no cell, tracker or constraints to keep a margin to",
        );
    }
    purpose::check(r.purpose, &r.calibration)?;
    check_candidates_and_target(r)?;
    if let Some(p) = &r.pool
        && p.postures.len() > MAX_POOL
    {
        let message = format!(
            "{} postures: a pool holds at most {MAX_POOL}",
            p.postures.len()
        );
        return Err(in_pool(&p.name, "pool", message));
    }
    Ok(())
}

fn invalid(field: &str, message: &str) -> Result<()> {
    Err(Error::InvalidField {
        field: field.into(),
        message: message.into(),
    })
}

fn invalid_option(option: JobOption, message: &str) -> Result<()> {
    Err(Error::InvalidOption {
        option,
        message: message.into(),
    })
}

/// The start, the pool, the distinctness and the restarts fit the method; the counts in range.
fn check_method(r: &Request) -> Result<()> {
    if r.start.is_some() && r.method != Method::Local {
        return invalid_option(JobOption::Start, "only for a local search");
    }
    if r.pool.is_some() != (r.method == Method::Pool) {
        return invalid("pool", "a pool choice needs the pool postures, and only it");
    }
    if let Some(d) = &r.distinct {
        if r.method != Method::Pool {
            return invalid(
                "distinct",
                "only for a pool choice: a search moves every posture freely and cannot forbid pairs; choose from a pool of postures (the pool keeps the first of every near pair), or drop distinct and look at the near pairs flagged",
            );
        }
        let deg = |v: f64| limits::check("distinct_deg", &[v.to_degrees()], &DISTINCT_DEG);
        (deg(d.joint).and(deg(d.angle))).map_err(|e| e.for_option(JobOption::DistinctDeg))?;
        limits::check("distinct_mm", &[d.position * 1e3], &DISTINCT_MM)
            .map_err(|e| e.for_option(JobOption::DistinctMm))?;
    }
    let most = limits::MAX_SEARCH_POSTURES as usize;
    match &r.start {
        Some(start) => check_count("start", start.len(), 2, most)
            .map_err(|e| e.for_option(JobOption::Start))?,
        None if r.target_pct.is_none() => check_count("postures", r.postures, 2, most)?,
        None => {}
    }
    if let Some(restarts) = r.restarts {
        if r.method != Method::Pool {
            return invalid_option(
                JobOption::Restarts,
                "only for a pool choice (the exchange runs over the pool)",
            );
        }
        limits::check_integer("restarts", restarts as u64, 1, limits::MAX_POOL_RESTARTS)
            .map_err(|e| e.for_option(JobOption::Restarts))?;
    }
    Ok(())
}

/// The candidate springs and the target deviation rate fit the purpose and the method.
fn check_candidates_and_target(r: &Request) -> Result<()> {
    if r.candidates.is_some() && !r.for_candidates {
        return Err(Error::OptionCombination {
            option: JobOption::Candidates,
            with: vec![JobOption::ForCandidates],
            needs: true,
            reason: String::new(),
        });
    }
    if r.for_candidates && r.purpose != Purpose::Stiffness {
        return invalid_option(
            JobOption::ForCandidates,
            "the candidates are springs of the stiffness model: design for them with the stiffness purpose, and for the calibration separately",
        );
    }
    if r.for_candidates && r.target_pct.is_some() {
        return invalid_option(
            JobOption::ForCandidates,
            "a target deviation rate is for the drives: give the number of postures",
        );
    }
    if let Some(pct) = r.target_pct {
        limits::check("target_pct", &[pct], &limits::TARGET_PCT)
            .map_err(|e| e.for_option(JobOption::TargetPct))?;
        if r.purpose != Purpose::Stiffness {
            return invalid_option(
                JobOption::TargetPct,
                "a target deviation rate is for the stiffness design only",
            );
        }
        if r.method == Method::Local {
            return invalid_option(
                JobOption::TargetPct,
                "needs a pool or the global search to choose each group",
            );
        }
    }
    Ok(())
}

/// Which of the request's options with a default a front end was given (the request holds them
/// as values): each is refused where it means nothing ([`check_given`]).
#[derive(Debug, Clone, Copy, Default)]
pub struct Given {
    /// The stiffness criterion ([`Request::criterion`]).
    pub criterion: bool,
    /// The global search's starts ([`stiffid_design::SearchOptions::starts`]).
    pub starts: bool,
    /// The global search's screening steps ([`stiffid_design::SearchOptions::screen_steps`]).
    pub screen_steps: bool,
    /// The global starts polished ([`stiffid_design::SearchOptions::polished`]).
    pub polished: bool,
    /// The local searches' settings given (other than their defaults), in this order: the most
    /// evaluations ([`stiffid_design::SearchOptions::max_evals`]), the gradient and the SQP
    /// ([`stiffid_design::SearchOptions::gradient`], [`stiffid_design::SearchOptions::solver`]).
    pub search: [bool; 3],
    /// A start group given ([`Request::start`]).
    pub start: bool,
    /// A seed other than its default ([`stiffid_design::SearchOptions::seed`]).
    pub seed: bool,
}

impl Given {
    /// Whether `seed` is given: other than [`stiffid_design::SearchOptions::seed`]'s default.
    pub fn seed_of(seed: u64) -> bool {
        seed != stiffid_design::SearchOptions::default().seed
    }

    /// [`Given::search`] of the most evaluations (`max_evals`: given or not), `gradient` and
    /// `solver` (given when not their defaults).
    pub fn search_of(
        max_evals: bool,
        gradient: stiffid_design::Gradient,
        solver: stiffid_design::Solver,
    ) -> [bool; 3] {
        [
            max_evals,
            gradient != stiffid_design::Gradient::default(),
            solver != stiffid_design::Solver::default(),
        ]
    }
}

/// Refuses the options `given` that mean nothing for `purpose` and `method`: the stiffness
/// criterion for a design for the calibration alone ([`Purpose::calibration_only`]), the
/// global search's starts, screening steps and polished starts for any other method, the local
/// searches' settings for a pool (its group is chosen by exchange, no search runs), and a seed
/// for a search from a start group given (nothing is drawn).
///
/// # Errors
/// [`Error::InvalidOption`] naming the option ([`JobOption::Criterion`], [`JobOption::Starts`],
/// [`JobOption::ScreenSteps`], [`JobOption::Polished`], [`JobOption::MaxEvals`],
/// [`JobOption::Gradient`], [`JobOption::Solver`], [`JobOption::Seed`]).
pub fn check_given(purpose: Purpose, method: Method, given: Given) -> Result<()> {
    let refuse = |option, message: &str| {
        Err(Error::InvalidOption {
            option,
            message: message.into(),
        })
    };
    if given.criterion && purpose.calibration_only() {
        return refuse(
            JobOption::Criterion,
            "a stiffness criterion: only with for = stiffness or both (the group is designed for the calibration, by the calibration's criterion)",
        );
    }
    let search = [JobOption::MaxEvals, JobOption::Gradient, JobOption::Solver];
    let mut given_search = given.search.into_iter().zip(search);
    if let Some((_, option)) = given_search.find(|(g, _)| *g && method == Method::Pool) {
        return refuse(
            option,
            "only for a search (from a start group, or global): a pool's group is chosen by exchange, no local search runs",
        );
    }
    if given.seed && given.start && method == Method::Local {
        return refuse(
            JobOption::Seed,
            "only with a random start group, the global search or a pool's exchange runs: the search starts from the group given, nothing is drawn",
        );
    }
    let global = [
        (given.starts, JobOption::Starts),
        (given.screen_steps, JobOption::ScreenSteps),
        (given.polished, JobOption::Polished),
    ];
    match global.into_iter().find(|(g, _)| *g) {
        Some((_, option)) if method != Method::Global => refuse(
            option,
            "only for the global search (local searches from seeded starts)",
        ),
        _ => Ok(()),
    }
}
