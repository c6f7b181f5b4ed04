//! The error budget (`crate::compensate::budget`).

use crate::compensate::budget::*;
use nalgebra::Matrix3;

#[test]
fn the_length_quantile_is_exact_for_equal_and_single_eigenvalues() {
    // One axis: |e| = sigma |z|, the 95% quantile 1.959964 sigma.
    let one = Matrix3::from_diagonal(&nalgebra::Vector3::new(4.0, 0.0, 0.0));
    assert!((length_quantile(&one, 0.95) - 2.0 * 1.959964).abs() < 1e-5);
    // Isotropic: |e|^2 = sigma^2 chi^2_3, the 95% quantile sqrt(7.814728) sigma.
    let iso = Matrix3::identity() * 9.0;
    assert!((length_quantile(&iso, 0.95) - 3.0 * 7.814728f64.sqrt()).abs() < 1e-5);
    assert_eq!(length_quantile(&Matrix3::zeros(), 0.95), 0.0);
}

#[test]
fn the_bound_adds_the_systematic_parts_to_the_random_ones_in_quadrature() {
    let b = Budget::new(1e-7, Some(3e-5), Some(4e-5), 2e-5, None);
    assert!((b.bound - (1e-7 + 2e-5 + 5e-5)).abs() < 1e-15);
    assert_eq!(b.dominant(), ("calibration", 4e-5));
    let none = Budget::new(0.0, None, None, 1e-5, None);
    assert_eq!(none.bound, 1e-5);
    assert_eq!(none.dominant().0, "force");
}
