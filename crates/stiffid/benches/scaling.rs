//! How cost grows with the size of the study (issue 6): criterion evaluation and identification for
//! 6, 24, 96 and 384 postures of the paper setup (4 measuring points, so `Psi` is 72 to 4608 x 6).
//!
//! Postures are drawn uniformly within the setup's bounds from a fixed seed. Throughput is reported
//! per posture, so linear growth shows as a constant throughput.

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use nalgebra::{DVector, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use stiffid::design::evaluate;
use stiffid::lsq::Factor;
use stiffid::observation::rope_observation_matrix;
use stiffid::{setup, Setup};

const POSTURES: [usize; 4] = [6, 24, 96, 384];

fn postures(setup: &Setup, n: usize) -> Vec<Vector6<f64>> {
    let mut rng = ChaCha8Rng::seed_from_u64(6);
    let b = &setup.bounds;
    (0..n)
        .map(|_| Vector6::from_fn(|i, _| rng.random_range(b.lower[i]..=b.upper[i])))
        .collect()
}

fn evaluation(c: &mut Criterion) {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let mut group = c.benchmark_group("scaling/evaluate");
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
    let mut group = c.benchmark_group("scaling/identify");
    for n in POSTURES {
        let psi = rope_observation_matrix(&setup, &postures(&setup, n));
        let delta: DVector<f64> = &psi * setup.nominal_compliance();
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(
            BenchmarkId::from_parameter(n),
            &(psi, delta),
            |b, (psi, delta)| {
                b.iter(|| {
                    Factor::try_new(black_box(psi))
                        .unwrap()
                        .solve(black_box(delta))
                })
            },
        );
    }
    group.finish();
}

criterion_group!(benches, evaluation, identification);
criterion_main!(benches);
