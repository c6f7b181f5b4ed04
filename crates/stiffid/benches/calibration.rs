//! The robot calibration fit (`stiffid calibrate`): full geometry and lumped gravity on the
//! FANUC R-2000iC/165F preset, noise-free readings of a robot with 0.5 mm / 0.5 mrad errors, at 36
//! postures x 3 measuring points and at 3000 postures x 3 points.

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::{Isometry3, Point3, Vector3, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use stiffid::metrology::calibration::error_model::{MeasuredIn, Observation};
use stiffid::metrology::calibration::fit::{self, Options};
use stiffid::metrology::calibration::{gravity, ErrorModel, Estimate, Geometry};
use stiffid::robot::presets;

fn campaign(postures: usize) -> (ErrorModel, Vec<Observation>) {
    let robot = presets::get("fanuc-r2000ic-165f").unwrap();
    let points = [
        Vector3::new(0.15, 0.0, 0.25),
        Vector3::new(-0.1, 0.12, 0.3),
        Vector3::new(0.0, -0.14, 0.2),
    ];
    let g = gravity::Terms::lumped(&robot, stiffid::Coordinates::Axis);
    let model = ErrorModel::new(&robot, &points, MeasuredIn::Tracker, Geometry::Full, g).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let mut values = model.nominal();
    for (c, p) in model.parameters().iter().enumerate() {
        if p.name.starts_with("joint") {
            values[c] += 5e-4 * (2.0 * rng.random::<f64>() - 1.0);
        }
    }
    let l = robot.limits();
    let frame = Isometry3::new(Vector3::new(3.0, -1.0, 0.5), Vector3::new(0.0, 0.0, 2.0));
    let mut obs = Vec::new();
    for i in 0..postures {
        let q = Vector6::from_fn(|j, _| {
            let (lo, hi) = (l.lower[j].max(-2.6), l.upper[j].min(2.6));
            0.5 * (lo + hi) + 0.6 * (hi - lo) * (rng.random::<f64>() - 0.5)
        });
        for k in 0..3 {
            let b = model.positions(&values, &[(q, k)]).unwrap()[0];
            obs.push(Observation {
                posture: i,
                point: k,
                q,
                measured: (frame.inverse() * Point3::from(b)).coords,
                wrench: Vector6::zeros(),
                e: Vec::new(),
                table: false,
            });
        }
    }
    (model, obs)
}

fn bench(c: &mut Criterion) {
    let options = Options {
        length: 1.0,
        priors: None,
        ridge: 0.0,
    };
    for postures in [36, 3000] {
        let (model, obs) = campaign(postures);
        let start: Estimate = fit::start(&model, &obs).unwrap();
        c.bench_function(&format!("calibrate full+lumped {postures}x3"), |b| {
            b.iter(|| fit::fit(&model, &obs, &start, &options).unwrap())
        });
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = bench
}
criterion_main!(benches);
