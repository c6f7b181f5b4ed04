//! Monte Carlo simulation of the identification experiment (Zhang et al. 2021, Section IV-A,
//! Fig. 4, Fig. 8, Tables 3-4).
//!
//! For each group of postures: the exact translation of every measuring point under the setup's
//! rope-mass load and its true (nominal) stiffness ([`crate::stiffness::rope_displacements`]); white
//! Gaussian noise of variance `sigma^2 m` on every coordinate, for each level multiple `m` of the
//! setup (Table 3); the compliances identified by least squares (Eq. 13-14) with the QR factor of
//! `Psi`, computed once per group and reused by every run; the deviation rate
//! `|k_identified - k_true| / k_true` of every joint. Mean and standard deviation over the runs per
//! group, level and joint, beside the first-order prediction of [`crate::design::criteria`].
//!
//! Every run draws its noise from its own generator, seeded from `(seed, group, level, run)`, and the
//! sums are taken in run order, so the result is the same whatever the number of threads.

use crate::design::criteria::evaluate;
use crate::lsq::Factor;
use crate::observation::rope_observation_matrix;
use crate::setup::Setup;
use crate::stiffness::rope_displacements;
use crate::{limits, Error, Result};
use nalgebra::{DVector, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;
use rayon::prelude::*;

/// How many runs, and the seed of the noise.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Options {
    /// Monte Carlo runs per group and noise level (the paper: 200). 1 to [`limits::MAX_RUNS`].
    pub runs: usize,
    /// Seed of the noise; the result depends on nothing else.
    pub seed: u64,
}

impl Default for Options {
    /// 200 runs (the paper's), seed 1.
    fn default() -> Self {
        Self { runs: 200, seed: 1 }
    }
}

/// The simulated identification of one group of postures. Every `Vec` has one entry per noise
/// level of the setup, in the setup's order; every array one entry per joint.
#[derive(Debug, Clone, PartialEq)]
pub struct GroupSimulation {
    /// Mean deviation rate `|k_id - k_true| / k_true` over the runs, percent.
    pub mean_deviation_pct: Vec<[f64; 6]>,
    /// Sample standard deviation (divisor `runs - 1`; 0 for one run) of the deviation rate, percent.
    pub std_deviation_pct: Vec<[f64; 6]>,
    /// The first-order prediction of the mean deviation rate, percent
    /// ([`crate::design::criteria::predicted_deviation_pct`]).
    pub predicted_deviation_pct: Vec<[f64; 6]>,
    /// Mean identified stiffness over the runs, Nm/rad.
    pub mean_stiffness: Vec<Vector6<f64>>,
}

/// One group made ready for the runs: its factor and exact displacements.
struct Prepared {
    factor: Factor,
    exact: DVector<f64>,
}

/// Simulates the identification with every group of postures (axis angles, rad) at every noise level
/// of the setup, `options.runs` times each, beside the first-order prediction of each group
/// ([`evaluate`]).
///
/// # Errors
/// [`Error::InvalidField`] for `runs` outside 1 to [`limits::MAX_RUNS`]; [`Error::MissingField`]
/// for a setup without a nominal stiffness (the true stiffness of the simulation); the errors of
/// [`Factor::try_new`] (for example [`Error::Unidentifiable`]) for a group whose observation
/// matrix cannot identify every joint.
pub fn monte_carlo(
    setup: &Setup,
    groups: &[Vec<Vector6<f64>>],
    options: &Options,
) -> Result<Vec<GroupSimulation>> {
    check_runs(options)?;
    let predicted: Vec<Vec<[f64; 6]>> = groups
        .iter()
        .map(|g| evaluate(setup, g).predicted_deviation_pct)
        .collect();
    monte_carlo_with_predictions(setup, groups, &predicted, options)
}

/// [`monte_carlo`] with the first-order predictions already at hand (for example from the groups'
/// [`crate::design::Evaluation`]s): `predicted[g]` is group `g`'s
/// [`crate::design::Evaluation::predicted_deviation_pct`], percent, \[levels\]\[6\], copied into its
/// result as is.
///
/// # Errors
/// As [`monte_carlo`]; [`Error::InvalidField`] when `predicted` does not hold one entry per group.
pub fn monte_carlo_with_predictions(
    setup: &Setup,
    groups: &[Vec<Vector6<f64>>],
    predicted: &[Vec<[f64; 6]>],
    options: &Options,
) -> Result<Vec<GroupSimulation>> {
    check_runs(options)?;
    let k_true = setup.try_nominal_stiffness("the simulation (the true stiffness)")?;
    if predicted.len() != groups.len() {
        return Err(Error::InvalidField {
            field: "predicted".into(),
            message: format!(
                "expected one prediction per group ({}), got {}",
                groups.len(),
                predicted.len()
            ),
        });
    }
    let prepared = groups
        .iter()
        .map(|g| prepare(setup, g, k_true))
        .collect::<Result<Vec<_>>>()?;
    let runs = options.runs;
    Ok(prepared
        .iter()
        .zip(predicted)
        .enumerate()
        .map(|(g, (group, predicted))| {
            let rates = group_runs(setup, group, g, options);
            summarise(k_true, &rates, runs, predicted.clone())
        })
        .collect())
}

/// The identified stiffness of every run of group `g`, level-major: one group at a time, so the
/// memory held is `levels x runs` results whatever the number of groups.
fn group_runs(setup: &Setup, group: &Prepared, g: usize, options: &Options) -> Vec<[f64; 6]> {
    let runs = options.runs;
    (0..setup.noise().levels.len() * runs)
        .into_par_iter()
        .map(|i| {
            let (l, r) = (i / runs, i % runs);
            let sigma = (setup.noise().variance * setup.noise().levels[l]).sqrt();
            let mut rng = ChaCha8Rng::seed_from_u64(run_seed(options.seed, g, l, r));
            identify_once(group, sigma, &mut rng)
        })
        .collect()
}

fn check_runs(options: &Options) -> Result<()> {
    limits::check_integer("runs", options.runs as u64, 1, limits::MAX_RUNS)
}

fn prepare(setup: &Setup, postures: &[Vector6<f64>], k_true: &Vector6<f64>) -> Result<Prepared> {
    let factor = Factor::try_new(rope_observation_matrix(setup, postures))?;
    let exact: Vec<f64> = postures
        .iter()
        .flat_map(|q| rope_displacements(setup, &setup.robot().frames(q), k_true))
        .flat_map(|d| [d.x, d.y, d.z])
        .collect();
    Ok(Prepared {
        factor,
        exact: DVector::from_vec(exact),
    })
}

/// Identified stiffness (Nm/rad) of one run: the exact displacements plus noise of standard
/// deviation `sigma` (m) on every coordinate, solved with the group's factor.
fn identify_once(group: &Prepared, sigma: f64, rng: &mut ChaCha8Rng) -> [f64; 6] {
    let noisy = group
        .exact
        .map(|d| d + sigma * rng.sample::<f64, _>(StandardNormal));
    let h = group.factor.solve(&noisy);
    std::array::from_fn(|j| 1.0 / h[j])
}

/// The seed of run `run` at level `level` of group `group`: the four numbers mixed by SplitMix64
/// steps, so neighbouring runs get unrelated streams.
pub fn run_seed(seed: u64, group: usize, level: usize, run: usize) -> u64 {
    [group as u64, level as u64, run as u64]
        .into_iter()
        .fold(splitmix64(seed), |acc, x| splitmix64(acc ^ x))
}

fn splitmix64(x: u64) -> u64 {
    let mut z = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Mean and standard deviation of the deviation rates, and the mean stiffness, per level, from the
/// identified stiffness of every run of one group (level-major, `runs` per level).
fn summarise(
    k_true: &Vector6<f64>,
    stiffness: &[[f64; 6]],
    runs: usize,
    predicted: Vec<[f64; 6]>,
) -> GroupSimulation {
    let mut out = GroupSimulation {
        mean_deviation_pct: Vec::new(),
        std_deviation_pct: Vec::new(),
        predicted_deviation_pct: predicted,
        mean_stiffness: Vec::new(),
    };
    for level in stiffness.chunks(runs) {
        let n = level.len() as f64;
        let rate = |k: &[f64; 6], j: usize| 100.0 * (k[j] - k_true[j]).abs() / k_true[j];
        let mean: [f64; 6] =
            std::array::from_fn(|j| level.iter().map(|k| rate(k, j)).sum::<f64>() / n);
        let std = std::array::from_fn(|j| match level.len() {
            1 => 0.0,
            _ => (level
                .iter()
                .map(|k| (rate(k, j) - mean[j]).powi(2))
                .sum::<f64>()
                / (n - 1.0))
                .sqrt(),
        });
        let k_mean = Vector6::from_fn(|j, _| level.iter().map(|k| k[j]).sum::<f64>() / n);
        out.mean_deviation_pct.push(mean);
        out.std_deviation_pct.push(std);
        out.mean_stiffness.push(k_mean);
    }
    out
}
