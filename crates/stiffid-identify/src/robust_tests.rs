//! Robust identification (`crate::robust`): the MAD scale and the reweighting's stops.

use crate::robust::*;
use nalgebra::{DMatrix, DVector};
use stiffid_core::common::stop::Stop;
use stiffid_core::common::warning::WarningKind;
use stiffid_core::Result;

#[test]
fn mad_scale_is_the_median_absolute_residual_times_the_gaussian_factor() {
    // |r| sorted: 0.5 1 2 3 100 -> median 2 (odd count, the outlier does not move it).
    let odd = DVector::from_vec(vec![-1.0, 3.0, 0.5, -100.0, 2.0]);
    assert_eq!(mad_scale(&odd, 100.0), MAD_TO_SIGMA * 2.0);
    // Even count: the mean of the middle two, 1 and 2.
    let even = DVector::from_vec(vec![2.0, -1.0, 0.5, 4.0]);
    assert_eq!(mad_scale(&even, 4.0), MAD_TO_SIGMA * 1.5);
    // 1.4826 is 1 / Phi^-1(3/4): the MAD of N(0, 1) is 0.6744897501960817.
    assert!((MAD_TO_SIGMA * 0.674_489_750_196_081_7 - 1.0).abs() < 1e-15);
}

/// A line `y = a x` through 20 points with two outliers: by plain least squares per step.
fn line_with_outliers() -> (DMatrix<f64>, DVector<f64>) {
    let x = DMatrix::from_fn(20, 1, |i, _| 1.0 + i as f64);
    let noise = |i: usize| 1e-3 * ((i * 7919) % 13) as f64 - 6e-3;
    let mut y = DVector::from_fn(20, |i, _| 2.0 * x[(i, 0)] + noise(i));
    y[3] += 5.0;
    y[11] -= 8.0;
    (x, y)
}

fn solve(a: DMatrix<f64>, b: &DVector<f64>) -> Result<(DVector<f64>, ())> {
    let qr = a.clone().qr();
    let h = qr
        .r()
        .solve_upper_triangular(&(qr.q().transpose() * b))
        .unwrap();
    Ok((h, ()))
}

#[test]
fn the_reweighting_says_why_it_stopped_and_warns_at_its_iteration_limit() {
    let (x, y) = line_with_outliers();
    let start = solve(x.clone(), &y).unwrap().0;
    for loss in [Loss::Huber, Loss::Tukey] {
        // Forced to stop after one step, the compliance is still moving.
        let (h1, _, cut) = iterate(&x, &y, start.clone(), loss, &solve, 1).unwrap();
        assert_eq!((cut.stop, cut.iterations), (Stop::IterationLimit, 1));
        assert!(!cut.converged());
        let warning = cut.warning().unwrap();
        assert_eq!(warning.kind, WarningKind::NotConverged);
        assert!(
            warning
                .message
                .contains("stopped at its limit of 1 iterations"),
            "{}",
            warning.message
        );
        // Left to converge, it meets the tolerance, near the slope 2, and does not warn.
        let (h, _, done) = fit(&x, &y, start.clone(), loss, &solve).unwrap();
        assert_eq!(done.stop, Stop::Converged);
        assert!(done.iterations > 1 && done.iterations < MAX_ITERATIONS);
        assert_eq!(done.warning(), None);
        assert!((h[0] - 2.0).abs() < 1e-3, "{}", h[0]);
        assert!((h1[0] - h[0]).abs() > TOLERANCE * h[0].abs());
    }
}

#[test]
fn mad_scale_of_an_exact_fit_is_floored_above_zero() {
    let exact = DVector::from_vec(vec![0.0, 0.0, 0.0, 1e-3]);
    assert_eq!(mad_scale(&exact, 2.0), f64::EPSILON * 2.0);
    assert_eq!(mad_scale(&DVector::zeros(3), 0.0), f64::MIN_POSITIVE);
}
