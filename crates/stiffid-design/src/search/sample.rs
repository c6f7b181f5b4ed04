//! Seeded, space-filling start groups within the setup's bounds (and cell constraints).

use super::constraints::{most_failed, violation};
use super::local::infeasible_error;
use nalgebra::Vector6;
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use stiffid_core::cell::Checker;
use stiffid_core::setup::Setup;
use stiffid_core::Result;

/// Uniform redraws of a posture that fails the cell's checks before the least violating draw is
/// kept.
pub(crate) const CONSTRAINT_TRIES: usize = 1000;

/// Uniform postures a global search draws before it starts, to stop at once when none of them
/// passes the cell's checks.
const PROBE_DRAWS: usize = 2000;

/// `Ok` if one of 2000 (`PROBE_DRAWS`) uniform postures within the bounds (stream `u64::MAX` of
/// `seed`) passes every check of `checker`, or if it constrains nothing.
///
/// # Errors
/// [`stiffid_core::Error::Infeasible`] naming the check failed by the most draws and the setup fields
/// that decide it, when none passes: a search would spend its whole budget and find nothing.
pub(super) fn check_some_feasible(checker: &Checker, seed: u64) -> Result<()> {
    if !checker.constrains() {
        return Ok(());
    }
    let setup = checker.setup();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(u64::MAX);
    let draws: Vec<Vector6<f64>> = (0..PROBE_DRAWS)
        .map(|_| {
            Vector6::from_fn(|a, _| {
                rng.random_range(setup.bounds().lower[a]..=setup.bounds().upper[a])
            })
        })
        .collect();
    if draws.iter().any(|q| checker.violation(q) == 0.0) {
        return Ok(());
    }
    let (kind, failed, postures) =
        most_failed(checker, std::iter::once(draws.as_slice())).expect("every draw fails a check");
    Err(infeasible_error(checker, kind, failed, postures))
}

/// A seeded group of `n` postures (axis angles, rad) within the setup's bounds: a Latin hypercube
/// (each axis's range cut into `n` equal strata, every posture in a different stratum of every
/// axis, uniform within the stratum), so the group spreads over the whole box.
///
/// A posture that fails the cell's checks ([`stiffid_core::cell::Checker`]: floor, obstacles,
/// self-collision, rope, line of sight, `[constraints]`) is redrawn uniformly in the box, up to
/// 1000 times (rejection sampling); if no draw passes, the least violating is kept (the search then
/// moves toward feasibility).
///
/// The same `(setup, n, seed)` gives the same group on every machine: ChaCha8 seeded with `seed`,
/// stream 0 ([`super::global`] uses streams 1, 2, ... for its starts).
pub fn random_group(setup: &Setup, n: usize, seed: u64) -> Vec<Vector6<f64>> {
    group_from_stream(&Checker::new(setup), n, seed, 0)
}

/// [`random_group`] from stream `stream` of the seed.
pub(super) fn group_from_stream(
    checker: &Checker,
    n: usize,
    seed: u64,
    stream: u64,
) -> Vec<Vector6<f64>> {
    let setup = checker.setup();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(stream);
    let (lower, upper) = (&setup.bounds().lower, &setup.bounds().upper);
    let strata: Vec<Vec<usize>> = (0..6)
        .map(|_| {
            let mut s: Vec<usize> = (0..n).collect();
            s.shuffle(&mut rng);
            s
        })
        .collect();
    let mut group: Vec<Vector6<f64>> = (0..n)
        .map(|i| {
            Vector6::from_fn(|a, _| {
                let u = (strata[a][i] as f64 + rng.random::<f64>()) / n as f64;
                lower[a] + u * (upper[a] - lower[a])
            })
        })
        .collect();
    if checker.constrains() {
        for q in group.iter_mut() {
            make_feasible(checker, q, &mut rng);
        }
    }
    group
}

fn make_feasible(checker: &Checker, q: &mut Vector6<f64>, rng: &mut ChaCha8Rng) {
    let setup = checker.setup();
    let mut worst = violation(checker, q);
    for _ in 0..CONSTRAINT_TRIES {
        if worst <= 0.0 {
            return;
        }
        let candidate = Vector6::from_fn(|a, _| {
            rng.random_range(setup.bounds().lower[a]..=setup.bounds().upper[a])
        });
        let v = violation(checker, &candidate);
        if v < worst {
            worst = v;
            *q = candidate;
        }
    }
}
