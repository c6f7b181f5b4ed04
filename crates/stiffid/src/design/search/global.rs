//! Global search: local searches in parallel from seeded space-filling starts, the best kept.

use super::constraints::violation;
use super::local::{check_count, infeasible, local_in};
use super::sample::group_from_stream;
use super::{SearchOptions, SearchOutcome};
use crate::cell::Checker;
use crate::design::Criterion;
use crate::progress::Progress;
use crate::setup::Setup;
use crate::{Error, Result};
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Minimises `criterion` over groups of `postures` postures by [`SearchOptions::starts`] local
/// searches ([`local`], each with the budget [`SearchOptions::max_evals`]) run in parallel (rayon)
/// from Latin-hypercube start groups (as [`super::random_group`], each posture redrawn until it
/// passes the cell's checks, at most [`super::CONSTRAINT_TRIES`] times; start s uses stream
/// `s + 1` of [`SearchOptions::seed`]), and keeps the best (the least violating first; the lowest
/// start index on ties).
///
/// Every start is seeded on its own and the results are compared in start order, so the same
/// options give the same postures whatever the thread count. `progress` receives
/// [`Progress::advance`] with the number of local searches finished so far, after each one (from
/// the worker threads); the caller begins and ends the stage.
///
/// # Errors
/// [`Error::InvalidField`] for fewer than 2 postures, no start, or the `test-pose` criterion on a
/// setup without test postures; [`Error::Infeasible`] naming the check failed by the most postures
/// of the starts' results when none of them passes every check.
pub fn global(
    setup: &Setup,
    criterion: Criterion,
    postures: usize,
    options: &SearchOptions,
    progress: &dyn Progress,
) -> Result<SearchOutcome> {
    check_count(setup, criterion, postures)?;
    if options.starts == 0 {
        return Err(Error::InvalidField {
            field: "starts".into(),
            message: "a global search needs at least 1 start".into(),
        });
    }
    let checker = Checker::new(setup);
    let done = AtomicUsize::new(0);
    let outcomes: Vec<SearchOutcome> = (0..options.starts)
        .into_par_iter()
        .map(|s| {
            let start = group_from_stream(&checker, postures, options.seed, s as u64 + 1);
            let outcome = local_in(&checker, criterion, &start, options);
            progress.advance(done.fetch_add(1, Ordering::Relaxed) + 1);
            outcome
        })
        .collect();
    infeasible(&checker, outcomes.iter())?;
    let evaluations = outcomes.iter().map(|o| o.evaluations).sum();
    let violation =
        |o: &SearchOutcome| -> f64 { o.postures.iter().map(|q| violation(&checker, q)).sum() };
    let best = outcomes
        .into_iter()
        .map(|o| (violation(&o), o))
        .reduce(
            |(bv, best), (v, o)| match v < bv || (v == bv && o.value < best.value) {
                true => (v, o),
                false => (bv, best),
            },
        )
        .expect("at least one start")
        .1;
    Ok(SearchOutcome {
        evaluations,
        ..best
    })
}
