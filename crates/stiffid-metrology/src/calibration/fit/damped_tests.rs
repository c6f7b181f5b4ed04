//! The damped steps from the bidiagonal form equal the SVD's `-V diag(s / (s^2 + lambda)) U^T
//! Q^T r` of the same factor, for a full-rank, a rank-deficient and a wide factor: the same
//! damped cost `|R dx + Q^T r|^2 + lambda |dx|^2` to 1e-12, the same step to 1e-9 (1e-6 below a
//! damping of 1e-6, where a rank-deficient factor's step is ill-conditioned).

use super::Damped;
use nalgebra::{DMatrix, DVector};

/// A `k x n` upper-trapezoidal factor of mixed sizes and signs.
fn factor(k: usize, n: usize) -> DMatrix<f64> {
    DMatrix::from_fn(k, n, |i, j| match i <= j {
        true => (0.3 + 0.71 * (i * n + j) as f64).sin() * 10f64.powi((j % 4) as i32 - 1),
        false => 0.0,
    })
}

/// The step of the SVD formula.
fn by_svd(r: &DMatrix<f64>, qtr: &DVector<f64>, lambda: f64) -> DVector<f64> {
    let svd = r.clone().svd(true, true);
    let (u, v_t) = (svd.u.unwrap(), svd.v_t.unwrap());
    let g = u.tr_mul(qtr);
    let w = DVector::from_fn(svd.singular_values.len(), |i, _| {
        let s = svd.singular_values[i];
        -s * g[i] / (s * s + lambda)
    });
    v_t.transpose() * w
}

#[test]
fn damped_steps_equal_the_svd_formula() {
    let mut deficient = factor(12, 12);
    let copy = deficient.column(3).into_owned();
    deficient.set_column(7, &copy);
    for r in [factor(12, 12), deficient, factor(5, 9)] {
        let qtr = DVector::from_fn(r.nrows(), |i, _| (1.3 * i as f64).cos());
        let damped = Damped::new(r.clone(), &qtr).unwrap();
        for lambda in [1e-12, 1e-6, 1e-2, 1.0, 1e3] {
            let (ours, svd) = (damped.step(lambda), by_svd(&r, &qtr, lambda));
            let cost =
                |dx: &DVector<f64>| (&r * dx + &qtr).norm_squared() + lambda * dx.norm_squared();
            let shape = format!("{}x{} at {lambda:e}", r.nrows(), r.ncols());
            let (a, b) = (cost(&ours), cost(&svd));
            assert!((a - b).abs() <= 1e-12 * b, "{shape}: cost {a} against {b}");
            // Below a damping of 1e-6 a rank-deficient factor's step is as ill-conditioned as
            // the SVD's own: their costs agree, their steps to the conditioning.
            let tolerance = if lambda >= 1e-6 { 1e-9 } else { 1e-6 };
            let d = (&ours - &svd).norm() / svd.norm();
            assert!(d < tolerance, "{shape}: step {ours} against {svd}");
        }
    }
}

#[test]
fn a_factor_not_finite_is_an_error_not_a_step() {
    let mut r = factor(4, 4);
    r[(1, 2)] = f64::NAN;
    assert!(Damped::new(r, &DVector::zeros(4)).is_err());
}
