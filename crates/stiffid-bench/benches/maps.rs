//! The joint error maps of a calibration (`stiffid calibrate --maps auto`): on a FANUC
//! R-2000iC/165F read at one point, 100 postures of a robot with 0.5 mm / 0.5 mrad joint errors
//! and cyclic errors on joints 1 and 2 (16 harmonics, 0.1 mrad), 0.02 mm tracker noise, from
//! the geometric fit: the choice of the maps by cross-validation with its nested held-out gain
//! (the linearised fit with every joint's 32 harmonics, the inner and the outer folds), the
//! final fit with the maps chosen, and the intervals' leave-one-posture-out folds linearised at
//! it (the ridge in the linear system).

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::{Isometry3, Point3, Vector3, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use stiffid::internal::metrology::calibration::error_model::{MeasuredIn, Observation};
use stiffid::internal::metrology::calibration::fit::{self, Options};
use stiffid::internal::metrology::calibration::maps::{self, Linear, Spec};
use stiffid::internal::metrology::calibration::{
    gravity, validation, ErrorModel, Geometry, Target,
};
use stiffid::internal::robot::external::ExternalValues;
use stiffid::internal::robot::presets;

const POSTURES: usize = 100;

/// The geometric model and the readings of the truth with maps on joints 1 and 2.
fn campaign() -> (ErrorModel, Vec<Observation>) {
    let robot = presets::get("fanuc-r2000ic-165f").unwrap();
    let points = [Vector3::new(0.0, 0.0, 0.2)];
    let g = gravity::Terms::none(&robot);
    let model = ErrorModel::new(&robot, &points, MeasuredIn::Tracker, Geometry::Full, g).unwrap();
    let truth = model.clone().with_maps([16, 16, 0, 0, 0, 0]).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let mut values = truth.nominal();
    for (c, p) in truth.parameters().iter().enumerate() {
        let u = 2.0 * rng.random::<f64>() - 1.0;
        match p.target {
            Target::Map { harmonic, .. } => values[c] = 1e-4 * u / harmonic as f64,
            Target::Joint { .. } => values[c] += 5e-4 * u,
            _ => {}
        }
    }
    let l = robot.limits();
    let frame = Isometry3::new(Vector3::new(3.0, -1.0, 0.5), Vector3::new(0.0, 0.0, 2.0));
    let noise = Normal::new(0.0, 2e-5).unwrap();
    let mut obs: Vec<Observation> = (0..POSTURES)
        .map(|i| Observation {
            posture: i,
            point: 0,
            q: Vector6::from_fn(|j, _| {
                let (lo, hi) = (l.lower[j].max(-3.1), l.upper[j].min(3.1));
                lo + (hi - lo) * rng.random::<f64>()
            }),
            measured: Vector3::zeros(),
            wrench: Vector6::zeros(),
            e: ExternalValues::NONE,
            table: false,
            direction: Vector6::zeros(),
        })
        .collect();
    let b = truth.predict(&values, &obs).unwrap();
    for (o, b) in obs.iter_mut().zip(b) {
        let read = (frame.inverse() * Point3::from(b)).coords;
        o.measured = read + Vector3::from_fn(|_, _| noise.sample(&mut rng));
    }
    (model, obs)
}

fn bench(c: &mut Criterion) {
    let options = Options {
        length: 1.0,
        priors: None,
        ridge: 0.0,
        gravity: None,
    };
    let (model, obs) = campaign();
    let start = fit::start(&model, &obs).unwrap();
    let fitted = fit::fit(&model, &obs, &start, &options).unwrap();
    let all: Vec<usize> = (0..POSTURES).collect();
    c.bench_function("maps auto: choice and nested gain, 100 postures", |b| {
        b.iter(|| {
            let linear =
                Linear::at(&model, &fitted, &obs, 1.0, Spec::Auto.candidates(false)).unwrap();
            let choice = maps::choose(&linear, &all, Spec::Auto).unwrap();
            let nested = maps::nested(&linear, &all, Spec::Auto).unwrap();
            (choice, nested)
        })
    });
    let linear = Linear::at(&model, &fitted, &obs, 1.0, Spec::Auto.candidates(false)).unwrap();
    let choice = maps::choose(&linear, &all, Spec::Auto).unwrap();
    let mapped = model.clone().with_maps(choice.maps).unwrap();
    let ridged = Options {
        ridge: choice.ridge,
        ..options
    };
    let extended = maps::extended(&mapped, &fitted.estimate);
    c.bench_function(
        "maps auto: final fit with the maps chosen, 100 postures",
        |b| b.iter(|| fit::fit(&mapped, &obs, &extended, &ridged).unwrap()),
    );
    let full = fit::fit(&mapped, &obs, &extended, &ridged).unwrap();
    c.bench_function(
        "maps auto: linearised folds of the intervals, 100 postures",
        |b| b.iter(|| validation::leave_one_out_linearised(&mapped, &obs, &full, &ridged).unwrap()),
    );
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = bench
}
criterion_main!(benches);
