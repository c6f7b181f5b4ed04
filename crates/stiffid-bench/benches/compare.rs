//! The stiffid side of `bench/compare.sh`: the same work as the NumPy/SciPy baseline
//! (`bench/baseline`) on the same inputs (`bench/inputs`), on the paper setup. Criterion evaluation
//! is timed by the `design` bench (its cost does not depend on the posture values).
//!
//! - `compare/lstsq`: the least-squares step alone, 72 x 6 (QR factor and solve);
//! - `compare/identify`: identification from the 24 measurements of `bench/inputs/measurements.csv`
//!   (observation matrix, least squares and statistics, as `stiffid identify` without file I/O);
//! - `compare/local-search`: SLSQP on `zhang2021` from the start group, default options (exact
//!   gradient); `compare/local-search-fd`: the same with finite-difference gradients;
//!   `compare/local-search-active-set`: the same with our SQP.

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::{DVector, Vector6};
use std::hint::black_box;
use stiffid::internal::design::{local, Criterion as Design, Gradient, SearchOptions, Solver};
use stiffid::internal::identify;
use stiffid::internal::math::lsq::Factor;
use stiffid::internal::observation::rope_observation_matrix;
use stiffid::internal::observation::Measurement;
use stiffid::internal::setup;

const START: &str = include_str!("../../../bench/inputs/start-group.csv");
const MEASUREMENTS: &str = include_str!("../../../bench/inputs/measurements.csv");

/// The start group (axis angles, rad), read by the library's parser.
fn start_group() -> Vec<Vector6<f64>> {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    stiffid::internal::io::postures::parse(START, setup.robot(), None).unwrap()
}

/// The measurements of `posture,point,q1_deg..q6_deg,fx_n,fy_n,fz_n,dx_mm,dy_mm,dz_mm`, read by the
/// library's parser.
fn measurements() -> Vec<Measurement> {
    stiffid::internal::io::measurements::parse(MEASUREMENTS)
        .unwrap()
        .measurements
}

fn compare(c: &mut Criterion) {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let start = start_group();
    let mut group = c.benchmark_group("compare");
    let psi = rope_observation_matrix(&setup, &start);
    let delta: DVector<f64> = &psi * setup.nominal_compliance().unwrap();
    group.bench_function("lstsq", |b| {
        b.iter(|| {
            Factor::try_new(black_box(&psi).clone())
                .unwrap()
                .solve(black_box(&delta))
        })
    });
    let data = measurements();
    group.bench_function("identify", |b| {
        b.iter(|| identify::least_squares(setup.arm(), black_box(&data)).unwrap())
    });
    let options = SearchOptions::default();
    group.sample_size(10).bench_function("local-search", |b| {
        b.iter(|| local(&setup, Design::Zhang2021, black_box(&start), &options).unwrap())
    });
    let fd = SearchOptions {
        gradient: Gradient::FiniteDifference,
        ..options.clone()
    };
    group.bench_function("local-search-fd", |b| {
        b.iter(|| local(&setup, Design::Zhang2021, black_box(&start), &fd).unwrap())
    });
    let ours = SearchOptions {
        solver: Solver::ActiveSet,
        ..options.clone()
    };
    group.bench_function("local-search-active-set", |b| {
        b.iter(|| local(&setup, Design::Zhang2021, black_box(&start), &ours).unwrap())
    });
    group.finish();
}

criterion_group!(benches, compare);
criterion_main!(benches);
