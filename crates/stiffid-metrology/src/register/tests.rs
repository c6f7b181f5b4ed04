//! The tracker's registration to the robot base (`crate::register`): the
//! transform, its standard deviation against Monte Carlo, and the suspect readings refused.

use crate::register::*;
use nalgebra::{Isometry3, Point3, Vector3, Vector6};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

fn truth() -> Isometry3<f64> {
    Isometry3::new(Vector3::new(3.2, -1.9, 0.4), Vector3::new(0.2, -0.1, 2.8))
}

/// Six points spread over a robot's reach, tracker frame, m.
fn tracker_points() -> Vec<Vector3<f64>> {
    let b = [
        [1.8, -0.6, 0.4],
        [2.2, 0.7, 1.6],
        [1.4, 0.2, 2.1],
        [2.5, -0.3, 1.0],
        [1.1, 0.9, 0.8],
        [1.9, 0.0, 2.4],
    ];
    let inv = truth().inverse();
    b.iter()
        .map(|p| (inv * Point3::from(Vector3::from(*p))).coords)
        .collect()
}

fn pairs(noise: impl FnMut() -> Vector3<f64>) -> Vec<Correspondence> {
    let mut noise = noise;
    tracker_points()
        .into_iter()
        .map(|t| Correspondence {
            base: (truth() * Point3::from(t)).coords,
            tracker: t + noise(),
        })
        .collect()
}

#[test]
fn noise_free_points_give_the_transform_back() {
    let r = fit(&pairs(Vector3::zeros)).unwrap();
    let back = r.base_from_tracker;
    for t in tracker_points() {
        let p = Point3::from(t);
        assert!(((back * p) - (truth() * p)).norm() < 1e-12, "1e-9 mm");
    }
    assert!(r.rms < 1e-12);
    assert!(back.rotation.angle_to(&truth().rotation) < 1e-12);
}

#[test]
fn a_reflection_is_refused() {
    let mirrored: Vec<Correspondence> = pairs(Vector3::zeros)
        .into_iter()
        .map(|c| Correspondence {
            tracker: Vector3::new(-c.tracker.x, c.tracker.y, c.tracker.z),
            ..c
        })
        .collect();
    let r = fit(&mirrored).unwrap();
    assert!(
        (r.base_from_tracker
            .rotation
            .to_rotation_matrix()
            .matrix()
            .determinant()
            - 1.0)
            .abs()
            < 1e-12
    );
    assert!(r.rms > 0.1, "a rotation cannot fit a mirror image");
    assert!(r.mirror_rms < 1e-12, "a reflection fits it exactly");
    let s = suspect(&r.residuals, r.rms, r.mirror_rms, 1e-5);
    assert!(matches!(s, Some(Suspect::Mirrored { .. })), "{s:?}");
    // The true readings, with noise: neither mirrored nor beyond the limit.
    let normal = Normal::new(0.0, 1e-5).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let r = fit(&pairs(|| Vector3::from_fn(|_, _| normal.sample(&mut rng)))).unwrap();
    assert!(r.mirror_rms > 0.1, "{}", r.mirror_rms);
    assert_eq!(suspect(&r.residuals, r.rms, r.mirror_rms, 1e-5), None);
}

#[test]
fn a_residual_beyond_the_limit_is_named() {
    let mut points = pairs(Vector3::zeros);
    points[4].tracker.z += 0.05;
    let r = fit(&points).unwrap();
    let Some(Suspect::Residual {
        index,
        length,
        limit,
    }) = suspect(&r.residuals, r.rms, r.mirror_rms, 1e-5)
    else {
        panic!("not flagged")
    };
    assert_eq!((index, limit), (4, RESIDUAL_LIMIT));
    assert!(length > 0.03 && length < 0.05, "{length}");
    // The same residual at a noise of 0.1 mm is within 1000 sigma.
    assert_eq!(suspect(&r.residuals, r.rms, r.mirror_rms, 1e-4), None);
    assert_eq!(residual_limit(1e-4), 0.1);
}

#[test]
fn standard_deviation_matches_monte_carlo() {
    let sigma = 0.01e-3 * 9.23f64.sqrt();
    let normal = Normal::new(0.0, sigma).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let runs = 1000;
    let (mut sum_sq, mut predicted) = (Vector6::zeros(), Vector6::zeros());
    for _ in 0..runs {
        let mut noise = || Vector3::from_fn(|_, _| normal.sample(&mut rng));
        let r = fit(&pairs(&mut noise)).unwrap();
        let dp = r.base_from_tracker.translation.vector - truth().translation.vector;
        let dr = (r.base_from_tracker.rotation * truth().rotation.inverse()).scaled_axis();
        let x = Vector6::new(dp.x, dp.y, dp.z, dr.x, dr.y, dr.z);
        sum_sq += x.component_mul(&x);
        predicted += r.std();
    }
    let monte_carlo = (sum_sq / runs as f64).map(f64::sqrt);
    let rotated: Vec<_> = tracker_points()
        .iter()
        .map(|t| truth().rotation * t)
        .collect();
    let analytic = (unit_covariance(&rotated).unwrap() * sigma * sigma)
        .diagonal()
        .map(f64::sqrt);
    let mean_reported = predicted / runs as f64;
    for k in 0..6 {
        let ratio = analytic[k] / monte_carlo[k];
        assert!((ratio - 1.0).abs() < 0.1, "parameter {k}: {ratio}");
        // The residual estimate of sigma has 12 degrees of freedom: E[s] = 0.979 sigma.
        let ratio = mean_reported[k] / monte_carlo[k];
        assert!(
            (ratio - 1.0).abs() < 0.1,
            "reported, parameter {k}: {ratio}"
        );
    }
}

#[test]
fn collinear_and_too_few_points_are_refused() {
    let line: Vec<Correspondence> = (0..5)
        .map(|i| {
            let t = Vector3::new(0.3 * i as f64, 0.1, 0.2);
            Correspondence {
                base: (truth() * Point3::from(t)).coords,
                tracker: t,
            }
        })
        .collect();
    let e = fit(&line).unwrap_err().to_string();
    assert!(e.contains("lie on one line"), "{e}");
    let nearly: Vec<Correspondence> = line
        .iter()
        .enumerate()
        .map(|(i, c)| Correspondence {
            tracker: c.tracker + Vector3::new(0.0, 1e-8 * i as f64 * (i as f64 - 2.0), 0.0),
            ..*c
        })
        .collect();
    assert!(fit(&nearly).is_err());
    let e = fit(&line[..2]).unwrap_err().to_string();
    assert!(e.contains("at least 3 points"), "{e}");
    let mut nan = pairs(Vector3::zeros);
    nan[3].tracker.y = f64::NAN;
    let e = fit(&nan).unwrap_err().to_string();
    assert_eq!(e, "points[4]: expected finite coordinates");
    assert!(rotation_std_per_noise(&line.iter().map(|c| c.base).collect::<Vec<_>>()).is_infinite());
}

#[test]
fn the_fragment_reads_back_as_the_setup_reads_it() {
    let r = fit(&pairs(Vector3::zeros)).unwrap();
    let text = stiffid_core::setup::builtin_text("zhang2021-comau-nj165")
        .unwrap()
        .to_string()
        + "\n"
        + &r.fragment();
    let setup =
        stiffid_core::setup::parse(&text, "s.toml", |n, _| stiffid_core::robot::presets::get(n))
            .unwrap();
    let back = setup.tracker().unwrap().base_from_tracker.unwrap();
    assert!((back.translation.vector - truth().translation.vector).norm() < 1e-8);
    assert!(back.rotation.angle_to(&truth().rotation) < 1e-7);
}
