//! One identification of the paper's experiment size, 6 postures x 4 measuring points: a 72 x 6
//! least-squares problem (QR, compliance, stiffness, residuals, cond(Psi), standard errors and
//! confidence intervals). Target: < 5 microseconds median. Also the kinematics that build `Psi` from
//! the 24 measurements, and the whole path, for reference.

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::Vector6;
use std::hint::black_box;
use stiffid::identify::{identify, observations, Measurement};
use stiffid::{setup, stiffness};

fn paper_measurements() -> (stiffid::Setup, Vec<Measurement>) {
    let setup = setup::builtin("zhang2021-comau-nj165").expect("built-in setup");
    let postures = [
        [10.0, -20.0, -100.0, 30.0, 40.0, 50.0],
        [-40.0, 10.0, -70.0, -60.0, -30.0, 120.0],
        [60.0, -40.0, -140.0, 90.0, 60.0, -90.0],
        [-70.0, 30.0, -60.0, -150.0, -70.0, 10.0],
        [30.0, -50.0, -160.0, 160.0, 20.0, -150.0],
        [0.0, 0.0, -90.0, 45.0, -45.0, 90.0],
    ];
    let mut data = Vec::new();
    for (i, q) in postures.iter().enumerate() {
        let q = Vector6::from_iterator(q.iter().map(|v: &f64| v.to_radians()));
        let frames = setup.robot.frames(&q);
        let wrench = setup.rope_wrench(&frames);
        let d = stiffness::deflection(&setup, &frames, &wrench, &setup.nominal_stiffness);
        for (point, disp) in d.displacements.iter().enumerate() {
            data.push(Measurement {
                posture: format!("{}", i + 1),
                point,
                q,
                wrench,
                // A little deterministic "noise" so that the statistics are not degenerate.
                displacement: disp.fixed_rows::<3>(0) * (1.0 + 1e-3 * ((point + i) % 3) as f64),
            });
        }
    }
    (setup, data)
}

fn bench(c: &mut Criterion) {
    let (setup, data) = paper_measurements();
    let obs = observations(&setup, &data).expect("valid measurements");
    c.bench_function("identify/72x6 least squares and statistics", |b| {
        b.iter(|| black_box(&obs).identify().expect("identifiable"))
    });
    c.bench_function("identify/observation matrix of 24 measurements", |b| {
        b.iter(|| observations(black_box(&setup), black_box(&data)).expect("valid"))
    });
    c.bench_function("identify/from measurements", |b| {
        b.iter(|| identify(black_box(&setup), black_box(&data)).expect("identifiable"))
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
