//! The backlash terms: noise-free recovery of each joint's half backlash with the geometry, with
//! and without cyclic maps (to 1e-9 of the largest), the Jacobian's backlash columns against
//! central differences, the choice by cross-validation that keeps no backlash term on a robot
//! without one and finds the one a robot has, and the refusal of a backlash term without
//! directions.

use super::error_model::{JointMaps, Observation, Target};
use super::fit;
use super::maps::{self, Linear, Spec};
use super::maps_tests::{identified, model, noisy, options, three_points, truth, whole_turns};
use super::tests::{postures, readings};
use super::{ErrorModel, Estimate};
use nalgebra::{DVector, Point3, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The readings of `truth` at `qs`, each posture approached from random directions (seeded).
fn approached(
    model: &ErrorModel,
    truth: &Estimate,
    qs: &[Vector6<f64>],
    seed: u64,
) -> Vec<Observation> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let directions: Vec<Vector6<f64>> = (qs.iter())
        .map(|_| Vector6::from_fn(|_, _| if rng.random::<bool>() { 1.0 } else { -1.0 }))
        .collect();
    let mut data = readings(model, truth, qs);
    for o in &mut data {
        o.direction = directions[o.posture];
    }
    let b = model.predict(&truth.values, &data).unwrap();
    for (o, b) in data.iter_mut().zip(b) {
        o.measured = (truth.frame.inverse() * Point3::from(b)).coords;
    }
    data
}

/// `truth` with half backlashes of 0.1 to 0.6 mrad of alternating sign on the model's backlash
/// terms.
fn with_backlash(model: &ErrorModel, mut truth: Estimate) -> Estimate {
    for (c, p) in model.parameters().iter().enumerate() {
        if let Target::Backlash { joint } = p.target {
            let sign = if joint % 2 == 0 { 1.0 } else { -1.0 };
            truth.values[c] = sign * 1e-4 * (joint + 1) as f64;
        }
    }
    truth
}

/// The worst error of the maps' coefficients and half backlashes fitted noise-free, relative to
/// the largest, with maps of `harmonics` and a backlash term on every joint.
fn recovered(harmonics: [usize; 6]) -> f64 {
    let geometry = three_points();
    let qs = whole_turns(60, 11);
    let kept = identified(&geometry, &qs);
    let terms = JointMaps {
        harmonics,
        backlash: [true; 6],
    };
    let mapped = geometry.clone().with_maps(terms).unwrap();
    let truth = with_backlash(&mapped, truth(&mapped, &kept, 3e-4, 5));
    let data = approached(&mapped, &truth, &qs, 3);
    let start = maps::extended(&mapped, &fit::start(&geometry, &data).unwrap());
    let found = fit::fit(&mapped, &data, &start, &options(0.0)).unwrap();
    assert!(found.rms < 1e-11, "rms {:e}", found.rms);
    let terms: Vec<usize> = (mapped.parameters().iter().enumerate())
        .filter(|(_, p)| matches!(p.target, Target::Map { .. } | Target::Backlash { .. }))
        .map(|(c, _)| c)
        .collect();
    assert_eq!(terms.len(), 2 * harmonics.iter().sum::<usize>() + 6);
    let largest = (terms.iter())
        .map(|&c| truth.values[c].abs())
        .fold(0.0, f64::max);
    let worst = (terms.iter())
        .map(|&c| (found.estimate.values[c] - truth.values[c]).abs())
        .fold(0.0, f64::max);
    // The calibrated robot carries them: its maps hold the half backlashes found.
    let robot = mapped.robot_at(&found.estimate.values).unwrap();
    let maps = robot.error_maps().unwrap();
    for (c, p) in mapped.parameters().iter().enumerate() {
        if let Target::Backlash { joint } = p.target {
            assert_eq!(maps[joint].backlash(), found.estimate.values[c]);
        }
    }
    // A URDF cannot hold them, and says so.
    let left = super::robot_file::urdf_leaves_out(&mapped, &found.estimate).unwrap();
    assert!(
        left.contains("error maps and their half backlashes of joints 1, 2, 3, 4, 5, 6"),
        "{left}"
    );
    eprintln!("worst {:e} relative", worst / largest);
    worst / largest
}

#[test]
fn backlash_is_recovered_to_1e_9_noise_free_alone() {
    let worst = recovered([0; 6]);
    assert!(worst <= 1e-9, "{worst:e} relative");
}

#[test]
fn backlash_is_recovered_to_1e_9_noise_free_with_cyclic_maps() {
    let worst = recovered([3, 8, 4, 0, 2, 5]);
    assert!(worst <= 1e-9, "{worst:e} relative");
}

#[test]
fn the_backlash_columns_match_central_differences() {
    let geometry = three_points();
    let qs = whole_turns(6, 2);
    let kept = identified(&geometry, &qs);
    let terms = JointMaps {
        harmonics: [2, 0, 1, 0, 0, 2],
        backlash: [true, true, false, true, true, true],
    };
    let mapped = geometry.with_maps(terms).unwrap();
    let x = with_backlash(&mapped, truth(&mapped, &kept, 2e-2, 9));
    let data = approached(&mapped, &x, &qs, 4);
    let j = mapped.jacobian_of(&x.values, &data).unwrap();
    for (c, p) in mapped.parameters().iter().enumerate() {
        if let Target::Backlash { joint } = p.target {
            // A backlash column is the joint's column times the direction: never zero here.
            assert!(j.column(c).amax() > 1e-3, "joint {}", joint + 1);
        }
    }
    super::tests::matches_central_differences(&mapped, &x.values, &j, |v: &DVector<f64>| {
        mapped.predict(v, &data).unwrap()
    });
}

/// The choice (auto, directions read) on a UR10 campaign of 60 postures read at one point with
/// a half backlash `b` (rad) on joint 2 and no map, tracker noise 0.02 mm per coordinate.
fn choose(b: f64, seed: u64) -> maps::Choice {
    let geometry = model();
    let qs = postures(geometry.robot(), 60, 200 + seed);
    let kept = identified(&geometry, &qs);
    let terms = JointMaps {
        harmonics: [0; 6],
        backlash: [false, true, false, false, false, false],
    };
    let mapped = geometry.clone().with_maps(terms).unwrap();
    let mut truth = truth(&mapped, &kept, 0.0, seed);
    let last = truth.values.len() - 1;
    truth.values[last] = b;
    let data = noisy(approached(&mapped, &truth, &qs, seed), 2e-5, seed);
    let start = fit::start(&geometry, &data).unwrap();
    let fitted = fit::fit(&geometry, &data, &start, &options(0.0)).unwrap();
    let linear = Linear::at(&geometry, &fitted, &data, 1.0, Spec::Auto.candidates(true)).unwrap();
    let all: Vec<usize> = (0..qs.len()).collect();
    maps::choose(&linear, &all, Spec::Auto).unwrap()
}

#[test]
fn the_choice_keeps_no_backlash_on_a_robot_without_one() {
    let seeds = 20usize;
    let none = (0..seeds as u64)
        .filter(|&s| !choose(0.0, s).maps.backlash.contains(&true))
        .count();
    eprintln!("no backlash in {none} of {seeds} seeds");
    assert!(
        none * 10 >= seeds * 9,
        "no backlash in {none} of {seeds} seeds"
    );
}

#[test]
fn the_choice_finds_a_backlash_that_pays() {
    // Half a backlash of 0.1 mrad on joint 2 moves the point by about 0.1 mm either way.
    let choice = choose(1e-4, 1);
    let want = JointMaps {
        harmonics: [0; 6],
        backlash: [false, true, false, false, false, false],
    };
    assert_eq!(choice.maps, want, "{choice:?}");
    assert!(choice.rms < 0.5 * choice.none_rms, "{choice:?}");
    assert!(
        (choice.tried.iter()).any(|t| t.kept && maps::name(&t.maps) == "J2:b"),
        "{choice:?}"
    );
}
