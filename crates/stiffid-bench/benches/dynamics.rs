//! The robot's mass at one posture: the mass matrix (composite rigid body algorithm), the TCP's
//! operational-space inertia and the six modes, with the forward kinematics, on the
//! `zhang2021-comau-nj165` setup given link masses and inertia tensors (the drives' nominal
//! stiffness). Goals: one posture under 20 us, 10 000 path postures under 0.2 s; and the
//! compensate job's per-point dynamics of a 10 000-point program
//! ([`stiffid::internal::machining::dynamics::program`]: every point milled, so every point's modes).

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::{Matrix3, Vector3, Vector6};
use std::hint::black_box;
use stiffid::internal::machining;
use stiffid::internal::machining::compensate::{self, Options, PathPoint, Target};
use stiffid::internal::machining::process::file;
use stiffid::internal::observation::deflection::Frame;
use stiffid::internal::observation::dynamics;
use stiffid::internal::robot::LinkMass;
use stiffid::internal::setup;

fn dynamics(c: &mut Criterion) {
    let setup = setup::builtin("zhang2021-comau-nj165").unwrap();
    let masses: [LinkMass; 6] = std::array::from_fn(|l| LinkMass {
        mass: 300.0 / (l + 1) as f64,
        centre: Vector3::new(0.1, -0.02 * l as f64, 0.05),
        inertia: Matrix3::from_diagonal(&Vector3::new(3.0, 2.5, 2.0)) / (l + 1) as f64,
    });
    let robot = setup.robot().clone().with_masses(Some(masses));
    let setup = (setup.to_builder()).with_robot(robot).build().unwrap();
    let h = setup.model_compliance("bench").unwrap().h;
    let model = dynamics::mass_model(setup.arm()).0.unwrap();
    let tcp = setup.tool().tcp;
    let q = setup.test_postures()[0];
    c.bench_function("frames + M(q) + Lambda + modes (COMAU)", |b| {
        b.iter(|| {
            let frames = setup.robot().frames(black_box(&q));
            dynamics::posture(&model, setup.arm(), &frames, &tcp, &h)
        })
    });
    let path: Vec<Vector6<f64>> = (0..10_000)
        .map(|i| q + Vector6::repeat(1e-4 * i as f64))
        .collect();
    let mut group = c.benchmark_group("path");
    group.sample_size(10);
    group.bench_function("10 000 postures: M(q) + Lambda + modes", |b| {
        b.iter(|| {
            let mut lowest = 0.0;
            for q in &path {
                let frames = setup.robot().frames(q);
                let p = dynamics::posture(&model, setup.arm(), &frames, &tcp, &h);
                lowest += p.modes.map_or(0.0, |m| m.frequencies[0]);
            }
            lowest
        })
    });
    let compliance = setup.model_compliance("bench").unwrap();
    let points: Vec<PathPoint> = path
        .iter()
        .map(|q| PathPoint {
            line: 1,
            target: Target::Posture(*q),
            wrench: Vector6::new(100.0, 0.0, 0.0, 0.0, 0.0, 0.0),
            frame: Frame::Base,
            external: stiffid::internal::robot::external::ExternalValues::NONE,
        })
        .collect();
    let options = Options::for_setup(&setup);
    let results = compensate::path(setup.arm(), &compliance, &points, &options).unwrap();
    let process = file::parse(
        "[tool]\ndiameter_mm = 20\nflutes = 3\n[cut]\nfeed_per_tooth_mm = 0.1\naxial_depth_mm = 4\n\
         radial_depth_mm = 10\nmode = \"down\"\nspindle_rpm = 6000\n[coefficients]\npreset = \"al7075-t6\"\n",
        "p.toml",
    )
    .unwrap();
    let operations = vec![Some(0); results.len()];
    group.bench_function("10 000 milling points: compensate's first frequency", |b| {
        b.iter(|| {
            machining::dynamics::program(
                setup.arm(),
                &model,
                &compliance,
                &process,
                &results,
                &operations,
            )
        })
    });
    group.finish();
}

criterion_group!(benches, dynamics);
criterion_main!(benches);
