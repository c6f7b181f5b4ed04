//! The stiffid side of `bench/compare.sh`: the same work as the NumPy/SciPy baseline
//! (`bench/baseline`) on the same inputs (`bench/inputs`), on the paper setup.
//!
//! - `compare/zhang2021`: one evaluation of the paper's index, 6 postures x 4 measuring points;
//! - `compare/evaluate`: every criterion and the predicted deviation rates (`stiffid evaluate`);
//! - `compare/lstsq`: the least-squares step alone, 72 x 6 (QR factor and solve);
//! - `compare/local-search`: SLSQP on `zhang2021` from the start group, default options.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use nalgebra::{DVector, Vector6};
use stiffid::design::{evaluate, local, Criterion as Design, Evaluator, SearchOptions};
use stiffid::lsq::Factor;
use stiffid::observation::rope_observation_matrix;
use stiffid::setup;

const START: &str = include_str!("../../../bench/inputs/start-group.csv");

/// The start group (axis angles, rad) from its CSV `posture,q1_deg,...,q6_deg`.
fn start_group() -> Vec<Vector6<f64>> {
    START
        .lines()
        .skip(1)
        .map(|line| {
            let deg: Vec<f64> = line
                .split(',')
                .skip(1)
                .map(|v| v.parse().unwrap())
                .collect();
            Vector6::from_iterator(deg.iter().map(|d| d.to_radians()))
        })
        .collect()
}

fn compare(c: &mut Criterion) {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let start = start_group();
    let mut group = c.benchmark_group("compare");
    group.bench_function("zhang2021", |b| {
        let evaluator = Evaluator::new(&setup);
        b.iter(|| evaluator.value(Design::Zhang2021, black_box(&start)))
    });
    group.bench_function("evaluate", |b| {
        b.iter(|| evaluate(&setup, black_box(&start)))
    });
    let psi = rope_observation_matrix(&setup, &start);
    let delta: DVector<f64> = &psi * setup.nominal_compliance();
    group.bench_function("lstsq", |b| {
        b.iter(|| {
            Factor::try_new(black_box(&psi))
                .unwrap()
                .solve(black_box(&delta))
        })
    });
    let options = SearchOptions::default();
    group.sample_size(10).bench_function("local-search", |b| {
        b.iter(|| local(&setup, Design::Zhang2021, black_box(&start), &options).unwrap())
    });
    group.finish();
}

criterion_group!(benches, compare);
criterion_main!(benches);
