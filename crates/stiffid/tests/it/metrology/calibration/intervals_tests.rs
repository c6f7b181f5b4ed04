//! The calibration's prediction intervals: the linearised leave-one-posture-out equals the
//! refitted one to a small share of the held-out error, and the jackknife+ intervals cover
//! held-out postures at their level where the residual noise alone does not.

use super::error_model::Observation;
use super::fit;
use super::intervals::{coverage, Intervals};
use super::maps_tests::{identified, model, noisy, options, truth};
use super::tests::{postures, readings};
use super::validation::{
    cross_validate, leave_one_out, leave_one_out_linearised, pooled, validate,
};
use super::ErrorModel;

/// A UR10 campaign of `n` fitted and `held` held-out postures (one point, tracker noise
/// 0.02 mm) of a robot whose joints 2 and 5 carry cyclic errors of `amplitude` (rad) that the
/// geometric model fitted does not hold: the geometry, its fit and the readings.
fn campaign(
    n: usize,
    held: usize,
    amplitude: f64,
    seed: u64,
) -> (ErrorModel, fit::Fit, Vec<Observation>, Vec<Observation>) {
    let geometry = model();
    let qs = postures(geometry.robot(), n + held, 500 + seed);
    let kept = identified(&geometry, &qs[..n]);
    let mapped = geometry.clone().with_maps([0, 8, 0, 0, 4, 0]).unwrap();
    let truth = truth(&mapped, &kept, amplitude, seed);
    let all = noisy(readings(&mapped, &truth, &qs), 2e-5, seed);
    let (fitted, mut out): (Vec<_>, Vec<_>) = all.into_iter().partition(|o| o.posture < n);
    for o in &mut out {
        o.posture -= n;
    }
    let start = fit::start(&geometry, &fitted).unwrap();
    let fit = fit::fit(&geometry, &fitted, &start, &options(0.0)).unwrap();
    (geometry, fit, fitted, out)
}

#[test]
fn the_linearised_folds_equal_the_refitted_ones() {
    let (model, fit, data, _) = campaign(40, 0, 2e-4, 1);
    let exact = leave_one_out(&model, &data, &fit.estimate, &options(0.0), &()).unwrap();
    let linear = leave_one_out_linearised(&model, &data, &fit, &options(0.0)).unwrap();
    let (exact, linear) = (pooled(&exact), pooled(&linear));
    // The held-out errors, about 0.2 mm: each within 15 % of their RMS (the refitted folds
    // move weakly determined parameters far enough for the second order to show), their RMS
    // within 2 %.
    let worst = (exact.errors.iter().zip(&linear.errors))
        .map(|(a, b)| (a.error - b.error).norm())
        .fold(0.0, f64::max);
    assert!(exact.rms > 1e-4, "{}", exact.rms);
    assert!(worst < 0.15 * exact.rms, "{worst:e} vs RMS {:e}", exact.rms);
    assert!(
        (linear.rms / exact.rms - 1.0).abs() < 0.02,
        "{:e} vs {:e}",
        linear.rms,
        exact.rms
    );
}

#[test]
fn the_one_step_cross_validation_equals_the_refitted_one() {
    let (model, fit, data, _) = campaign(40, 0, 2e-4, 1);
    let exact = leave_one_out(&model, &data, &fit.estimate, &options(0.0), &()).unwrap();
    let exact = pooled(&exact);
    let step = cross_validate(&model, &data, &fit, &options(0.0), &()).unwrap();
    // One Gauss-Newton step from the full fit, the held-out posture on the model itself: the
    // same postures in the same order, each error within 15 % of their RMS, the RMS within 2 %.
    assert_eq!(step.errors.len(), exact.errors.len());
    let worst = (exact.errors.iter().zip(&step.errors))
        .map(|(a, b)| {
            assert_eq!((a.posture, a.point), (b.posture, b.point));
            (a.error - b.error).norm()
        })
        .fold(0.0, f64::max);
    assert!(exact.rms > 1e-4, "{}", exact.rms);
    assert!(worst < 0.15 * exact.rms, "{worst:e} vs RMS {:e}", exact.rms);
    assert!(
        (step.rms / exact.rms - 1.0).abs() < 0.02,
        "{:e} vs {:e}",
        step.rms,
        exact.rms
    );
}

#[test]
fn the_intervals_cover_held_out_postures_at_their_level() {
    let level = 0.9;
    let (mut covered, mut coordinates, mut noise_covered) = (0, 0, 0);
    for seed in 0..10 {
        let (model, fit, data, out) = campaign(60, 300, 2e-4, seed);
        let folds = leave_one_out_linearised(&model, &data, &fit, &options(0.0)).unwrap();
        let intervals = Intervals::new(&folds);
        let bounds = intervals
            .of(&model, &fit.estimate, &out, level, false)
            .unwrap();
        let held = validate(&model, &fit.estimate, &out).unwrap();
        let errors: Vec<_> = held.errors.iter().map(|e| e.error).collect();
        let c = coverage(&bounds, &errors, level, intervals.folds());
        covered += c.covered;
        coordinates += c.coordinates;
        // The residual noise alone: +-1.645 sigma of the fit.
        noise_covered += (errors.iter())
            .flat_map(|e| {
                e.iter()
                    .map(|v| v.abs() <= 1.645 * fit.sigma)
                    .collect::<Vec<_>>()
            })
            .filter(|b| *b)
            .count();
    }
    let share = covered as f64 / coordinates as f64;
    let noise = noise_covered as f64 / coordinates as f64;
    assert_eq!(coordinates, 10 * 300 * 3);
    eprintln!("coverage {share:.4}, the residual noise's {noise:.4}");
    assert!(
        (share - level).abs() <= 0.03,
        "coverage {share:.4} at {level}"
    );
    // The residuals understate the held-out error: the noise's interval covers less.
    assert!(
        noise < share - 0.02,
        "noise alone {noise:.4}, jackknife+ {share:.4}"
    );
}

#[test]
fn the_linearised_intervals_with_maps_cover_at_their_level() {
    // The maps fitted (joints 2 and 5 at the true harmonics, under a ridge): the linearised folds
    // carry the ridge rows, and the intervals cover held-out postures at their level.
    let level = 0.9;
    let (mut covered, mut coordinates) = (0, 0);
    for seed in 0..10 {
        let (geometry, fit, data, out) = campaign(60, 300, 2e-4, seed);
        let mapped = geometry.with_maps([0, 8, 0, 0, 4, 0]).unwrap();
        let ridged = options(1e-5);
        let start = super::maps::extended(&mapped, &fit.estimate);
        let fit = fit::fit(&mapped, &data, &start, &ridged).unwrap();
        let folds = leave_one_out_linearised(&mapped, &data, &fit, &ridged).unwrap();
        assert!(folds.iter().all(|f| f.change.is_some()));
        let intervals = Intervals::new(&folds);
        let bounds = intervals
            .of(&mapped, &fit.estimate, &out, level, false)
            .unwrap();
        let held = validate(&mapped, &fit.estimate, &out).unwrap();
        // The maps fitted: the held-out error is near the tracker noise (0.02 mm per coordinate).
        assert!(held.rms < 1e-4, "seed {seed}: {:e}", held.rms);
        let errors: Vec<_> = held.errors.iter().map(|e| e.error).collect();
        let c = coverage(&bounds, &errors, level, intervals.folds());
        covered += c.covered;
        coordinates += c.coordinates;
    }
    let share = covered as f64 / coordinates as f64;
    eprintln!("coverage with maps {share:.4}");
    assert!(
        (share - level).abs() <= 0.03,
        "coverage {share:.4} at {level}"
    );
}
