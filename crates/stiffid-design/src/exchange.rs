//! The best `n` of `u` candidates for any value of a group: every group enumerated when there
//! are few, else the modified Fedorov exchange (Cook & Nachtsheim 1980, Technometrics 22(3)) from
//! seeded random groups. A pool of postures ([`super::Pool`]) and a registration design
//! ([`crate::registration`]) choose their groups with it; each gives the value of a group of
//! candidate indices (lower is better, `+infinity` for a group that determines nothing).

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use stiffid_core::{common::limits, Result};

/// Most passes of one exchange run (each pass that exchanges nothing ends the run; the value
/// falls strictly at every exchange, so the limit is a guard, not reached in practice).
const MAX_PASSES: usize = 100;

/// How a pool is searched.
#[derive(Debug, Clone, PartialEq)]
pub struct PoolOptions {
    /// Exchange runs from seeded random groups (default 8).
    pub restarts: usize,
    /// Seed of the random groups: run r uses ChaCha8 stream `r` of it (default 1).
    pub seed: u64,
    /// Enumerate every group when there are at most this many (default 100 000); 0 always uses
    /// the exchange algorithm.
    pub enumeration_limit: u64,
}

impl PoolOptions {
    /// Checks every field against its documented limit: `restarts` 1 to
    /// [`limits::MAX_POOL_RESTARTS`], `enumeration_limit` at most [`limits::MAX_ENUMERATION`].
    /// [`Pool::best`](super::Pool::best) calls it.
    ///
    /// # Errors
    /// [`stiffid_core::Error::InvalidField`] naming the field (`PoolOptions.restarts`), the value and the range.
    pub(crate) fn validate(&self) -> Result<()> {
        let restarts = self.restarts as u64;
        limits::check_integer(
            "PoolOptions.restarts",
            restarts,
            1,
            limits::MAX_POOL_RESTARTS,
        )?;
        let limit = self.enumeration_limit;
        limits::check_integer(
            "PoolOptions.enumeration_limit",
            limit,
            0,
            limits::MAX_ENUMERATION,
        )
    }
}

impl Default for PoolOptions {
    fn default() -> Self {
        Self {
            restarts: 8,
            seed: 1,
            enumeration_limit: 100_000,
        }
    }
}

/// How a group was chosen from a pool.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PoolMethod {
    /// Every group was evaluated: the group is the exact optimum.
    Enumeration,
    /// The exchange algorithm: the best of its restarts, a local optimum.
    Exchange,
}

impl PoolMethod {
    /// Its name in documents: `enumeration` or `exchange`.
    pub fn name(self) -> &'static str {
        match self {
            PoolMethod::Enumeration => "enumeration",
            PoolMethod::Exchange => "exchange",
        }
    }
}

/// The group chosen.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Chosen {
    /// Candidate indices, in the order the search left them.
    pub group: Vec<usize>,
    /// Enumeration or exchange.
    pub method: PoolMethod,
    /// Groups evaluated.
    pub evaluations: usize,
}

/// The group of `n` of the candidates `0..u` with the lowest `value`: enumerated (lexicographic
/// order, the first on ties) when there are at most `options.enumeration_limit` groups, else the
/// best of `options.restarts` exchange runs (run `r` starts from a random group drawn with ChaCha8
/// stream `r` of `options.seed`; the lowest run index on ties). The same options give the same
/// group whatever the thread count. `n <= u` and `options` valid ([`PoolOptions::validate`]) are
/// the caller's to check.
pub(crate) fn best(
    u: usize,
    n: usize,
    options: &PoolOptions,
    value: &(dyn Fn(&[usize]) -> f64 + Sync),
) -> Chosen {
    let groups = binomial(u, n);
    if groups <= options.enumeration_limit as u128 {
        return Chosen {
            group: enumerate(u, n, value),
            method: PoolMethod::Enumeration,
            evaluations: groups as usize,
        };
    }
    let runs: Vec<(Vec<usize>, f64, usize)> = (0..options.restarts)
        .into_par_iter()
        .map(|r| {
            let mut rng = ChaCha8Rng::seed_from_u64(options.seed);
            rng.set_stream(r as u64);
            let start = rand::seq::index::sample(&mut rng, u, n).into_vec();
            exchange(u, start, value)
        })
        .collect();
    let evaluations = runs.iter().map(|r| r.2).sum();
    let best = runs
        .into_iter()
        .reduce(|best, run| if run.1 < best.1 { run } else { best })
        .expect("at least one restart");
    Chosen {
        group: best.0,
        method: PoolMethod::Exchange,
        evaluations,
    }
}

/// The best of every group of `n` of `0..u` (lexicographic order, the first on ties).
fn enumerate(u: usize, n: usize, value: &dyn Fn(&[usize]) -> f64) -> Vec<usize> {
    let mut group: Vec<usize> = (0..n).collect();
    let mut best = (group.clone(), value(&group));
    while next_combination(&mut group, u) {
        let v = value(&group);
        if v < best.1 {
            best = (group.clone(), v);
        }
    }
    best.0
}

/// One modified Fedorov run from `group`: each member in turn is exchanged for the candidate
/// that lowers the value most, until a whole pass exchanges none. Its end group, value and
/// evaluations.
fn exchange(
    u: usize,
    mut group: Vec<usize>,
    value: &dyn Fn(&[usize]) -> f64,
) -> (Vec<usize>, f64, usize) {
    let mut in_group = vec![false; u];
    group.iter().for_each(|&k| in_group[k] = true);
    let mut current = value(&group);
    let mut evaluations = 1;
    for _ in 0..MAX_PASSES {
        let mut exchanged = false;
        for slot in 0..group.len() {
            let out = group[slot];
            let mut best: Option<(usize, f64)> = None;
            for candidate in (0..u).filter(|&j| !in_group[j]) {
                group[slot] = candidate;
                let v = value(&group);
                evaluations += 1;
                if improves(v, best.map_or(current, |b| b.1)) {
                    best = Some((candidate, v));
                }
            }
            group[slot] = out;
            if let Some((candidate, v)) = best {
                in_group[out] = false;
                in_group[candidate] = true;
                group[slot] = candidate;
                current = v;
                exchanged = true;
            }
        }
        if !exchanged {
            break;
        }
    }
    (group, current, evaluations)
}

/// Whether `v` is lower than `than` by more than rounding (so an exchange loop cannot cycle).
pub(crate) fn improves(v: f64, than: f64) -> bool {
    v < than && (than.is_infinite() || than - v > 1e-12 * than.abs())
}

/// The next combination of `group.len()` of `0..u` in lexicographic order; false after the last.
pub(crate) fn next_combination(group: &mut [usize], u: usize) -> bool {
    let n = group.len();
    let Some(i) = (0..n).rev().find(|&i| group[i] < u - n + i) else {
        return false;
    };
    group[i] += 1;
    for k in i + 1..n {
        group[k] = group[k - 1] + 1;
    }
    true
}

/// `C(u, n)`, `u128::MAX` when larger.
pub(crate) fn binomial(u: usize, n: usize) -> u128 {
    if n > u {
        return 0;
    }
    // C(u, k + 1) = C(u, k) (u - k) / (k + 1), exact in integers.
    (0..n.min(u - n))
        .try_fold(1u128, |c, k| {
            c.checked_mul((u - k) as u128).map(|p| p / (k as u128 + 1))
        })
        .unwrap_or(u128::MAX)
}
