//! One identification of the paper's experiment size, 6 postures x 4 measuring points: a 72 x 6
//! least-squares problem (QR, compliance, stiffness, residuals, cond(Psi), standard errors and
//! confidence intervals). Target: < 5 microseconds median. Also the kinematics that build `Psi` from
//! the 24 measurements, and the whole path, for reference.

use stiffid::internal::identify::Identify;
#[path = "../../stiffid/tests/it/common.rs"]
mod common;

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::Vector3;
use std::hint::black_box;
use stiffid::internal::identify;
use stiffid::internal::observation::{Measurement, Observations};
use stiffid::internal::setup;

fn bench(c: &mut Criterion) {
    let setup = setup::builtin("zhang2021-comau-nj165").expect("built-in setup");
    // A little deterministic "noise" so that the statistics are not degenerate.
    let data: Vec<Measurement> = common::paper_measurements(&setup)
        .into_iter()
        .enumerate()
        .map(|(i, m)| Measurement {
            displacement: m.displacement + Vector3::repeat(1e-6 * ((i % 5) as f64 - 2.0)),
            ..m
        })
        .collect();
    let obs = Observations::from_measurements(setup.arm(), &data).expect("valid measurements");
    c.bench_function("identify/72x6 least squares and statistics", |b| {
        b.iter(|| black_box(&obs).least_squares().expect("identifiable"))
    });
    c.bench_function("identify/observation matrix of 24 measurements", |b| {
        b.iter(|| {
            Observations::from_measurements(black_box(setup.arm()), black_box(&data))
                .expect("valid")
        })
    });
    c.bench_function("identify/from measurements", |b| {
        b.iter(|| {
            identify::least_squares(black_box(setup.arm()), black_box(&data)).expect("identifiable")
        })
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
