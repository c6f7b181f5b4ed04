//! Forward kinematics plus the five point Jacobians (loading point and four measuring points) of
//! the `zhang2021-comau-nj165` setup for one posture: what each posture of a design costs.
//! Target (issue 2): under 1 microsecond.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use nalgebra::{Matrix6, Vector3};
use stiffid::{setup, Coordinates};

fn kinematics(c: &mut Criterion) {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let points: Vec<Vector3<f64>> = std::iter::once(setup.tool.loading_point)
        .chain(setup.tool.measuring_points.iter().copied())
        .collect();
    let q = setup.test_postures[0];
    c.bench_function(
        "frames + 5 point Jacobians (COMAU, axis coordinates)",
        |b| {
            b.iter(|| {
                let frames = setup.robot.frames(black_box(&q));
                let mut sum = Matrix6::zeros();
                for p in &points {
                    sum += frames.jacobian(black_box(p), Coordinates::Axis);
                }
                sum
            })
        },
    );
    c.bench_function("frames (COMAU)", |b| {
        b.iter(|| setup.robot.frames(black_box(&q)))
    });
}

criterion_group!(benches, kinematics);
criterion_main!(benches);
