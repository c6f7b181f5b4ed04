//! The registration design (`crate::registration`): its criterion against the SVD.

use crate::registration::*;
use nalgebra::Vector3;

#[test]
fn the_criterion_from_moments_equals_the_covariance_by_svd() {
    let setup = stiffid_core::setup::builtin("zhang2021-comau-nj165").unwrap();
    let group = crate::random_group(&setup, 4, 5);
    let all: Vec<Vector3<f64>> = group.iter().flat_map(|q| points(&setup, q, &[])).collect();
    let moments: Vec<Moments> = group
        .iter()
        .map(|q| Moments::of(&points(&setup, q, &[])))
        .collect();
    let fast = criterion(moments.iter());
    let svd = stiffid_metrology::register::rotation_std_per_noise(&all);
    assert!((fast - svd).abs() < 1e-9 * svd, "{fast} vs {svd}");
    let one_point = [Moments::of(&all[..1])];
    assert!(criterion(one_point.iter()).is_infinite());
}
