//! Leave-one-posture-out cross-validation of 20 000 postures (the FANUC R-2000iC/165F rows cycled
//! with shifted axis angles, one measuring point per posture): every least-squares fold from the
//! full fit's QR factor and block hat matrix, linear in the postures; and a robust (Huber)
//! 5-fold cross-validation, which refits each fold.

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::Vector6;
use std::hint::black_box;
use stiffid::internal::identify::cross_validation::Method;
use stiffid::internal::identify::Identify;
use stiffid::internal::identify::{cross_validate, Loss};
use stiffid::internal::io::measurements;
use stiffid::internal::observation::{Measurement, Observations};
use stiffid::internal::setup;

const FANUC: &str = include_str!("../../../examples/data/fanuc-r2000ic-165f/measurements.csv");

/// `n` postures: the FANUC measurements cycled, posture `i` with its angles shifted by
/// `1e-3 (i / 43)` rad.
fn postures(n: usize) -> Vec<Measurement> {
    let file = measurements::parse(FANUC).unwrap();
    let data = &file.measurements;
    (0..n)
        .map(|i| {
            let m = &data[i % data.len()];
            Measurement {
                posture: i,
                q: m.q + Vector6::repeat(1e-3 * (i / data.len()) as f64),
                ..m.clone()
            }
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let setup = setup::builtin("fanuc-r2000ic-165f").unwrap();
    let obs = Observations::from_measurements(setup.arm(), &postures(20_000)).unwrap();
    let full = obs.least_squares().unwrap();
    let mut group = c.benchmark_group("cross_validation");
    group.sample_size(10);
    group.bench_function(
        "leave one posture out, 20 000 postures, least squares",
        |b| {
            b.iter(|| {
                let n = obs.postures;
                cross_validate(black_box(&obs), &full, n, Method::LeastSquares).unwrap()
            })
        },
    );
    let huber = Method::Robust(Loss::Huber);
    let robust = huber.fit(&obs).unwrap();
    group.bench_function("5 folds, 20 000 postures, huber (refitted)", |b| {
        b.iter(|| cross_validate(black_box(&obs), &robust, 5, huber).unwrap())
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
