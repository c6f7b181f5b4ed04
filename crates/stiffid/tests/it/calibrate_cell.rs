//! Cell calibration: the tracker transform and the measuring points fitted together from
//! unloaded readings simulated on the paper setup (the robot calibration without joint errors or
//! gravity terms).

use crate::common::{deg, PAPER_POSTURES_DEG};
use nalgebra::{Isometry3, Point3, Vector3, Vector6};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use stiffid::internal::metrology::calibration::error_model::Observation;
use stiffid::internal::metrology::cell_calibration;
use stiffid::Setup;

fn paper() -> Setup {
    stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap()
}

fn truth() -> Isometry3<f64> {
    Isometry3::new(Vector3::new(3.0, -2.0, 0.4), Vector3::new(0.02, -0.01, 2.5))
}

/// The unloaded readings at `postures` (axis angles, rad) with every measuring point shifted by
/// `shift(k)` from the setup's, noise of `noise_m` per coordinate.
fn readings_at(
    setup: &Setup,
    postures: &[Vector6<f64>],
    shift: impl Fn(usize) -> Vector3<f64>,
    noise_m: f64,
    seed: u64,
) -> Vec<Observation> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let normal = Normal::new(0.0, noise_m.max(1e-300)).unwrap();
    let mut out = Vec::new();
    for (i, q) in postures.iter().enumerate() {
        let flange = setup.robot().frames(q).flange;
        for (k, c) in setup.tool().measuring_points.iter().enumerate() {
            let base = flange * Point3::from(c + shift(k));
            let mut tracker = (truth().inverse() * base).coords;
            if noise_m > 0.0 {
                tracker += Vector3::from_fn(|_, _| normal.sample(&mut rng));
            }
            out.push(Observation {
                posture: i,
                point: k,
                q: *q,
                measured: tracker,
                wrench: Vector6::zeros(),
                e: stiffid::internal::robot::external::ExternalValues::NONE,
                table: false,
                direction: Vector6::zeros(),
            });
        }
    }
    out
}

/// [`readings_at`] the six paper postures.
fn readings(
    setup: &Setup,
    shift: impl Fn(usize) -> Vector3<f64>,
    noise_m: f64,
    seed: u64,
) -> Vec<Observation> {
    let postures: Vec<_> = PAPER_POSTURES_DEG.iter().map(deg).collect();
    readings_at(setup, &postures, shift, noise_m, seed)
}

fn shift(k: usize) -> Vector3<f64> {
    // 2 mm in a different direction for each point.
    let d = [
        Vector3::x(),
        Vector3::y(),
        Vector3::z(),
        Vector3::new(1.0, -1.0, 1.0).normalize(),
    ];
    d[k % 4] * 2e-3
}

#[test]
fn tool_points_shifted_by_2_mm_are_corrected() {
    let setup = paper();
    let exact = cell_calibration::fit(&setup, &readings(&setup, shift, 0.0, 1)).unwrap();
    for k in 0..4 {
        assert!(
            (exact.shifts[k] - shift(k)).amax() < 1e-9,
            "{}",
            exact.shifts[k]
        );
    }
    assert!(exact.rms < 1e-9);
    assert!(
        (exact.base_from_tracker.translation.vector - truth().translation.vector).amax() < 1e-9
    );
    // With the paper's tracker noise: each shift within 5 standard deviations of the truth, and
    // the standard deviations (of the points, and of the transform's translation and rotation)
    // close to a Monte Carlo's.
    let sigma = setup.noise().reading_sd();
    let runs = 200;
    let mut errors = [Vector3::zeros(); 4];
    let mut predicted = [Vector3::zeros(); 4];
    let (mut transform_errors, mut transform_predicted) = ([0.0; 6], [0.0; 6]);
    for seed in 0..runs {
        let fit = cell_calibration::fit(&setup, &readings(&setup, shift, sigma, seed)).unwrap();
        let t = fit.base_from_tracker;
        let dp = t.translation.vector - truth().translation.vector;
        let dtheta = (t.rotation * truth().rotation.inverse()).scaled_axis();
        for a in 0..6 {
            let e = if a < 3 { dp[a] } else { dtheta[a - 3] };
            transform_errors[a] += e * e / runs as f64;
            transform_predicted[a] += fit.transform_std[a] / runs as f64;
        }
        for k in 0..4 {
            let e = fit.shifts[k] - shift(k);
            let s = fit.point_std[k].unwrap();
            assert!(
                e.iter().zip(s.iter()).all(|(e, s)| e.abs() < 5.0 * s),
                "{e} {s}"
            );
            errors[k] += e.component_mul(&e) / runs as f64;
            predicted[k] += s / runs as f64;
        }
    }
    for a in 0..6 {
        let ratio = transform_errors[a].sqrt() / transform_predicted[a];
        assert!((ratio - 1.0).abs() < 0.15, "transform {a}: {ratio}");
    }
    for k in 0..4 {
        for a in 0..3 {
            let ratio = errors[k][a].sqrt() / predicted[k][a];
            assert!(
                (ratio - 1.0).abs() < 0.15,
                "point {} axis {a}: {ratio}",
                k + 1
            );
        }
    }
}

/// Postures that turn the flange about one axis (joint 1's) cannot tell a point's offset along
/// it from the transform's translation: refused, naming the rank.
#[test]
fn one_flange_orientation_is_refused() {
    let setup = paper();
    let q0 = deg(&PAPER_POSTURES_DEG[0]);
    let postures: Vec<_> = (0..6)
        .map(|i| q0 + Vector6::new(0.2 * i as f64, 0.0, 0.0, 0.0, 0.0, 0.0))
        .collect();
    let obs = readings_at(&setup, &postures, shift, 0.0, 1);
    let e = cell_calibration::fit(&setup, &obs).unwrap_err().to_string();
    assert!(
        e.contains("postures that turn the flange") && e.contains("of the 18 unknowns"),
        "{e}"
    );
}
