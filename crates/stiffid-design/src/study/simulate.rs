//! Monte Carlo simulation of the identification experiment (Zhang et al. 2021, Section IV-A,
//! Fig. 4, Fig. 8, Tables 3-4).
//!
//! For each group of postures: the exact translation of every measuring point under the setup's
//! rope-mass load and its true (nominal) stiffness ([`stiffid_core::observation::stiffness::rope_displacements`]); white
//! Gaussian noise of variance `sigma^2 m` on every coordinate, for each level multiple `m` of the
//! setup (Table 3); the compliances identified by least squares (Eq. 13-14) with the QR factor of
//! `Psi`, computed once per group and reused by every run; the deviation rate
//! `|k_identified - k_true| / k_true` of every joint. Mean and standard deviation over the runs per
//! group, level and joint, beside the first-order prediction of [`crate::criteria`].
//!
//! With load steps (`[loading] steps_n`), every run draws each coordinate's unloaded reading and
//! its reading at every step with the noise, and solves the least squares over every step's rows
//! through the displacement at the rope load they reduce to exactly ([`stiffid_core::setup::load_steps`]).
//!
//! With virtual springs in the setup's model ([`stiffid_core::model`]) the truth is the nominal compliance
//! of every parameter, the exact displacements are `Psi h_true` (one column per parameter,
//! [`rope_observation_matrix`]), every run identifies every parameter by the Householder QR of that
//! `Psi`, and each virtual spring gets its deviation rates and first-order prediction beside the
//! drives' ([`GroupSimulation`]'s `spring_*` fields).
//!
//! Every run draws its noise from its own generator, seeded from `(seed, group, level, run)`, and the
//! sums are taken in run order, so the result is the same whatever the number of threads.

use crate::evaluate;
use stiffid_core::common::progress::{Progress, Tally};
use stiffid_core::math::lsq::Factor;
use stiffid_identify::svd::identifiability;

use nalgebra::{DMatrix, DVector, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;
use rayon::prelude::*;
use stiffid_core::observation::rope_observation_matrix;
use stiffid_core::observation::stiffness::rope_displacements;
use stiffid_core::setup::load_steps::StepWeights;
use stiffid_core::setup::Setup;
use stiffid_core::{common::limits, Error, Result};

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
    /// ([`crate::criteria::predicted_deviation_pct`]).
    pub predicted_deviation_pct: Vec<[f64; 6]>,
    /// Mean identified stiffness over the runs, Nm/rad.
    pub mean_stiffness: Vec<Vector6<f64>>,
    /// Per level, the mean deviation rate of each virtual spring of the model, percent, in the
    /// model's order (empty rows for the drives alone).
    pub spring_mean_deviation_pct: Vec<Vec<f64>>,
    /// Per level, the sample standard deviation of each virtual spring's deviation rate, percent.
    pub spring_std_deviation_pct: Vec<Vec<f64>>,
    /// Per level, each virtual spring's first-order predicted mean deviation rate, percent:
    /// `100 sqrt(2/pi) sqrt(m) s_j`, `s_j` its [`crate::Evaluation::spring_relative_std`].
    pub spring_predicted_deviation_pct: Vec<Vec<f64>>,
    /// Per level, each virtual spring's mean identified stiffness, SI (Nm/rad for a rotation, N/m
    /// for a translation).
    pub spring_mean_stiffness: Vec<Vec<f64>>,
}

/// How a group's runs are solved: the QR factor of the drives' `Psi`, or of a model's.
enum Solver {
    /// The six drives ([`Factor`], boxed: it is large beside the model's two handles).
    Drives(Box<Factor>),
    /// Any number of parameters: `Q` (m x n) and `R` (n x n) of the Householder QR of `Psi`.
    Model(DMatrix<f64>, DMatrix<f64>),
}

/// One group made ready for the runs: its factor and exact displacements.
struct Prepared {
    solver: Solver,
    exact: DVector<f64>,
}

/// The truth of the simulation: the setup's nominal stiffness of every parameter.
struct Truth {
    /// The drives', Nm/rad.
    drives: Vector6<f64>,
    /// Every parameter's compliance (drives, then virtual springs), SI.
    h: DVector<f64>,
}

/// Simulates the identification with every group of postures (axis angles, rad) at every noise level
/// of the setup, `options.runs` times each, beside the first-order prediction of each group
/// ([`evaluate`]).
///
/// # Errors
/// [`Error::InvalidField`] for `runs` outside 1 to [`limits::MAX_RUNS`], or groups x noise levels
/// x runs over [`limits::MAX_SIMULATED_RUNS`]; [`Error::MissingField`]
/// for a setup without a nominal stiffness (the true stiffness of the simulation); the errors of
/// [`Factor::try_new`] (for example [`Error::Unidentifiable`]) for a group whose observation
/// matrix cannot identify every joint.
pub fn monte_carlo(
    setup: &Setup,
    groups: &[Vec<Vector6<f64>>],
    options: &Options,
) -> Result<Vec<GroupSimulation>> {
    monte_carlo_reporting(setup, groups, options, &())
}

/// [`monte_carlo`], reporting to `progress` as `monte_carlo_with_predictions` does.
///
/// # Errors
/// As [`monte_carlo`].
pub fn monte_carlo_reporting(
    setup: &Setup,
    groups: &[Vec<Vector6<f64>>],
    options: &Options,
    progress: &dyn Progress,
) -> Result<Vec<GroupSimulation>> {
    check_runs(options)?;
    let predicted: Vec<Vec<[f64; 6]>> = groups
        .iter()
        .map(|g| evaluate(setup, g).predicted_deviation_pct)
        .collect();
    monte_carlo_with_predictions(setup, groups, &predicted, options, progress)
}

/// [`monte_carlo`] with the first-order predictions already at hand (for example from the groups'
/// [`crate::Evaluation`]s): `predicted[g]` is group `g`'s
/// [`crate::Evaluation::predicted_deviation_pct`], percent, \[levels\]\[6\], copied into its
/// result as is. `progress` hears one stage, `Monte Carlo identification`, one unit per run
/// (groups x levels x runs).
///
/// # Errors
/// As [`monte_carlo`]; [`Error::InvalidField`] when `predicted` does not hold one entry per group.
pub(crate) fn monte_carlo_with_predictions(
    setup: &Setup,
    groups: &[Vec<Vector6<f64>>],
    predicted: &[Vec<[f64; 6]>],
    options: &Options,
    progress: &dyn Progress,
) -> Result<Vec<GroupSimulation>> {
    check_runs(options)?;
    let needed_by = "the simulation (the true stiffness)";
    let truth = Truth {
        drives: *setup.try_nominal_stiffness(needed_by)?,
        h: setup.model_compliance(needed_by)?.h,
    };
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
        .map(|g| prepare(setup, g, &truth))
        .collect::<Result<Vec<_>>>()?;
    let runs = options.runs;
    let total = groups.len() * setup.noise().levels.len() * runs;
    if total as u64 > limits::MAX_SIMULATED_RUNS {
        return Err(Error::InvalidField {
            field: "runs".into(),
            message: format!(
                "{runs} runs x {} noise levels x {} groups = {total} identifications, more than {:.0e}: give fewer runs",
                setup.noise().levels.len(),
                groups.len(),
                limits::MAX_SIMULATED_RUNS as f64
            ),
        });
    }
    progress.begin("Monte Carlo identification", total);
    let tally = Tally::new(progress);
    let simulations = prepared
        .iter()
        .zip(predicted)
        .zip(groups)
        .enumerate()
        .map(|(g, ((group, predicted), postures))| {
            let stiffness = group_runs(setup, group, g, options, &tally);
            let mut sim = summarise(&truth.drives, &stiffness, runs, predicted.clone());
            if !setup.model().is_drives_only() {
                add_springs(&mut sim, setup, postures, &truth, &stiffness, runs);
            }
            sim
        })
        .collect();
    progress.end();
    Ok(simulations)
}

/// The virtual springs' deviation rates, mean stiffness and first-order predictions of one
/// group from the identified stiffness of every run (level-major, `runs` per level).
fn add_springs(
    sim: &mut GroupSimulation,
    setup: &Setup,
    postures: &[Vector6<f64>],
    truth: &Truth,
    stiffness: &[Vec<f64>],
    runs: usize,
) {
    let k_true: Vec<f64> = truth.h.iter().skip(6).map(|h| 1.0 / h).collect();
    let spread: Vec<f64> = evaluate(setup, postures).spring_relative_std;
    for (level, multiple) in stiffness.chunks(runs).zip(&setup.noise().levels) {
        let n = level.len() as f64;
        let rate = |k: &[f64], s: usize| 100.0 * (k[6 + s] - k_true[s]).abs() / k_true[s];
        let mean: Vec<f64> = (0..k_true.len())
            .map(|s| level.iter().map(|k| rate(k, s)).sum::<f64>() / n)
            .collect();
        let std = (0..k_true.len())
            .map(|s| match level.len() {
                1 => 0.0,
                _ => (level
                    .iter()
                    .map(|k| (rate(k, s) - mean[s]).powi(2))
                    .sum::<f64>()
                    / (n - 1.0))
                    .sqrt(),
            })
            .collect();
        let factor = 100.0 * (2.0 / std::f64::consts::PI).sqrt() * multiple.sqrt();
        sim.spring_predicted_deviation_pct
            .push(spread.iter().map(|s| factor * s).collect());
        sim.spring_mean_stiffness.push(
            (0..k_true.len())
                .map(|s| level.iter().map(|k| k[6 + s]).sum::<f64>() / n)
                .collect(),
        );
        sim.spring_mean_deviation_pct.push(mean);
        sim.spring_std_deviation_pct.push(std);
    }
}

/// The identified stiffness of every run of group `g`, level-major: one group at a time, so the
/// memory held is `levels x runs` results whatever the number of groups.
fn group_runs(
    setup: &Setup,
    group: &Prepared,
    g: usize,
    options: &Options,
    tally: &Tally,
) -> Vec<Vec<f64>> {
    let runs = options.runs;
    let weights = StepWeights::new(setup.load().load, setup.load_steps());
    (0..setup.noise().levels.len() * runs)
        .into_par_iter()
        .map(|i| {
            let (l, r) = (i / runs, i % runs);
            // Without steps the noise is added to each displacement, with them to each reading.
            let variance = match weights {
                None => setup.noise().displacement_variance(),
                Some(_) => setup.noise().reading_variance,
            };
            let sigma = (variance * setup.noise().levels[l]).sqrt();
            let mut rng = ChaCha8Rng::seed_from_u64(run_seed(options.seed, g, l, r));
            let stiffness = identify_once(group, sigma, weights.as_ref(), &mut rng);
            tally.add(1);
            stiffness
        })
        .collect()
}

fn check_runs(options: &Options) -> Result<()> {
    limits::check_integer("runs", options.runs as u64, 1, limits::MAX_RUNS)
}

fn prepare(setup: &Setup, postures: &[Vector6<f64>], truth: &Truth) -> Result<Prepared> {
    let psi = rope_observation_matrix(setup, postures);
    if !setup.model().is_drives_only() {
        return prepare_model(setup, psi, &truth.h);
    }
    let factor = Factor::try_new(psi)?;
    let exact: Vec<f64> = postures
        .iter()
        .flat_map(|q| rope_displacements(setup, &setup.robot().frames(q), &truth.drives))
        .flat_map(|d| [d.x, d.y, d.z])
        .collect();
    Ok(Prepared {
        solver: Solver::Drives(Box::new(factor)),
        exact: DVector::from_vec(exact),
    })
}

/// A group of a model with virtual springs: the QR factor of its `Psi` (one column per
/// parameter) and the exact displacements `Psi h`.
///
/// # Errors
/// [`Error::InvalidField`] (`model`) naming the parameters the group cannot separate.
fn prepare_model(setup: &Setup, psi: DMatrix<f64>, h: &DVector<f64>) -> Result<Prepared> {
    let parameters = setup.model().parameters();
    let ident = identifiability(&psi)?;
    if let Some(c) = ident.unidentifiable.first() {
        return Err(Error::InvalidField {
            field: "model".into(),
            message: format!(
                "the group's postures cannot separate {}: the simulation needs every parameter identified",
                c.describe(&parameters)
            ),
        });
    }
    let exact = &psi * h;
    let qr = psi.qr();
    Ok(Prepared {
        solver: Solver::Model(qr.q(), qr.r()),
        exact,
    })
}

/// Identified stiffness (SI, every parameter) of one run, solved with the group's factor: the
/// exact displacements plus noise of standard deviation `sigma` (m) on every coordinate; with load
/// steps, each coordinate's unloaded and step readings drawn with that noise and combined into
/// the least squares' displacement at the rope load ([`StepWeights`]).
fn identify_once(
    group: &Prepared,
    sigma: f64,
    weights: Option<&StepWeights>,
    rng: &mut ChaCha8Rng,
) -> Vec<f64> {
    let mut normal = || rng.sample::<f64, _>(StandardNormal);
    let noisy = match weights {
        None => group.exact.map(|d| d + sigma * normal()),
        Some(w) => group.exact.map(|d| {
            let reference = w.reference * normal();
            let steps: f64 = w.steps.iter().map(|w| w * normal()).sum();
            d + sigma * (reference + steps)
        }),
    };
    match &group.solver {
        Solver::Drives(factor) => factor.solve(&noisy).iter().map(|h| 1.0 / h).collect(),
        Solver::Model(q, r) => {
            let c = q.tr_mul(&noisy);
            let h = r
                .solve_upper_triangular(&c)
                .expect("a full-rank R (checked in prepare_model)");
            h.iter().map(|h| 1.0 / h).collect()
        }
    }
}

/// The seed of run `run` at level `level` of group `group`: the four numbers mixed by SplitMix64
/// steps, so neighbouring runs get unrelated streams.
pub(crate) fn run_seed(seed: u64, group: usize, level: usize, run: usize) -> u64 {
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
    stiffness: &[Vec<f64>],
    runs: usize,
    predicted: Vec<[f64; 6]>,
) -> GroupSimulation {
    let mut out = GroupSimulation {
        mean_deviation_pct: Vec::new(),
        std_deviation_pct: Vec::new(),
        predicted_deviation_pct: predicted,
        mean_stiffness: Vec::new(),
        spring_mean_deviation_pct: Vec::new(),
        spring_std_deviation_pct: Vec::new(),
        spring_predicted_deviation_pct: Vec::new(),
        spring_mean_stiffness: Vec::new(),
    };
    for level in stiffness.chunks(runs) {
        let n = level.len() as f64;
        let rate = |k: &[f64], j: usize| 100.0 * (k[j] - k_true[j]).abs() / k_true[j];
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
