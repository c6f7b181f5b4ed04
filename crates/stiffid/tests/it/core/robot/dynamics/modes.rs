use nalgebra::{Matrix6, Vector6};
use stiffid_core::robot::dynamics::modes::*;

#[test]
fn two_uncoupled_springs_ring_at_sqrt_k_over_m() {
    let m = Matrix6::from_diagonal(&Vector6::new(2.0, 3.0, 1.0, 4.0, 5.0, 6.0));
    let k = Vector6::new(800.0, 300.0, 900.0, 100.0, 500.0, 2400.0);
    let c = Matrix6::from_diagonal(&k.map(|k| 1.0 / k));
    let modes = modes(&m, &c).expect("positive definite");
    let mut expected: Vec<f64> = (0..6)
        .map(|i| (k[i] / m[(i, i)]).sqrt() / std::f64::consts::TAU)
        .collect();
    expected.sort_by(f64::total_cmp);
    for (f, e) in modes.frequencies.iter().zip(&expected) {
        assert!((f - e).abs() < 1e-12 * e, "{f} vs {e}");
    }
    // 5 rad/s (k 100, m 4) is the lowest: a motion of joint 4 alone.
    assert!((modes.shapes[0] - Vector6::new(0.0, 0.0, 0.0, 1.0, 0.0, 0.0)).norm() < 1e-12);
}

#[test]
fn a_singular_mass_matrix_has_no_modes() {
    let m = Matrix6::from_diagonal(&Vector6::new(1.0, 1.0, 1.0, 1.0, 1.0, 0.0));
    assert!(modes(&m, &Matrix6::identity()).is_none());
}
