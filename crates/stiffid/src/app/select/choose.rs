//! The group chosen by a search or from a pool, the smallest group for a target, and the same
//! search without the cell's checks, as the request asks them
//! ([`stiffid_design::selection::search`]).

use super::{Candidates, Method, Request, Unconstrained};
use crate::app::purpose::Purpose;
use stiffid_core::{Result, Setup};
pub(super) use stiffid_design::selection::search::Found;
use stiffid_design::selection::search::{self, How, Searching};
use stiffid_design::target::TargetOutcome;
use stiffid_design::Goal;

/// How the request chooses its group: from `pool`, or by its method.
pub(super) fn how<'a>(r: &'a Request, pool: Option<&'a Candidates<'a>>) -> How<'a> {
    match (pool, r.method) {
        (Some(p), _) => How::Pool(p, r.restarts),
        (None, Method::Global) => How::Global,
        (None, _) => How::Local(r.start.as_deref()),
    }
}

/// The request's search budget and progress, its stages naming `name`.
pub(super) fn searching<'a>(r: &'a Request, name: &'a str) -> Searching<'a> {
    Searching {
        options: &r.options,
        progress: r.progress,
        name,
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
    let name = name(r, goal);
    search::choose(setup, goal, how(r, pool), n, searching(r, &name))
}

/// The name of what `goal` minimises in the progress' stages.
pub(super) fn name(r: &Request, goal: &Goal) -> String {
    match (r.purpose, goal.calibration) {
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
    }
}

/// The name of a choice.
fn choice_name<C: stiffid_core::common::choice::Choice>(c: C) -> &'static str {
    c.name()
}

/// The smallest group that reaches `pct` ([`search::smallest`]).
pub(super) fn smallest(
    r: &Request,
    pool: Option<&Candidates>,
    pct: f64,
) -> Result<(Found, TargetOutcome)> {
    let name = name(r, &Goal::stiffness(r.criterion));
    let how = how(r, pool);
    search::smallest(r.setup, r.criterion, how, searching(r, &name), pct)
}

/// With cell checks: the same search of `n` postures without them ([`search::unconstrained`]).
pub(super) fn unconstrained(r: &Request, goal: &Goal, n: usize) -> Result<Option<Unconstrained>> {
    let name = name(r, goal);
    search::unconstrained(r.setup, goal, how(r, None), n, searching(r, &name))
}
