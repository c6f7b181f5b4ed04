//! Load steps in the design (`[loading] steps_n`): the predicted deviation rates against the
//! Monte Carlo that simulates every step's readings, against an independent least squares over
//! every step's rows, and the setup's checks of the steps.

use crate::common::{deg, PAPER_POSTURES_DEG};
use nalgebra::{DMatrix, DVector, Vector6};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use stiffid::internal::design::evaluate;
use stiffid::internal::observation::rope_observation_matrix;
use stiffid::internal::study::simulate::{monte_carlo, Options};
use stiffid::Setup;

const STEPS_N: [f64; 5] = [100.0, 200.0, 300.0, 400.0, 500.0];

fn paper() -> Setup {
    stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap()
}

fn stepped() -> Setup {
    paper()
        .to_builder()
        .with_load_steps(STEPS_N.to_vec())
        .build()
        .unwrap()
}

fn postures() -> Vec<Vector6<f64>> {
    PAPER_POSTURES_DEG.iter().map(deg).collect()
}

/// The level index of multiple 1 in the paper setup's levels.
fn level_one(setup: &Setup) -> usize {
    setup.noise().levels.iter().position(|&m| m == 1.0).unwrap()
}

#[test]
fn the_prediction_with_steps_is_the_reading_noise_scaled_by_the_steps() {
    let (plain, stepped) = (paper(), stepped());
    let (s1, s2) = (1500.0, 550_000.0);
    let factor: f64 = 500.0f64.powi(2) * (s2 + s1 * s1) / (s2 * s2);
    let reading = plain.noise().reading_variance;
    assert!((stepped.displacement_variance() / reading - factor).abs() < 1e-12);
    // Without steps a displacement is two readings: the step formula with one step at the load.
    assert_eq!(plain.displacement_variance(), 2.0 * reading);
    let (a, b) = (
        evaluate(&plain, &postures()),
        evaluate(&stepped, &postures()),
    );
    for (pa, pb) in a
        .predicted_deviation_pct
        .iter()
        .zip(&b.predicted_deviation_pct)
    {
        for j in 0..6 {
            assert!(
                (pb[j] / pa[j] - (factor / 2.0).sqrt()).abs() < 1e-9,
                "joint {}",
                j + 1
            );
        }
    }
    // Scale-free criteria do not change: the steps do not change which group is best.
    assert!((a.scaled_cond - b.scaled_cond).abs() < 1e-9 * a.scaled_cond);
    assert_eq!(a.cond_psi, b.cond_psi);
}

#[test]
fn the_monte_carlo_of_every_steps_readings_matches_the_prediction() {
    let setup = stepped();
    let options = Options {
        runs: 2000,
        seed: 5,
    };
    let sim = &monte_carlo(&setup, &[postures()], &options).unwrap()[0];
    let l = level_one(&setup);
    for j in 0..6 {
        let (mc, predicted) = (
            sim.mean_deviation_pct[l][j],
            sim.predicted_deviation_pct[l][j],
        );
        assert!(
            (mc / predicted - 1.0).abs() < 0.1,
            "joint {}: Monte Carlo {mc:.4} %, predicted {predicted:.4} %",
            j + 1
        );
    }
}

/// The least squares over every step's rows, each step's displacement its reading minus the
/// shared unloaded reading, solved by SVD: the prediction holds without the reduction to one
/// block that the simulation uses.
#[test]
fn an_independent_least_squares_over_every_steps_rows_matches_the_prediction() {
    let setup = stepped();
    let psi = rope_observation_matrix(&setup, &postures());
    let k_true = *setup.nominal_stiffness().unwrap();
    let h = DVector::from_iterator(6, k_true.iter().map(|k| 1.0 / k));
    let exact = &psi * &h;
    let rows = psi.nrows();
    let load = setup.load().load;
    let mut stacked = DMatrix::zeros(rows * STEPS_N.len(), 6);
    for (s, f) in STEPS_N.iter().enumerate() {
        stacked
            .rows_mut(s * rows, rows)
            .copy_from(&(&psi * (f / load)));
    }
    let svd = stacked.clone().svd(true, true);
    let sigma = setup.noise().reading_sd();
    let normal = Normal::new(0.0, sigma).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let runs = 1500;
    let mut sum = [0.0; 6];
    for _ in 0..runs {
        let reference = DVector::from_fn(rows, |_, _| normal.sample(&mut rng));
        let mut d = DVector::zeros(rows * STEPS_N.len());
        for (s, f) in STEPS_N.iter().enumerate() {
            let reading = DVector::from_fn(rows, |_, _| normal.sample(&mut rng));
            let step = &exact * (f / load) + reading - &reference;
            d.rows_mut(s * rows, rows).copy_from(&step);
        }
        let fit = svd.solve(&d, 1e-14).unwrap();
        for j in 0..6 {
            sum[j] += 100.0 * ((1.0 / fit[j] - k_true[j]) / k_true[j]).abs();
        }
    }
    let predicted = &evaluate(&setup, &postures()).predicted_deviation_pct[level_one(&setup)];
    for j in 0..6 {
        let mc = sum[j] / runs as f64;
        assert!(
            (mc / predicted[j] - 1.0).abs() < 0.1,
            "joint {}: least squares {mc:.4} %, predicted {:.4} %",
            j + 1,
            predicted[j]
        );
    }
}

#[test]
fn steps_are_read_from_the_setup_file_and_checked() {
    let text = stiffid::internal::setup::builtin_text("zhang2021-comau-nj165").unwrap();
    let with = |steps: &str| {
        let t = text.replace("[loading]\n", &format!("[loading]\nsteps_n = {steps}\n"));
        assert_ne!(t, text, "the built-in setup has a [loading] table");
        stiffid::internal::setup::parse(&t, "s.toml", |r, _| {
            stiffid::internal::robot::presets::get(r)
        })
    };
    assert_eq!(
        with("[100.0, 250.0, 500.0]").unwrap().load_steps(),
        [100.0, 250.0, 500.0]
    );
    let e = with("[100.0, 100.0]").unwrap_err().to_string();
    assert!(
        e.contains("loading.steps_n[2]") && e.contains("rising"),
        "{e}"
    );
    let e = with("[-5.0]").unwrap_err().to_string();
    assert!(e.contains("loading.steps_n"), "{e}");
}
