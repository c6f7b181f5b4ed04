//! The Jacobi SVD kernels' tests: round-robin pairs, singular values and vectors against known matrices.

use super::householder::triangular_factor;
use super::jacobi::*;
use nalgebra::{DMatrix, Matrix6, Vector6};
use nalgebra::{Rotation3, Vector3};

#[test]
fn round_robin_pairs_every_column_once_in_disjoint_rounds() {
    assert_eq!(round_robin(6), PAIRS_6);
    for n in 1..=13 {
        let pairs = round_robin(n);
        let mut seen = pairs.clone();
        seen.sort_unstable();
        seen.dedup();
        let all: Vec<(usize, usize)> = (0..n)
            .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
            .collect();
        assert_eq!(seen, all, "n = {n}");
        assert_eq!(pairs.len(), all.len(), "n = {n}");
        // Each round of n / 2 pairs (the even case) touches every column once.
        if n % 2 == 0 {
            for round in pairs.chunks(n / 2) {
                let mut cols: Vec<usize> = round.iter().flat_map(|&(i, j)| [i, j]).collect();
                cols.sort_unstable();
                assert_eq!(cols, (0..n).collect::<Vec<_>>(), "n = {n}");
            }
        }
    }
}

#[test]
fn the_six_column_and_the_n_column_kernels_agree_to_the_bit() {
    // The same sweeps on the same pairs: fixed-size and dynamic columns give the same bits.
    let a =
        Matrix6::from_fn(|i, j| ((i * 6 + j) as f64 * 0.37).cos() + f64::from(u8::from(i == j)));
    let (s6, v6) = singular_values_and_vectors(&a);
    let (sn, vn) = singular_values_and_vectors_n(&DMatrix::from_column_slice(6, 6, a.as_slice()));
    assert_eq!(s6.as_slice(), sn.as_slice());
    assert_eq!(v6.as_slice(), vn.as_slice());
    assert_eq!(
        cond(&a),
        cond_n(&DMatrix::from_column_slice(6, 6, a.as_slice()))
    );
}

#[test]
fn n_column_singular_values_match_nalgebras_svd_for_wide_graded_factors() {
    for n in [7, 9, 12] {
        let a = DMatrix::from_fn(2 * n, n, |i, j| {
            let x = (i * n + j) as f64;
            let v = (x * 0.7548776662).fract() - 0.5 + 1e-2 * (x * 0.5698402910).fract();
            v * 10f64.powi((j % 4) as i32)
        });
        let r = a.clone().qr().r();
        let want = a.svd(false, false).singular_values;
        let (s, v) = singular_values_and_vectors_n(&r);
        let mut got: Vec<f64> = s.iter().copied().collect();
        got.sort_by(|x, y| y.total_cmp(x));
        for (g, w) in got.iter().zip(want.iter()) {
            assert!((g - w).abs() < 1e-13 * want[0], "n {n}: {g} vs {w}");
        }
        assert!((v.transpose() * &v - DMatrix::identity(n, n)).amax() < 1e-13);
        for k in 0..n {
            assert!(((&r * v.column(k)).norm() - s[k]).abs() < 1e-13 * want[0]);
        }
        let (c, c_want) = (cond_n(&r), want[0] / want[n - 1]);
        assert!(
            (c - c_want).abs() < 1e-13 * c_want * c_want,
            "n {n}: {c} vs {c_want}"
        );
    }
}

#[test]
fn singular_values_of_a_rotated_diagonal_matrix_are_its_diagonal() {
    let s = [7.0, 3.0, 1e-3, 2.0, 0.5, 11.0];
    let rotation = |axis: Vector3<f64>, angle: f64| {
        let r = Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle);
        let mut m = Matrix6::identity();
        m.fixed_view_mut::<3, 3>(0, 0).copy_from(r.matrix());
        m.fixed_view_mut::<3, 3>(3, 3).copy_from(r.matrix());
        m
    };
    let u = rotation(Vector3::new(1.0, 2.0, 3.0), 0.7);
    let v = rotation(Vector3::new(-2.0, 0.5, 1.0), 1.9)
        * Matrix6::from_fn(|i, j| {
            // A permutation mixing the two 3x3 blocks.
            f64::from(u8::from(j == (i + 2) % 6))
        });
    let a = u * Matrix6::from_diagonal(&Vector6::from_column_slice(&s)) * v.transpose();
    let mut got: Vec<f64> = singular_values(&a).iter().copied().collect();
    got.sort_by(f64::total_cmp);
    let mut want = s.to_vec();
    want.sort_by(f64::total_cmp);
    for (g, w) in got.iter().zip(&want) {
        assert!((g - w).abs() < 1e-13 * w.max(1.0), "{g} vs {w}");
    }
    assert!((cond(&a) - 11.0 / 1e-3).abs() < 1e-8 * 11e3);
}

#[test]
fn singular_values_of_a_diagonal_matrix_are_exact_and_of_a_singular_one_include_zero() {
    let d = Vector6::new(-4.0, 1.0, 2.5, 8.0, 0.25, 3.0);
    assert_eq!(singular_values(&Matrix6::from_diagonal(&d)), d.abs());
    let mut singular = Matrix6::from_diagonal(&d);
    singular.set_column(2, &(singular.column(0) * 2.0));
    let s = singular_values(&singular);
    assert!(s.min() <= 1e-15 * s.max());
    assert_eq!(cond(&singular), f64::INFINITY);
}

#[test]
fn singular_values_match_nalgebras_svd_on_triangular_factors_of_graded_matrices() {
    // 200 triangular factors of 12x6 matrices whose columns differ in scale by up to 1e4.
    // The reference is accurate to about eps s_max in every singular value (normwise), so
    // that is the comparison, and cond to 1e-13 cond^2 relative.
    for case in 0..200 {
        let a = DMatrix::from_fn(12, 6, |i, j| {
            let x = (case * 72 + i * 6 + j) as f64;
            (x * 0.7548776662).fract() - 0.5 + 1e-2 * (x * 0.5698402910).fract()
        }) * DMatrix::from_diagonal(&nalgebra::DVector::from_fn(6, |j, _| {
            10f64.powi(((case + j) % 5) as i32)
        }));
        let r = triangular_factor(a.clone());
        let want = a.svd(false, false).singular_values;
        let mut got: Vec<f64> = singular_values(&r).iter().copied().collect();
        got.sort_by(|x, y| y.total_cmp(x));
        for (g, w) in got.iter().zip(want.iter()) {
            assert!((g - w).abs() < 1e-13 * want[0], "case {case}: {g} vs {w}");
        }
        let c = cond(&r);
        let c_want = want[0] / want[5];
        assert!(
            (c - c_want).abs() < 1e-13 * c_want * c_want,
            "case {case}: {c} vs {c_want}"
        );
    }
}

#[test]
fn singular_vectors_map_to_their_singular_values() {
    let a =
        Matrix6::from_fn(|i, j| ((i * 6 + j) as f64 * 0.37).cos() + f64::from(u8::from(i == j)));
    let (s, v) = singular_values_and_vectors(&a);
    assert!((v.transpose() * v - Matrix6::identity()).amax() < 1e-14);
    for k in 0..6 {
        assert!(((a * v.column(k)).norm() - s[k]).abs() < 1e-13 * s.max());
    }
}
