//! Cell calibration: the tracker transform and the measuring points fitted together from
//! unloaded readings simulated on the paper setup.

use crate::common::{deg, PAPER_POSTURES_DEG};
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use stiffid::metrology::calibrate::{self, Observation};
use stiffid::Setup;

fn paper() -> Setup {
    stiffid::setup::builtin("zhang2021-comau-nj165").unwrap()
}

fn truth() -> Isometry3<f64> {
    Isometry3::new(Vector3::new(3.0, -2.0, 0.4), Vector3::new(0.02, -0.01, 2.5))
}

/// The unloaded readings of the six paper postures with every measuring point shifted by
/// `shift(k)` from the setup's, noise of `noise_m` per coordinate.
fn readings(
    setup: &Setup,
    shift: impl Fn(usize) -> Vector3<f64>,
    noise_m: f64,
    seed: u64,
) -> Vec<Observation> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let normal = Normal::new(0.0, noise_m.max(1e-300)).unwrap();
    let mut out = Vec::new();
    for q in PAPER_POSTURES_DEG.iter() {
        let flange = setup.robot().frames(&deg(q)).flange;
        for (k, c) in setup.tool().measuring_points.iter().enumerate() {
            let base = flange * Point3::from(c + shift(k));
            let mut tracker = (truth().inverse() * base).coords;
            if noise_m > 0.0 {
                tracker += Vector3::from_fn(|_, _| normal.sample(&mut rng));
            }
            out.push(Observation {
                point: k,
                flange,
                tracker,
            });
        }
    }
    out
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
fn the_analytic_jacobian_matches_finite_differences() {
    let setup = paper();
    let obs = readings(&setup, shift, 0.0, 1);
    let points = setup.tool().measuring_points.clone();
    let read = vec![Some(6), Some(9), Some(12), Some(15)];
    let t = truth();
    let j = calibrate::jacobian(&obs, &t, &read);
    let step = 1e-6;
    for c in 0..j.ncols() {
        let perturbed = |sign: f64| {
            let mut dx = nalgebra::DVector::zeros(j.ncols());
            dx[c] = sign * step;
            let transform = Isometry3::from_parts(
                Translation3::from(t.translation.vector + dx.fixed_rows::<3>(0)),
                UnitQuaternion::from_scaled_axis(dx.fixed_rows::<3>(3).into_owned()) * t.rotation,
            );
            let mut p = points.clone();
            for (k, col) in read.iter().enumerate() {
                p[k] += dx.fixed_rows::<3>(col.unwrap());
            }
            calibrate::residuals(&obs, &transform, &p)
        };
        let fd = (perturbed(1.0) - perturbed(-1.0)) / (2.0 * step);
        let error = (fd - j.column(c)).amax();
        assert!(error < 1e-7, "column {c}: {error}");
    }
}

#[test]
fn tool_points_shifted_by_2_mm_are_corrected() {
    let setup = paper();
    let points = &setup.tool().measuring_points;
    let exact = calibrate::fit(&readings(&setup, shift, 0.0, 1), points).unwrap();
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
    // With the paper's tracker noise: each shift within 4 standard deviations of the truth, and
    // the standard deviations close to a Monte Carlo's.
    let sigma = setup.noise().reading_sd();
    let runs = 200;
    let mut errors = [Vector3::zeros(); 4];
    let mut predicted = [Vector3::zeros(); 4];
    for seed in 0..runs {
        let fit = calibrate::fit(&readings(&setup, shift, sigma, seed), points).unwrap();
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

#[test]
fn one_flange_orientation_is_refused() {
    let setup = paper();
    let mut obs = readings(&setup, shift, 0.0, 1);
    let first = obs[0].flange;
    for (i, o) in obs.iter_mut().enumerate() {
        o.flange = Isometry3::from_parts(
            Translation3::from(first.translation.vector + Vector3::new(0.1 * i as f64, 0.0, 0.0)),
            first.rotation,
        );
    }
    let e = calibrate::fit(&obs, &setup.tool().measuring_points)
        .unwrap_err()
        .to_string();
    assert!(e.contains("postures that turn the flange"), "{e}");
}
