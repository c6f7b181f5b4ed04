//! The linear-algebra kernels' tests: the six-column QR and triangular factors
//! ([`super::householder`]), inverses and products against known matrices.

use super::householder::{householder_qr, upper_triangle};
use super::linalg::*;
use nalgebra::{DMatrix, Matrix6, Vector6};

/// A fixed, well-conditioned 9x6 matrix (column-major), not triangular, not symmetric.
fn sample() -> DMatrix<f64> {
    DMatrix::from_fn(9, 6, |i, j| {
        let (i, j) = (i as f64, j as f64);
        (1.0 + i * 0.7 + j * 1.3).sin() + if i == j { 2.0 } else { 0.0 }
    })
}

/// `Q = H_1 .. H_6` (m x m) from the reflectors below the diagonal of `a` and `taus`.
fn q_of(a: &DMatrix<f64>, taus: &Vector6<f64>) -> DMatrix<f64> {
    let m = a.nrows();
    let mut q = DMatrix::identity(m, m);
    for k in 0..6 {
        let mut v = DMatrix::zeros(m, 1);
        v[k] = 1.0;
        for i in k + 1..m {
            v[i] = a[(i, k)];
        }
        let h = DMatrix::identity(m, m) - &v * v.transpose() * taus[k];
        q *= h;
    }
    q
}

#[test]
fn householder_qr_gives_orthogonal_q_triangular_r_and_q_r_equal_to_a() {
    let a = sample();
    let m = a.nrows();
    let mut f = a.clone();
    let taus = householder_qr(f.as_mut_slice(), m);
    let q = q_of(&f, &taus);
    assert!((q.transpose() * &q - DMatrix::identity(m, m)).amax() < 1e-14);
    let r = upper_triangle(f.as_slice(), m);
    let mut r_full = DMatrix::zeros(m, 6);
    r_full.view_mut((0, 0), (6, 6)).copy_from(&r);
    assert!((&q * r_full - &a).amax() < 1e-13 * a.amax());
    // R is nalgebra's up to the signs of its rows.
    let reference = a.clone().qr().r();
    for i in 0..6 {
        let sign = (r[(i, i)] * reference[(i, i)]).signum();
        for j in 0..6 {
            assert!((r[(i, j)] - sign * reference[(i, j)]).abs() < 1e-13);
        }
    }
}

#[test]
fn householder_qr_skips_a_column_already_triangular() {
    // Column 0 is e_0: no reflection needed (tau = 0), and R[0, 0] keeps its value.
    let mut a = sample();
    a.column_mut(0).fill(0.0);
    a[(0, 0)] = 3.0;
    let taus = householder_qr(a.as_mut_slice(), 9);
    assert_eq!(taus[0], 0.0);
    assert_eq!(a[(0, 0)], 3.0);
}

#[test]
fn inverse_is_nalgebras_with_every_row_swap() {
    // Rows reversed with small leading entries: partial pivoting swaps at every step.
    let a = Matrix6::from_fn(|i, j| {
        ((i * 6 + j) as f64 * 0.61).sin() + if i + j == 5 { 3.0 } else { 0.0 }
    });
    let want = a.try_inverse().unwrap();
    let got = inverse(&a).unwrap();
    assert!((got - want).amax() < 1e-14 * want.amax(), "{got} vs {want}");
    assert!((a * got - Matrix6::identity()).amax() < 1e-14);
}

/// A vector of `n` entries of mixed sizes and signs (no two sums reorder to the same bits).
fn mixed(n: usize, seed: f64) -> Vec<f64> {
    (0..n)
        .map(|i| (seed + 0.37 * i as f64).sin() * 10f64.powi((i % 7) as i32 - 3))
        .collect()
}

/// [`dot`] summed as documented: four partial sums over whole chunks of four, then the rest.
fn dot_reference(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let whole = n - n % 4;
    let mut s = [0.0; 4];
    for i in 0..whole {
        s[i % 4] += a[i] * b[i];
    }
    let rest: f64 = (whole..n).map(|i| a[i] * b[i]).sum();
    (s[0] + s[1]) + (s[2] + s[3]) + rest
}

#[test]
fn dot_and_dot4_sum_in_the_documented_order_to_the_last_bit_at_every_length() {
    for n in (0..80).chain([255, 256, 257, 1001]) {
        let a = mixed(n, 0.1);
        let b: Vec<Vec<f64>> = (0..4).map(|j| mixed(n + j, 1.0 + j as f64)).collect();
        let four = dot4(&a, [&b[0], &b[1], &b[2], &b[3]]);
        for j in 0..4 {
            let reference = dot_reference(&a, &b[j][..n]);
            assert_eq!(
                dot(&a, &b[j]).to_bits(),
                reference.to_bits(),
                "dot, n = {n}"
            );
            assert_eq!(four[j].to_bits(), reference.to_bits(), "dot4 {j}, n = {n}");
        }
    }
}

#[test]
fn axpy4_is_four_axpy_in_turn_to_the_last_bit_at_every_length() {
    for n in (0..80).chain([255, 256, 257, 1001]) {
        let x: Vec<Vec<f64>> = (0..4).map(|j| mixed(n, 2.0 + j as f64)).collect();
        let alpha = [0.3, -1.7e3, 2.5e-4, -0.9];
        let mut once = mixed(n, 7.0);
        let mut turns = once.clone();
        axpy4(alpha, [&x[0], &x[1], &x[2], &x[3]], &mut once);
        for j in 0..4 {
            axpy(alpha[j], &x[j], &mut turns);
        }
        let mut plain = mixed(n, 7.0);
        for j in 0..4 {
            for i in 0..n {
                plain[i] += alpha[j] * x[j][i];
            }
        }
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<u64>>();
        assert_eq!(bits(&once), bits(&turns), "n = {n}");
        assert_eq!(bits(&turns), bits(&plain), "n = {n}");
    }
}
