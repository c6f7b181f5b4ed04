//! Householder reflections on column-major slices, their vectors kept in LAPACK's storage (each
//! reflection's vector below the diagonal where it zeroed) and applied, never formed: the
//! reflection of a column ([`reflector`]), a reflection applied to one column ([`reflect`]) or to
//! several, four at a time ([`reflect_columns`]), and the QR factorisation of any number of
//! columns ([`qr`], LAPACK's `dgeqr2` operations in blocks of columns: every crate's QR of a
//! matrix it factors by Householder reflections), and its six-column form, the identification's
//! ([`triangular_factor`]). Each column's result is that of the
//! reflections applied to it alone, one after the other, to the last bit, with the four-way
//! [`dot`] and [`axpy`] of [`super::linalg`].

use super::linalg::{axpy, dot, dot4};
use nalgebra::{DMatrix, Matrix6, Vector6};

/// The reflections a trailing column is taken through while it sits in cache: a block of them
/// is `BLOCK` columns of the matrix (2400 rows: 600 KiB, within a 1 MiB L2).
const BLOCK: usize = 32;

/// Makes `x` into a reflection `H = I - tau v v^T` with `H x = beta e_1`: returns `tau`, leaves
/// `beta` in `x[0]` and `v[1..]` in `x[1..]` (`v[0] = 1`); `tau = 0` (the identity, `x` unchanged)
/// where `x[1..]` is zero.
pub fn reflector(x: &mut [f64]) -> f64 {
    let alpha = x[0];
    let tail = dot(&x[1..], &x[1..]).sqrt();
    if tail == 0.0 {
        return 0.0;
    }
    let beta = -alpha.signum() * (alpha * alpha + tail * tail).sqrt();
    let inv = 1.0 / (alpha - beta);
    x[1..].iter_mut().for_each(|v| *v *= inv);
    x[0] = beta;
    (beta - alpha) / beta
}

/// `y = (I - tau v v^T) y`, `v = (1, tail)`.
pub fn reflect(tail: &[f64], tau: f64, y: &mut [f64]) {
    let w = tau * (y[0] + dot(tail, &y[1..]));
    y[0] -= w;
    axpy(-w, tail, &mut y[1..]);
}

/// Each of the column-major `columns` (`m` rows each), from its row `from`, taken through the
/// reflection of [`reflect`] (`tail` of `m - from - 1` entries): four columns at a time, their
/// dots with `tail` summed together (`dot4`), each column's result that of [`reflect`] alone.
pub fn reflect_columns(tail: &[f64], tau: f64, columns: &mut [f64], m: usize, from: usize) {
    let mut groups = columns.chunks_exact_mut(4 * m);
    for g in &mut groups {
        let (c0, rest) = g.split_at_mut(m);
        let (c1, rest) = rest.split_at_mut(m);
        let (c2, c3) = rest.split_at_mut(m);
        let mut cs = [
            &mut c0[from..],
            &mut c1[from..],
            &mut c2[from..],
            &mut c3[from..],
        ];
        let d = dot4(tail, [&cs[0][1..], &cs[1][1..], &cs[2][1..], &cs[3][1..]]);
        for (c, d) in cs.iter_mut().zip(d) {
            let w = tau * (c[0] + d);
            c[0] -= w;
            axpy(-w, tail, &mut c[1..]);
        }
    }
    for c in groups.into_remainder().chunks_exact_mut(m) {
        reflect(tail, tau, &mut c[from..]);
    }
}

/// Householder QR in place of the column-major matrix `a` of `m` rows, its first `reflections`
/// columns reduced (`reflections <= min(m, columns)`) and every column after them taken through
/// the reflections: `R` on and above the diagonal of those columns, `Q^T` times the others in
/// theirs. Returns the `tau`s.
pub fn qr(a: &mut [f64], m: usize, reflections: usize) -> Vec<f64> {
    let mut taus = vec![0.0; reflections];
    for k0 in (0..reflections).step_by(BLOCK) {
        let k1 = (k0 + BLOCK).min(reflections);
        for k in k0..k1 {
            let (left, right) = a.split_at_mut((k + 1) * m);
            let col = &mut left[k * m + k..];
            taus[k] = reflector(col);
            if taus[k] == 0.0 {
                continue;
            }
            reflect_columns(&col[1..], taus[k], &mut right[..(k1 - k - 1) * m], m, k);
        }
        let (panel, trailing) = a.split_at_mut(k1 * m);
        for group in trailing.chunks_mut(4 * m) {
            for k in (k0..k1).filter(|&k| taus[k] != 0.0) {
                let tail = &panel[k * m + k + 1..(k + 1) * m];
                reflect_columns(tail, taus[k], group, m, k);
            }
        }
    }
    taus
}

/// Householder QR in place of the column-major `m x 6` matrix `a` (LAPACK `dgeqrf`,
/// [`qr`]): on return `R` is on and above the diagonal and the
/// reflector vectors `v_k` (with `v_k[k] = 1` implied) below it. Returns the `tau_k`.
pub(crate) fn householder_qr(a: &mut [f64], m: usize) -> Vector6<f64> {
    Vector6::from_column_slice(&qr(a, m, 6))
}

/// `R_A` of the Householder QR `A = Q_A R_A` (6x6, upper triangular, `A^T A = R_A^T R_A`) of an
/// `m x 6` matrix; zero rows are appended to a matrix of fewer than 6 rows (they change neither).
pub fn triangular_factor(a: DMatrix<f64>) -> Matrix6<f64> {
    let m = a.nrows().max(6);
    let mut a = a.resize_vertically(m, 0.0);
    householder_qr(a.as_mut_slice(), m);
    upper_triangle(a.as_slice(), m)
}

/// The upper triangle `R` (6x6) of the in-place result of `householder_qr` on `a` with `m` rows.
pub(crate) fn upper_triangle(a: &[f64], m: usize) -> Matrix6<f64> {
    Matrix6::from_fn(|i, j| if i <= j { a[j * m + i] } else { 0.0 })
}
