//! The paper's simulation study (Zhang et al. 2021, Section IV-A) and what lies beyond it: groups
//! of postures found by the paper's local searches and by global searches, their Monte Carlo
//! identification at every noise level of the setup (Fig. 8, Table 4), the deflection at the
//! validation postures (Table 5), a check of the start group, and the [`findings`].
//!
//! [`run`] is the whole study as `stiffid reproduce` runs it, the start-group check included.

mod findings;
pub mod observability;
pub mod simulate;
#[cfg(test)]
mod simulate_tests;
mod table4;
mod trials;

pub use findings::{criterion_values, findings, Findings, StartCheck, Versus};
pub use stiffid_core::math::spearman;
pub use table4::paper_table4;
pub use trials::StartTrial;
use trials::{judge, paper_searches};

use crate::study::simulate::{
    monte_carlo_with_predictions, GroupSimulation, Options as SimulationOptions,
};
use crate::{evaluate, global, Criterion, Evaluation, SearchOptions, Solver};
use nalgebra::{Vector3, Vector6};
use rayon::prelude::*;
use stiffid_core::common::progress::{Progress, Tally};
use stiffid_core::observation::stiffness::rope_displacements;
use stiffid_core::setup::Setup;
use stiffid_core::{common::limits, Result};

/// Postures per group (the paper's 6).
pub const POSTURES: usize = 6;

/// Local searches per global search by default: half the search's default (32). On the paper
/// setup (seed 1) `relative-a` then equals what 32 starts find to 4 digits, at half the time.
pub const DEFAULT_STARTS: usize = 16;

/// Start groups of the start-group check by default.
pub const DEFAULT_TRIALS: usize = 20;

/// What to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Options {
    /// Monte Carlo runs per group and noise level (the paper: 200). At least 1.
    pub runs: usize,
    /// Seed of the start group, the global searches' starts and the noise.
    pub seed: u64,
    /// Local searches per global search. At least 1.
    pub starts: usize,
    /// Start groups of the start-group check (seeds `seed`, `seed + 1`, ...); 0 skips it.
    pub trials: usize,
    /// The SQP of every search (default [`Solver::default`]).
    pub solver: Solver,
}

impl Default for Options {
    /// 200 runs, seed 1, [`DEFAULT_STARTS`] starts, [`DEFAULT_TRIALS`] trials, the default
    /// solver.
    fn default() -> Self {
        Self {
            runs: 200,
            seed: 1,
            starts: DEFAULT_STARTS,
            trials: DEFAULT_TRIALS,
            solver: Solver::default(),
        }
    }
}

/// How a group was obtained.
#[derive(Debug, Clone, PartialEq)]
pub enum Origin {
    /// The seeded Latin-hypercube start group (Group 1).
    Start,
    /// SQP from Group 1 on a criterion (the paper's Groups 2 and 3).
    Local(Criterion),
    /// The best of `starts` SQP searches from seeded Latin-hypercube starts (beyond the paper).
    Global(Criterion, usize),
}

impl Origin {
    /// The criterion searched, if any.
    pub fn criterion(&self) -> Option<Criterion> {
        match self {
            Origin::Start => None,
            Origin::Local(c) | Origin::Global(c, _) => Some(*c),
        }
    }
}

/// One group of postures and everything measured on it.
#[derive(Debug, Clone)]
pub struct Group {
    /// File-safe name, e.g. `group3-zhang2021`.
    pub name: String,
    /// Short label, e.g. `Group 3 (zhang2021, local)`.
    pub title: String,
    /// How it was obtained.
    pub origin: Origin,
    /// Axis angles, rad.
    pub postures: Vec<Vector6<f64>>,
    /// Every design criterion, and the first-order predicted deviation rates (computed once; the
    /// simulation holds a copy).
    pub evaluation: Evaluation,
    /// Criterion evaluations the search spent (0 for the start group).
    pub evaluations: usize,
    /// The Monte Carlo identification.
    pub simulation: GroupSimulation,
    /// `|delta(k_mean) - delta(k_true)|` (m) of every measuring point at every test posture, with the
    /// group's mean identified stiffness at [`Study::validation_level`]: \[test posture\]\[point\].
    pub validation_error: Vec<Vec<f64>>,
}

impl Group {
    /// Mean over noise levels and joints of the mean deviation rate, percent: one number to rank
    /// groups by (the paper's "average rates of deviation", Fig. 8).
    pub fn average_deviation_pct(&self) -> f64 {
        average(&self.simulation.mean_deviation_pct)
    }

    /// The same mean of the first-order predicted deviation rate, percent.
    pub fn predicted_average_pct(&self) -> f64 {
        self.evaluation.predicted_average_pct()
    }
}

/// The mean of rates [levels][6]; 0 for none.
fn average(rates: &[[f64; 6]]) -> f64 {
    rates.iter().flatten().sum::<f64>() / (6 * rates.len()).max(1) as f64
}

/// The whole study.
#[derive(Debug, Clone)]
pub struct Study {
    /// The setup (true stiffness = its nominal stiffness).
    pub setup: Setup,
    /// Seed of everything random.
    pub seed: u64,
    /// Monte Carlo runs per group and level.
    pub runs: usize,
    /// Groups: 1 start, 2 classical, 3 zhang2021, then the global searches.
    pub groups: Vec<Group>,
    /// The noise level (index) whose mean identified stiffness is validated: the one nearest
    /// multiple 1 (the paper's level 2).
    pub validation_level: usize,
    /// True displacement (m) of every measuring point at every test posture: \[test posture\]\[point\].
    pub test_deflection: Vec<Vec<Vector3<f64>>>,
    /// The start-group check: the paper's local searches from `trials` start groups.
    pub trials: Vec<StartTrial>,
    /// Wall time of [`run`], s (a front end may add its own work to it).
    pub elapsed_s: f64,
}

/// Runs the study on a setup (its nominal stiffness is the true one): Group 1 a seeded random
/// start group ([`crate::random_group`]); Groups 2 and 3 the paper's local searches on
/// `classical` and `zhang2021` from it; Groups 4 and 5 global searches on `relative-a` and
/// `d-optimal` ([`global`], `options.starts` starts); the start-group check ([`StartTrial`];
/// its first start group is Group 1); then the Monte Carlo identification of every group at every
/// noise level ([`crate::study::simulate`]) and the validation-posture deflections with each group's mean
/// identified stiffness. Parallel (rayon): every search runs in one pool, so the two cores stay
/// busy; the same options give the same study whatever the thread count.
///
/// `progress` hears two stages: `searches` (one unit per local search and per global search's
/// start) and `Monte Carlo identification` (one unit per run: groups x levels x runs).
///
/// # Errors
/// [`stiffid_core::Error::InvalidField`] for `runs`, `starts` or `trials` outside their limits
/// ([`limits::MAX_RUNS`], [`limits::MAX_STARTS`], [`limits::MAX_TRIALS`]; `trials` may be 0),
/// and for a `seed` so large that the trials' seeds (`seed + 1`, ...) would pass `u64::MAX`;
/// [`stiffid_core::Error::MissingField`] for a setup without a nominal stiffness or a characteristic
/// length; the errors of the searches and of [`crate::study::simulate::monte_carlo`] (for example
/// [`stiffid_core::Error::Unidentifiable`] for a group that cannot identify every joint).
///
/// # Examples
/// A small study on the paper's setup: 5 runs, 1 start per global search, no start-group check.
/// ```
/// use stiffid_design::study::{self, Options};
/// let setup = stiffid_core::setup::builtin("zhang2021-comau-nj165")?;
/// let options = Options { runs: 5, seed: 1, starts: 1, trials: 0, ..Options::default() };
/// let s = study::run(&setup, &options, &())?;
/// assert_eq!(s.groups.len(), 5);
/// assert_eq!(s.groups[2].name, "group3-zhang2021");
/// let f = study::findings(&s);
/// assert!(f.prediction_error.is_finite());
/// # Ok::<(), stiffid_core::Error>(())
/// ```
pub fn run(setup: &Setup, options: &Options, progress: &dyn Progress) -> Result<Study> {
    let started = std::time::Instant::now();
    let k_true = setup.try_nominal_stiffness("the study (the true stiffness it simulates)")?;
    setup.try_characteristic_length("the study (criteria classical and zhang2021)")?;
    let counts = [
        ("runs", options.runs, 1, limits::MAX_RUNS),
        ("starts", options.starts, 1, limits::MAX_STARTS),
        ("trials", options.trials, 0, limits::MAX_TRIALS),
    ];
    for (field, value, min, max) in counts {
        limits::check_integer(field, value as u64, min, max)?;
    }
    let end = options.seed.checked_add(options.trials as u64);
    end.ok_or_else(|| stiffid_core::Error::InvalidField {
        field: "seed".into(),
        message: format!(
            "{}: expected at most {} (u64::MAX less the {} trials, whose seeds follow it)",
            options.seed,
            u64::MAX - options.trials as u64,
            options.trials
        ),
    })?;
    let search = SearchOptions {
        starts: options.starts,
        seed: options.seed,
        solver: options.solver,
        ..SearchOptions::default()
    };
    let (found, trials) = search_all(setup, options, &search, progress)?;
    let evaluations: Vec<Evaluation> = found.iter().map(|(_, p, _)| evaluate(setup, p)).collect();
    let sims = monte_carlo_with_predictions(
        setup,
        &found.iter().map(|(_, p, _)| p.clone()).collect::<Vec<_>>(),
        &evaluations
            .iter()
            .map(|e| e.predicted_deviation_pct.clone())
            .collect::<Vec<_>>(),
        &SimulationOptions {
            runs: options.runs,
            seed: options.seed,
        },
        progress,
    )?;
    let validation_level = nearest_level(&setup.noise().levels, 1.0);
    let test_deflection: Vec<Vec<Vector3<f64>>> = setup
        .test_postures()
        .iter()
        .map(|q| rope_displacements(setup, &setup.robot().frames(q), k_true))
        .collect();
    let groups = found
        .into_iter()
        .zip(evaluations.into_iter().zip(sims))
        .enumerate()
        .map(
            |(i, ((origin, postures, evaluations), (evaluation, simulation)))| {
                let k = simulation.mean_stiffness[validation_level];
                Group {
                    name: group_name(i, &origin),
                    title: group_title(i, &origin),
                    evaluation,
                    validation_error: validation_error(setup, &test_deflection, &k),
                    origin,
                    postures,
                    evaluations,
                    simulation,
                }
            },
        )
        .collect();
    Ok(Study {
        setup: setup.clone(),
        seed: options.seed,
        runs: options.runs,
        groups,
        validation_level,
        test_deflection,
        trials,
        elapsed_s: started.elapsed().as_secs_f64(),
    })
}

/// A group found: how, its postures, the criterion evaluations spent.
type Found = (Origin, Vec<Vector6<f64>>, usize);

/// The start group, the paper's two local searches from it and the two global searches.
/// Every search of the study in one parallel pool, so that both cores stay busy to the end: the
/// paper's two local searches from the start group of each trial's seed (the first is Group 1,
/// its searches Groups 2 and 3; with no trials, Group 1's alone) and the two global searches
/// (Groups 4 and 5). Each search is deterministic, so the result does not depend on the schedule.
/// `progress` hears one stage, one unit per local search and per global search's start.
fn search_all(
    setup: &Setup,
    options: &Options,
    search: &SearchOptions,
    progress: &dyn Progress,
) -> Result<(Vec<Found>, Vec<StartTrial>)> {
    // The caller checked that `seed + trials` does not overflow.
    let seeds: Vec<u64> = (0..options.trials.max(1) as u64)
        .map(|i| options.seed + i)
        .collect();
    let global_criteria = [Criterion::RelativeA, Criterion::DOptimal];
    progress.begin(
        "searches",
        2 * seeds.len() + global_criteria.len() * options.starts,
    );
    let tally = Tally::new(progress);
    let (paper, globals) = rayon::join(
        || paper_searches(setup, &seeds, search, &tally),
        || {
            global_criteria
                .into_par_iter()
                .map(|c| global(setup, c, POSTURES, search, &tally.part()))
                .collect::<Result<Vec<_>>>()
        },
    );
    progress.end();
    let (paper, globals) = (paper?, globals?);
    let trials = match options.trials {
        0 => Vec::new(),
        _ => judge(setup, &seeds, &paper),
    };
    let (start, [classical, zhang]) = paper.into_iter().next().expect("at least one seed");
    let mut found = vec![(Origin::Start, start, 0)];
    for (criterion, o) in [Criterion::Classical, Criterion::Zhang2021]
        .into_iter()
        .zip([classical, zhang])
    {
        found.push((Origin::Local(criterion), o.postures, o.evaluations));
    }
    for (criterion, o) in global_criteria.into_iter().zip(globals) {
        let origin = Origin::Global(criterion, options.starts);
        found.push((origin, o.postures, o.evaluations));
    }
    Ok((found, trials))
}

fn group_name(i: usize, origin: &Origin) -> String {
    match origin.criterion() {
        None => format!("group{}-start", i + 1),
        Some(c) => format!("group{}-{c}", i + 1),
    }
}

fn group_title(i: usize, origin: &Origin) -> String {
    match origin {
        Origin::Start => format!("Group {} (start)", i + 1),
        Origin::Local(c) => format!("Group {} ({c}, local)", i + 1),
        Origin::Global(c, _) => format!("Group {} ({c}, global)", i + 1),
    }
}

/// The index of the level multiple nearest `m`.
fn nearest_level(levels: &[f64], m: f64) -> usize {
    (0..levels.len())
        .min_by(|&a, &b| (levels[a] - m).abs().total_cmp(&(levels[b] - m).abs()))
        .unwrap_or(0)
}

fn validation_error(setup: &Setup, truth: &[Vec<Vector3<f64>>], k: &Vector6<f64>) -> Vec<Vec<f64>> {
    setup
        .test_postures()
        .iter()
        .zip(truth)
        .map(|(q, t)| {
            let d = rope_displacements(setup, &setup.robot().frames(q), k);
            d.iter().zip(t).map(|(a, b)| (a - b).norm()).collect()
        })
        .collect()
}

#[cfg(test)]
pub(crate) mod observability_tests;
