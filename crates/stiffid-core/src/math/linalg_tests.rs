//! The linear-algebra kernels' tests: QR, triangular factors, inverses and products against known matrices.

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
