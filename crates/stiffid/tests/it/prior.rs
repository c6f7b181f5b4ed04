//! Starting values for a new setup: the characteristic length minimises the median dexterity.

use nalgebra::{Matrix6, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use stiffid::internal::robot::kinematics::{dexterity, Coordinates};
use stiffid::internal::{setup, setup::prior};

/// The median dexterity of the paper setup's TCP over 2000 postures of its own seeded sample.
fn median_at(jacobians: &[Matrix6<f64>], l: f64) -> f64 {
    let mut k: Vec<f64> = jacobians.iter().map(|j| dexterity(j, l)).collect();
    k.sort_by(f64::total_cmp);
    k[k.len() / 2]
}

#[test]
fn the_paper_setup_gets_about_1_2_m_and_it_minimises_the_median_dexterity() {
    let s = setup::builtin("zhang2021-comau-nj165").unwrap();
    let (lower, upper) = (s.bounds().lower, s.bounds().upper);
    let l = prior::characteristic_length(s.robot(), &lower, &upper, &s.tool().tcp, 1).unwrap();
    assert!((1.0..1.4).contains(&l), "L = {l} m");
    // An independent sample (another generator, 4x the postures) agrees that L is the minimum.
    let mut rng = ChaCha8Rng::seed_from_u64(99);
    let jacobians: Vec<Matrix6<f64>> = (0..2000)
        .map(|_| {
            let q = Vector6::from_fn(|a, _| rng.random_range(lower[a]..=upper[a]));
            s.robot()
                .frames(&q)
                .jacobian(&s.tool().tcp, Coordinates::Axis)
        })
        .collect();
    let at_l = median_at(&jacobians, l);
    for other in [0.7 * l, 1.4 * l] {
        assert!(median_at(&jacobians, other) > at_l, "{other} m beats {l} m");
    }
}

#[test]
fn bad_bounds_are_refused_with_the_axis() {
    let s = setup::builtin("zhang2021-comau-nj165").unwrap();
    let mut lower = s.bounds().lower;
    lower[2] = f64::NAN;
    let e = prior::characteristic_length(s.robot(), &lower, &s.bounds().upper, &s.tool().tcp, 1);
    assert!(e.unwrap_err().to_string().contains("axis 3"));
}
