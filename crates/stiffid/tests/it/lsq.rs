//! The QR kernels of `lsq::Factor` against nalgebra's SVD: solution, singular values (also of
//! strongly graded matrices, where one-sided Jacobi must keep the small ones accurate), covariance
//! and the rank checks.

use nalgebra::{DMatrix, DVector, Matrix6, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use stiffid::internal::math::lsq::{Factor, Reduced};
use stiffid::Error;

/// A random m x 6 matrix whose columns have the given scales.
fn random(m: usize, scales: [f64; 6], seed: u64) -> DMatrix<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    DMatrix::from_fn(m, 6, |_, j| rng.random_range(-1.0..1.0) * scales[j])
}

fn sorted(v: &Vector6<f64>) -> Vector6<f64> {
    let mut s = *v;
    s.as_mut_slice().sort_by(f64::total_cmp);
    s
}

#[test]
fn factor_matches_the_svd_solution_singular_values_and_covariance() {
    for (seed, m) in [(1, 6), (2, 7), (3, 72), (4, 129), (5, 4608)] {
        let psi = random(m, [1e-3, 2e-4, 5e-4, 3e-3, 4e-3, 6e-3], seed);
        let delta = DVector::from_fn(m, |i, _| (i as f64 * 0.37).sin() * 1e-3);
        let factor = Factor::try_new(psi.clone()).unwrap();
        let svd = psi.clone().svd(true, true);
        let reference = svd.solve(&delta, 0.0).unwrap();
        let h = factor.solve(&delta);
        let rel = (h - &reference).amax() / reference.amax();
        assert!(rel < 1e-12, "m = {m}: solution differs by {rel:e}");
        let sv = sorted(&factor.singular_values());
        let reference_sv = sorted(&Vector6::from_iterator(svd.singular_values.iter().copied()));
        let rel = (sv - reference_sv).component_div(&reference_sv).amax();
        assert!(rel < 1e-12, "m = {m}: singular values differ by {rel:e}");
        let gram = psi.transpose() * &psi;
        let cov_reference: Matrix6<f64> = gram.fixed_view::<6, 6>(0, 0).try_inverse().unwrap();
        let rel = (factor.unit_covariance() - cov_reference).amax() / cov_reference.amax();
        assert!(rel < 1e-9, "m = {m}: covariance differs by {rel:e}");
        let r = factor.r();
        let rtr = r.transpose() * r;
        assert!((rtr - gram.fixed_view::<6, 6>(0, 0)).amax() < 1e-12 * gram.amax());
    }
}

#[test]
fn singular_values_of_an_ill_conditioned_matrix_are_accurate() {
    // A matrix built from known singular values over nine orders of magnitude (cond 1e9, just
    // inside the rank tolerance).
    let q = random(40, [1.0; 6], 10).qr().q();
    let sigma = Vector6::new(1.0, 1e-2, 1e-4, 1e-6, 1e-8, 1e-9);
    let v = random(6, [1.0; 6], 11).qr().q();
    let psi =
        &q * DMatrix::from_diagonal(&DVector::from_column_slice(sigma.as_slice())) * v.transpose();
    let factor = Factor::try_new(psi.clone()).unwrap();
    let sv = sorted(&factor.singular_values());
    let rel = (sv - sorted(&sigma)).component_div(&sorted(&sigma)).amax();
    // Backward-stable QR perturbs psi by ~eps |psi|, so the smallest singular value (1e-9) is
    // good to ~eps / 1e-9 relative.
    assert!(rel < 1e-5, "relative error {rel:e}");
    assert!(
        (factor.cond() - 1e9).abs() < 1e-5 * 1e9,
        "cond {}",
        factor.cond()
    );
}

#[test]
fn rank_checks_name_the_joints() {
    let mut psi = random(30, [1.0; 6], 12);
    psi.column_mut(3).fill(0.0);
    match Factor::try_new(psi.clone()).unwrap_err() {
        Error::Unidentifiable { joints, .. } => assert_eq!(joints, vec![4]),
        other => panic!("{other}"),
    }
    let mut psi = random(30, [1.0; 6], 13);
    let combination = psi.column(1) * 2.0 - psi.column(4);
    psi.set_column(5, &combination);
    match Factor::try_new(psi.clone()).unwrap_err() {
        Error::Unidentifiable { joints, .. } => assert_eq!(joints, vec![2, 5, 6]),
        other => panic!("{other}"),
    }
    let mut psi = random(30, [1.0; 6], 14);
    psi[(7, 2)] = f64::NAN;
    assert!(matches!(
        Factor::try_new(psi.clone()),
        Err(Error::NotFinite { .. })
    ));
    assert_eq!(
        Factor::try_new(random(5, [1.0; 6], 15)).unwrap_err(),
        Error::TooFewRows { rows: 5 }
    );
}

#[test]
fn reduction_in_blocks_of_any_size_equals_the_one_shot_factor() {
    let m = 1000;
    let psi = random(m, [1e-3, 2e-4, 5e-4, 3e-3, 4e-3, 6e-3], 11);
    let delta = DVector::from_fn(m, |i, _| (i as f64 * 0.53).cos() * 1e-3);
    let factor = Factor::try_new(psi.clone()).unwrap();
    let h = factor.solve(&delta);
    // Uneven blocks (1 row, fewer than six, many), then merged reductions of disjoint rows.
    let mut reduced = Reduced::default();
    let mut other = Reduced::default();
    let mut start = 0;
    for (k, size) in [1, 2, 5, 6, 7, 64, 300, 15].into_iter().cycle().enumerate() {
        let size = size.min(m - start);
        if size == 0 {
            break;
        }
        let (p, d) = (
            psi.rows(start, size).into_owned(),
            delta.rows(start, size).into_owned(),
        );
        match k % 3 {
            0 => reduced.push(&p, &d),
            _ => other.push(&p, &d),
        }
        start += size;
    }
    reduced.merge(&other);
    assert_eq!(reduced.rows(), m);
    // Another row order: same problem, same solution.
    let solution = reduced.try_solve().unwrap();
    assert!(
        (solution.h - h).amax() < 1e-12 * h.amax(),
        "{} vs {h}",
        solution.h
    );
    let covariance = factor.unit_covariance();
    assert!((solution.unit_covariance - covariance).amax() < 1e-12 * covariance.amax());
    assert!((solution.cond - factor.cond()).abs() < 1e-12 * factor.cond());
}

#[test]
fn reduction_refuses_what_the_factor_refuses() {
    let mut few = Reduced::default();
    few.push(&random(5, [1.0; 6], 15), &DVector::zeros(5));
    assert!(matches!(
        few.try_solve(),
        Err(Error::TooFewRows { rows: 5 })
    ));
    let mut psi = random(40, [1.0; 6], 16);
    psi.column_mut(3).fill(0.0);
    let mut zero = Reduced::default();
    zero.push(&psi, &DVector::zeros(40));
    match zero.try_solve().unwrap_err() {
        Error::Unidentifiable { joints, .. } => assert_eq!(joints, vec![4]),
        e => panic!("{e}"),
    }
    psi[(0, 0)] = f64::NAN;
    let mut nan = Reduced::default();
    nan.push(&psi, &DVector::zeros(40));
    assert!(matches!(nan.try_solve(), Err(Error::NotFinite { .. })));
}
