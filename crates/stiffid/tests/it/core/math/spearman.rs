use stiffid_core::math::{ranks, spearman};

#[test]
fn ties_get_mean_ranks() {
    assert_eq!(ranks(&[3.0, 1.0, 3.0, 2.0]), [3.5, 1.0, 3.5, 2.0]);
}

#[test]
fn spearman_of_monotone_reversed_and_constant_samples() {
    let x = [1.0, 2.0, 3.0, 4.0];
    assert_eq!(spearman(&x, &[10.0, 20.0, 25.0, 100.0]), Some(1.0));
    assert_eq!(spearman(&x, &[4.0, 3.0, 2.0, 1.0]), Some(-1.0));
    assert_eq!(spearman(&x, &[1.0, 1.0, 1.0, 1.0]), None);
    assert_eq!(spearman(&x[..2], &[1.0, 2.0]), None);
    // x ranks 1..5, y ranks 2,1,4,3,5: d^2 = 4, rho = 1 - 6*4/(5*24) = 0.8.
    let rho = spearman(&[1.0, 2.0, 3.0, 4.0, 5.0], &[2.0, 1.0, 4.0, 3.0, 5.0]).unwrap();
    assert!((rho - 0.8).abs() < 1e-12);
}

#[test]
fn spearman_with_ties_by_hand() {
    // x ranks 1, 2.5, 2.5, 4 (mean 2.5): deviations -1.5, 0, 0, 1.5, sum of squares 4.5.
    // y ranks 1, 3, 2, 4: deviations -1.5, 0.5, -0.5, 1.5, sum of squares 5.
    // Cross sum 2.25 + 0 + 0 + 2.25 = 4.5, rho = 4.5 / sqrt(4.5 * 5) = 0.9487 (= sqrt(0.9)).
    let rho = spearman(&[1.0, 2.0, 2.0, 7.0], &[0.1, 0.5, 0.3, 0.9]).unwrap();
    assert!((rho - 0.9f64.sqrt()).abs() < 1e-12, "{rho}");
}
