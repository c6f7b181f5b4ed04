//! The joint error maps: noise-free recovery with the geometry (to 1e-6 of the largest
//! coefficient: the first harmonic of joint 3, parallel to joints 2 and 4, is weakly determined), and the choice by
//! cross-validation that keeps no map on a robot without one.

use super::error_model::{Geometry, MeasuredIn, Observation, Target};
use super::fit::{self, Options};
use super::maps::{self, Linear, Spec};
use super::tests::{postures, readings, tracker, ur10};
use super::{gravity, ErrorModel, Estimate};
use nalgebra::{Vector3, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

/// The UR10 read at one point (as a T-Mac 109 mm along the flange axis), full geometry.
pub(super) fn model() -> ErrorModel {
    let robot = ur10();
    ErrorModel::new(
        &robot,
        &[Vector3::new(0.0, 0.0, 0.109)],
        MeasuredIn::Tracker,
        Geometry::Full,
        gravity::Terms::none(&robot),
    )
    .unwrap()
}

/// A truth with every identified geometric error drawn within +-0.5 mm or mrad and, with maps,
/// their coefficients `amplitude / h` (rad) of random sign.
pub(super) fn truth(
    model: &ErrorModel,
    identified: &[usize],
    amplitude: f64,
    seed: u64,
) -> Estimate {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut x = model.nominal();
    for (c, p) in model.parameters().iter().enumerate() {
        let u = 2.0 * rng.random::<f64>() - 1.0;
        match p.target {
            Target::Frame(_) => {}
            Target::Map { harmonic, .. } => x[c] = amplitude * u / harmonic as f64,
            _ if identified.contains(&c) => x[c] += 5e-4 * u,
            _ => {}
        }
    }
    Estimate {
        frame: tracker(),
        values: x,
    }
}

pub(super) fn identified(model: &ErrorModel, qs: &[Vector6<f64>]) -> Vec<usize> {
    let nominal = Estimate {
        frame: nalgebra::Isometry3::identity(),
        values: model.nominal(),
    };
    let probe = readings(model, &nominal, qs);
    let start = fit::start(model, &probe).unwrap();
    (fit::fit(model, &probe, &start, &options(0.0)).unwrap())
        .identifiability
        .identified
}

pub(super) fn options(ridge: f64) -> Options {
    Options {
        length: 1.0,
        priors: None,
        ridge,
    }
}

pub(super) fn noisy(mut data: Vec<Observation>, sd: f64, seed: u64) -> Vec<Observation> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let normal = Normal::new(0.0, sd).unwrap();
    for o in &mut data {
        o.measured += Vector3::from_fn(|_, _| normal.sample(&mut rng));
    }
    data
}

#[test]
fn maps_are_recovered_with_the_geometry_noise_free() {
    let geometry = model();
    let qs = postures(geometry.robot(), 80, 3);
    let kept = identified(&geometry, &qs);
    let mapped = geometry.clone().with_maps([0, 4, 8, 0, 3, 0]).unwrap();
    let truth = truth(&mapped, &kept, 3e-4, 7);
    let data = readings(&mapped, &truth, &qs);
    let start = maps::extended(&mapped, &fit::start(&geometry, &data).unwrap());
    let found = fit::fit(&mapped, &data, &start, &options(0.0)).unwrap();
    assert!(found.rms < 1e-11, "rms {:e}", found.rms);
    let largest = (mapped.parameters().iter().enumerate())
        .filter(|(_, p)| matches!(p.target, Target::Map { .. }))
        .map(|(c, _)| truth.values[c].abs())
        .fold(0.0, f64::max);
    for (c, p) in mapped.parameters().iter().enumerate() {
        if let Target::Map { .. } = p.target {
            let (got, want) = (found.estimate.values[c], truth.values[c]);
            assert!(
                (got - want).abs() <= 1e-6 * largest,
                "{}: {got:e} vs {want:e}",
                p.name
            );
        }
    }
    // The calibrated robot carries them: its frames give the readings.
    let robot = mapped.robot_at(&found.estimate.values).unwrap();
    for o in data.iter().take(5) {
        let b = robot
            .frames(&o.q)
            .point(&mapped.point(&found.estimate.values, 0));
        let t = found.estimate.frame * nalgebra::Point3::from(o.measured);
        assert!((b - t.coords).norm() < 1e-10);
    }
}

/// The choice of `spec` on a UR10 campaign of `n` postures with maps of `amplitude` (rad) on
/// joints 2 and 5 (none at 0), tracker noise 0.02 mm per coordinate.
fn choose(amplitude: f64, n: usize, seed: u64) -> (maps::Choice, maps::Nested) {
    let geometry = model();
    let qs = postures(geometry.robot(), n, 100 + seed);
    let kept = identified(&geometry, &qs);
    let mapped = geometry.clone().with_maps([0, 8, 0, 0, 4, 0]).unwrap();
    let truth = truth(&mapped, &kept, amplitude, seed);
    let data = noisy(readings(&mapped, &truth, &qs), 2e-5, seed);
    let start = fit::start(&geometry, &data).unwrap();
    let fitted = fit::fit(&geometry, &data, &start, &options(0.0)).unwrap();
    let linear = Linear::at(&geometry, &fitted, &data, 1.0, Spec::Auto.candidates()).unwrap();
    let all: Vec<usize> = (0..n).collect();
    (
        maps::choose(&linear, &all, Spec::Auto).unwrap(),
        maps::nested(&linear, &all, Spec::Auto).unwrap(),
    )
}

#[test]
fn the_choice_keeps_no_map_on_a_robot_without_one() {
    let seeds = 20usize;
    let none = (0..seeds as u64)
        .filter(|&s| choose(0.0, 60, s).0.harmonics == [0; 6])
        .count();
    assert!(none * 10 >= seeds * 9, "no map in {none} of {seeds} seeds");
}

#[test]
fn the_choice_finds_the_maps_and_the_nested_figure_shows_the_gain() {
    let (choice, nested) = choose(2e-4, 100, 1);
    // Joint 2's map moves the point by about 0.2 mm; joint 5's, 109 mm from the point, by about
    // 20 um, the tracker's noise: the choice need not see it.
    assert!(choice.harmonics[1] > 0, "{choice:?}");
    assert!(choice.rms < 0.5 * choice.none_rms, "{choice:?}");
    assert!(nested.rms < 0.5 * nested.none_rms, "{nested:?}");
}
