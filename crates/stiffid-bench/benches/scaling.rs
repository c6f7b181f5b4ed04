//! How cost grows with the size of the study (issue 6): criterion evaluation and identification for
//! 6, 24, 96 and 384 postures of the paper setup (4 measuring points, so `Psi` is 72 to 4608 x 6);
//! the Monte Carlo simulation of one group of 6 postures at the setup's 6 noise levels for 200, 2000
//! and 20000 runs; and the Monte Carlo study of `stiffid reproduce` (5 groups x 6 levels x 200 runs).
//!
//! Postures are drawn uniformly within the setup's bounds from a fixed seed (the cost does not depend
//! on their values). Throughput is reported per posture or per run, so linear growth shows as a
//! constant throughput.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use nalgebra::{DVector, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;
use stiffid::internal::design::evaluate;
use stiffid::internal::math::lsq::Factor;
use stiffid::internal::observation::rope_observation_matrix;
use stiffid::internal::study::simulate::{self, Options};
use stiffid::{internal::setup, Setup};

const POSTURES: [usize; 4] = [6, 24, 96, 384];

fn postures(setup: &Setup, n: usize) -> Vec<Vector6<f64>> {
    let mut rng = ChaCha8Rng::seed_from_u64(6);
    let b = &setup.bounds();
    (0..n)
        .map(|_| Vector6::from_fn(|i, _| rng.random_range(b.lower[i]..=b.upper[i])))
        .collect()
}

fn evaluation(c: &mut Criterion) {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let mut group = c.benchmark_group("scaling-evaluate");
    for n in POSTURES {
        let qs = postures(&setup, n);
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::from_parameter(n), &qs, |b, qs| {
            b.iter(|| evaluate(&setup, black_box(qs)))
        });
    }
    group.finish();
}

fn identification(c: &mut Criterion) {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let mut group = c.benchmark_group("scaling-identify");
    for n in POSTURES {
        let psi = rope_observation_matrix(&setup, &postures(&setup, n));
        let delta: DVector<f64> = &psi * setup.nominal_compliance().unwrap();
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(
            BenchmarkId::from_parameter(n),
            &(psi, delta),
            |b, (psi, delta)| {
                b.iter(|| {
                    Factor::try_new(black_box(psi).clone())
                        .unwrap()
                        .solve(black_box(delta))
                })
            },
        );
    }
    group.finish();
}

fn monte_carlo(c: &mut Criterion) {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let levels = setup.noise().levels.len();
    let mut group = c.benchmark_group("monte-carlo");
    group.sample_size(10);
    let one = vec![postures(&setup, 6)];
    for runs in [200, 2000, 20000] {
        let options = Options { runs, seed: 1 };
        group.throughput(Throughput::Elements((runs * levels) as u64));
        group.bench_with_input(BenchmarkId::from_parameter(runs), &one, |b, groups| {
            b.iter(|| simulate::monte_carlo(&setup, black_box(groups), &options).unwrap())
        });
    }
    let five: Vec<_> = postures(&setup, 30).chunks(6).map(<[_]>::to_vec).collect();
    let options = Options::default();
    group.throughput(Throughput::Elements((5 * levels * options.runs) as u64));
    group.bench_function("reproduce-5x6x200", |b| {
        b.iter(|| simulate::monte_carlo(&setup, black_box(&five), &options).unwrap())
    });
    group.finish();
}

criterion_group!(benches, evaluation, identification, monte_carlo);
criterion_main!(benches);
