//! The statistics of the drift check ([`super::drift`]).

use super::drift::{allowed, noise_length};

#[test]
fn the_noise_floor_is_the_chi_quantile_of_three_coordinates() {
    // Tables: chi-square with 3 degrees of freedom, 7.8147 at 95 %, 11.3449 at 99 %.
    assert!((noise_length(1e-5, 0.95) - 1e-5 * 7.8147f64.sqrt()).abs() < 1e-9);
    assert!((noise_length(2e-5, 0.99) - 2e-5 * 11.3449f64.sqrt()).abs() < 1e-9);
    assert_eq!(noise_length(0.0, 0.95), 0.0);
}

#[test]
fn allowed_is_the_binomial_critical_count() {
    // n = 10, p = 0.05: P(X >= 3) = 0.0115 > 0.01, P(X >= 4) = 0.00103.
    assert_eq!(allowed(10, 0.05, 0.01), 3);
    // n = 1: P(X >= 1) = 0.05 > 0.01.
    assert_eq!(allowed(1, 0.05, 0.01), 1);
    assert_eq!(allowed(10, 0.0, 0.01), 0);
    // n = 100000, p = 0.05: mean 5000, sd 68.9; the 99 % quantile near 5000 + 2.33 sd.
    let k = allowed(100_000, 0.05, 0.01);
    assert!((5155..=5165).contains(&k), "{k}");
}
