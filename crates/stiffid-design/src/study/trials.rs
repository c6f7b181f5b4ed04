//! The start-group check: does the paper's result depend on its start group? The paper's two local
//! searches from many seeded start groups, each group judged by its first-order prediction.

use super::POSTURES;
use crate::{evaluate, local, random_group, Criterion, SearchOptions, SearchOutcome};
use nalgebra::Vector6;
use rayon::prelude::*;
use stiffid_core::common::progress::Tally;
use stiffid_core::setup::Setup;
use stiffid_core::Result;

/// The paper's two local searches from one seeded start group, judged by the first-order
/// predicted average deviation rate (mean over levels and joints, %; on the paper setup within a
/// few percent of the Monte Carlo mean).
#[derive(Debug, Clone, PartialEq)]
pub struct StartTrial {
    /// Seed of the start group ([`random_group`]).
    pub seed: u64,
    /// Predicted average deviation rate, %: start group, `classical` local, `zhang2021` local.
    pub predicted_average_pct: [f64; 3],
}

impl StartTrial {
    /// Whether the `zhang2021` group beats both the start and the `classical` group.
    pub fn zhang_beats_both(&self) -> bool {
        let [start, classical, zhang] = self.predicted_average_pct;
        zhang < start && zhang < classical
    }
}

fn predicted_average_pct(setup: &Setup, postures: &[Vector6<f64>]) -> f64 {
    evaluate(setup, postures).predicted_average_pct()
}

/// The paper's two local searches, in the order of [`PaperSearches`].
const PAPER: [Criterion; 2] = [Criterion::Classical, Criterion::Zhang2021];

/// The start group of a seed and the outcomes of the paper's `classical` and `zhang2021` local
/// searches from it.
pub(super) type PaperSearches = (Vec<Vector6<f64>>, [SearchOutcome; 2]);

/// The paper's two local searches from the start group of every seed ([`random_group`]), all in
/// one parallel pool of searches (each is deterministic, so the result does not depend on the
/// schedule or the thread count); `tally` hears one unit per search.
pub(super) fn paper_searches(
    setup: &Setup,
    seeds: &[u64],
    search: &SearchOptions,
    tally: &Tally,
) -> Result<Vec<PaperSearches>> {
    let mut outcomes = (0..PAPER.len() * seeds.len())
        .into_par_iter()
        .map(|i| {
            let start = random_group(setup, POSTURES, seeds[i / PAPER.len()]);
            let outcome = local(setup, PAPER[i % PAPER.len()], &start, search);
            tally.add(1);
            outcome
        })
        .collect::<Result<Vec<_>>>()?
        .into_iter();
    Ok(seeds
        .iter()
        .map(|&seed| {
            let pair = [(); 2].map(|()| outcomes.next().expect("two searches per seed"));
            (random_group(setup, POSTURES, seed), pair)
        })
        .collect())
}

/// The trials of `seeds` from their [`paper_searches`].
pub(super) fn judge(setup: &Setup, seeds: &[u64], searches: &[PaperSearches]) -> Vec<StartTrial> {
    seeds
        .par_iter()
        .zip(searches)
        .map(|(&seed, (start, [classical, zhang]))| StartTrial {
            seed,
            predicted_average_pct: [start, &classical.postures, &zhang.postures]
                .map(|group| predicted_average_pct(setup, group)),
        })
        .collect()
}
