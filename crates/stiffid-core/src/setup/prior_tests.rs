//! The priors' tests: the golden-section search and the stiffness prior.

use super::prior::*;

#[test]
fn golden_section_finds_the_minimum_of_a_parabola() {
    let x = golden_section(|x| (x - 0.3).powi(2), -2.0, 5.0, 1e-9);
    assert!((x - 0.3).abs() < 1e-8, "{x}");
}

#[test]
fn the_stiffness_prior_scales_with_the_payload_and_refuses_nonsense() {
    let k = nominal_stiffness(82.5).unwrap();
    assert_eq!(k[1], 1_500_000.0);
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e9] {
        assert!(nominal_stiffness(bad).is_err(), "{bad}");
    }
}
