//! Forward kinematics plus the five point Jacobians (loading point and four measuring points) of
//! the `zhang2021-comau-nj165` setup for one posture: what each posture of a design costs.
//! Target (issue 2): under 1 microsecond. Also the 6x6 kernels of the design criteria against
//! nalgebra's general ones (issue 14): the dexterity's inverse and the condition number of `R`.

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::{Matrix6, Vector3};
use std::hint::black_box;
use stiffid::internal::math::lsq::Factor;
use stiffid::internal::observation::rope_observation_matrix;
use stiffid::{dexterity, internal::setup, Coordinates};

fn kinematics(c: &mut Criterion) {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let points: Vec<Vector3<f64>> = std::iter::once(setup.tool().loading_point)
        .chain(setup.tool().measuring_points.iter().copied())
        .collect();
    let q = setup.test_postures()[0];
    c.bench_function(
        "frames + 5 point Jacobians (COMAU, axis coordinates)",
        |b| {
            b.iter(|| {
                let frames = setup.robot().frames(black_box(&q));
                let mut sum = Matrix6::zeros();
                for p in &points {
                    sum += frames.jacobian(black_box(p), Coordinates::Axis);
                }
                sum
            })
        },
    );
    c.bench_function("frames (COMAU)", |b| {
        b.iter(|| setup.robot().frames(black_box(&q)))
    });
    // With joint error maps (issue 50: within 20 % of without): three axes with 16 harmonics each,
    // as a calibration with maps writes them.
    let map = |k: f64| {
        let c: Vec<f64> = (1..=16).map(|h| k * 1e-5 / h as f64).collect();
        stiffid::internal::robot::ErrorMap::new(c.clone(), c).unwrap()
    };
    let mapped = setup.robot().clone().with_error_maps([
        stiffid::internal::robot::ErrorMap::default(),
        map(1.0),
        map(-2.0),
        stiffid::internal::robot::ErrorMap::default(),
        map(3.0),
        stiffid::internal::robot::ErrorMap::default(),
    ]);
    c.bench_function("frames (COMAU, error maps on 3 axes x 16 harmonics)", |b| {
        b.iter(|| mapped.frames(black_box(&q)))
    });
    // The dexterity's 6x6 inverse: stiffid's fixed-size Gauss-Jordan against nalgebra's LU
    // `try_inverse` (the former kernel), on the same normalised TCP Jacobian.
    let frames = setup.robot().frames(&q);
    let tcp = frames.jacobian(&setup.tool().tcp, Coordinates::Axis);
    let l = setup.characteristic_length().unwrap();
    c.bench_function("dexterity (fixed-size inverse)", |b| {
        b.iter(|| dexterity(black_box(&tcp), l))
    });
    c.bench_function("dexterity (nalgebra try_inverse)", |b| {
        b.iter(|| {
            let mut jn = *black_box(&tcp);
            jn.fixed_rows_mut::<3>(0).scale_mut(1.0 / l);
            jn.try_inverse().map(|inv| jn.norm() * inv.norm() / 6.0)
        })
    });
    // cond_2 of a 6x6 triangular factor: one-sided Jacobi (Factor::cond) against nalgebra's SVD.
    let psi = rope_observation_matrix(&setup, setup.test_postures());
    let factor = Factor::try_new(psi.clone()).unwrap();
    let r = *factor.r();
    c.bench_function("cond of R (Jacobi)", |b| {
        b.iter(|| black_box(&factor).cond())
    });
    c.bench_function("cond of R (nalgebra SVD)", |b| {
        b.iter(|| {
            let s = black_box(&r).singular_values();
            s.max() / s.min()
        })
    });
}

criterion_group!(benches, kinematics);
criterion_main!(benches);
