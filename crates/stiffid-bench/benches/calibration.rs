//! The robot calibration fit (`stiffid calibrate`): full geometry and lumped gravity on the
//! FANUC R-2000iC/165F preset, noise-free readings of a robot with 0.5 mm / 0.5 mrad errors, at 36
//! postures x 3 measuring points and at 3000 postures x 3 points; the same on a 6 m track (its
//! direction and error motions of order 3 fitted too, the postures spread over the rail), and
//! the choice of the track's orders by cross-validation (`--error-motions auto`) at 36; the fit
//! and the leave-one-posture-out cross-validation (`--cross-validate`) of 1000 postures x 1 point.

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::{Isometry3, Point3, Vector3, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use stiffid::internal::metrology::calibration::error_model::{MeasuredIn, Observation};
use stiffid::internal::metrology::calibration::fit::{self, Options};
use stiffid::internal::metrology::calibration::{
    gravity, motions, validation, ErrorModel, Estimate, Geometry,
};
use stiffid::internal::robot::external::{
    ErrorMotions, ExternalAxes, ExternalAxis, ExternalValues,
};
use stiffid::internal::robot::presets;

/// The campaign and, with `track`, the arm on a 6 m track along x whose true error motions are
/// of order 3 (0.1 mm, 0.1 mrad), with the model of the arm alone (the track's parameters are
/// added by the caller).
fn campaign(postures: usize, track: bool) -> (ErrorModel, Vec<Observation>) {
    let mut robot = presets::get("fanuc-r2000ic-165f").unwrap();
    if track {
        let mut axis = ExternalAxis::linear("track", Vector3::x_axis(), 0.0, 6.0);
        axis.errors = ErrorMotions::new(vec![[1e-4; 6], [-1e-4; 6], [1e-4; 6]]).unwrap();
        robot = robot.with_external(Some(ExternalAxes::new(vec![axis]).unwrap()));
    }
    let points = [
        Vector3::new(0.15, 0.0, 0.25),
        Vector3::new(-0.1, 0.12, 0.3),
        Vector3::new(0.0, -0.14, 0.2),
    ];
    let g = gravity::Terms::lumped(&robot, stiffid::Coordinates::Axis);
    let model = ErrorModel::new(&robot, &points, MeasuredIn::Tracker, Geometry::Full, g).unwrap();
    // The truth: the track as the robot holds it.
    let truth = match track {
        true => model.clone().with_external(&[0], 0).unwrap(),
        false => model.clone(),
    };
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
        let e = match track {
            true => ExternalValues::new(&[6.0 * (i % 12) as f64 / 11.0]).unwrap(),
            false => ExternalValues::NONE,
        };
        for k in 0..3 {
            obs.push(Observation {
                posture: i,
                point: k,
                q,
                measured: Vector3::zeros(),
                wrench: Vector6::zeros(),
                e,
                table: false,
                direction: Vector6::zeros(),
            });
        }
    }
    let mut values_truth = truth.nominal();
    values_truth.rows_mut(0, values.len()).copy_from(&values);
    let b = truth.predict(&values_truth, &obs).unwrap();
    for (o, b) in obs.iter_mut().zip(b) {
        o.measured = (frame.inverse() * Point3::from(b)).coords;
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
    for postures in [36, 3000] {
        let (model, obs) = campaign(postures, false);
        let start: Estimate = fit::start(&model, &obs).unwrap();
        c.bench_function(&format!("calibrate full+lumped {postures}x3"), |b| {
            b.iter(|| fit::fit(&model, &obs, &start, &options).unwrap())
        });
    }
    for postures in [36, 3000] {
        let (arm, obs) = campaign(postures, true);
        let model = arm.clone().with_external(&[3], 0).unwrap();
        let start: Estimate = fit::start(&model, &obs).unwrap();
        c.bench_function(
            &format!("calibrate full+lumped on a track {postures}x3"),
            |b| b.iter(|| fit::fit(&model, &obs, &start, &options).unwrap()),
        );
        if postures == 36 {
            c.bench_function("calibrate track orders by cross-validation 36x3", |b| {
                b.iter(|| motions::choose(&arm, 0, &obs, &options, motions::Spec::Auto).unwrap())
            });
        }
    }
    // `calibrate --cross-validate` of 1000 one-point postures: the fit, then its folds.
    let (model, mut obs) = campaign(1000, false);
    obs.retain(|o| o.point == 0);
    let start: Estimate = fit::start(&model, &obs).unwrap();
    c.bench_function("calibrate full+lumped 1000x1", |b| {
        b.iter(|| fit::fit(&model, &obs, &start, &options).unwrap())
    });
    let fitted = fit::fit(&model, &obs, &start, &options).unwrap();
    c.bench_function("calibrate cross-validation 1000x1", |b| {
        b.iter(|| validation::cross_validate(&model, &obs, &fitted, &options, &()).unwrap())
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = bench
}
criterion_main!(benches);
