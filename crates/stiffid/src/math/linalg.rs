//! Dense kernels for the `m x 6` least-squares problems of stiffid: Householder QR specialised to
//! six columns and one-sided Jacobi singular values of a 6x6 triangular factor.
//!
//! The six-column case is small enough that general-purpose routines spend most of their time on
//! bookkeeping; these kernels keep [`crate::math::lsq::Factor`] and the design evaluator
//! ([`crate::design::Evaluator`]) within their microsecond budgets. Everything else uses nalgebra.

use nalgebra::{DMatrix, Matrix6, Vector6};

/// Householder QR in place of the column-major `m x 6` matrix `a` (LAPACK `dgeqrf`): on return `R`
/// is on and above the diagonal and the reflector vectors `v_k` (with `v_k[k] = 1` implied) below
/// it. Returns the `tau_k`.
pub(crate) fn householder_qr(a: &mut [f64], m: usize) -> Vector6<f64> {
    let mut taus = Vector6::zeros();
    householder_qr_columns(a, m, taus.as_mut_slice());
    taus
}

/// [`householder_qr`] of the column-major `m x n` matrix `a`, `n = taus.len() <= m` columns (the
/// same operations in the same order for six): the `tau_k` are written to `taus`.
#[inline(always)]
pub(crate) fn householder_qr_columns(a: &mut [f64], m: usize, taus: &mut [f64]) {
    for k in 0..taus.len() {
        let (left, right) = a.split_at_mut((k + 1) * m);
        let col = &mut left[k * m + k..];
        let alpha = col[0];
        let tail = dot(&col[1..], &col[1..]).sqrt();
        if tail == 0.0 {
            continue;
        }
        let beta = -alpha.signum() * (alpha * alpha + tail * tail).sqrt();
        let tau = (beta - alpha) / beta;
        let inv = 1.0 / (alpha - beta);
        col[1..].iter_mut().for_each(|x| *x *= inv);
        col[0] = beta;
        taus[k] = tau;
        let v = &col[1..];
        for c in right.chunks_exact_mut(m) {
            let c = &mut c[k..];
            let w = tau * (c[0] + dot(v, &c[1..]));
            c[0] -= w;
            axpy(-w, v, &mut c[1..]);
        }
    }
}

/// The 15 column pairs of a 6-column matrix in five rounds of three disjoint pairs (round-robin
/// order): the three rotations of a round are independent, which lets the processor overlap them.
const JACOBI_PAIRS: [(usize, usize); 15] = [
    (0, 1),
    (2, 5),
    (3, 4),
    (0, 5),
    (1, 4),
    (2, 3),
    (0, 4),
    (3, 5),
    (1, 2),
    (0, 3),
    (2, 4),
    (1, 5),
    (0, 2),
    (1, 3),
    (4, 5),
];

/// The singular values of a 6x6 matrix by one-sided (Hestenes) Jacobi: plane rotations of column
/// pairs until every pair is orthogonal to working precision (`|u_i . u_j| <= eps |u_i| |u_j|`);
/// the column norms are then the singular values, in no particular order. Columns whose squared
/// norm is below `eps^2 |r|_F^2` are numerically zero and left alone (a rank-deficient `R` would
/// otherwise rotate rounding noise for the full 60 sweeps).
pub(crate) fn singular_values(r: &Matrix6<f64>) -> Vector6<f64> {
    jacobi(r, None)
}

/// The singular values of a 6x6 matrix `r` ([`singular_values`]) and its right singular vectors:
/// column k of the matrix is the unit vector `v_k` with `|r v_k| = s_k` (the product of the Jacobi
/// rotations, `r V = U diag(s)`).
pub(crate) fn singular_values_and_vectors(r: &Matrix6<f64>) -> (Vector6<f64>, Matrix6<f64>) {
    let mut v: [[f64; 6]; 6] =
        std::array::from_fn(|j| std::array::from_fn(|i| f64::from(u8::from(i == j))));
    let s = jacobi(r, Some(&mut v));
    (s, Matrix6::from_fn(|i, j| v[j][i]))
}

/// One-sided Jacobi on the columns of `r`; the rotations are also applied to the columns of `v`
/// (column-major) if given.
fn jacobi(r: &Matrix6<f64>, mut v: Option<&mut [[f64; 6]; 6]>) -> Vector6<f64> {
    let mut u: [[f64; 6]; 6] = std::array::from_fn(|j| std::array::from_fn(|i| r[(i, j)]));
    let dot6 = |x: &[f64; 6], y: &[f64; 6]| {
        (x[0] * y[0] + x[1] * y[1]) + (x[2] * y[2] + x[3] * y[3]) + (x[4] * y[4] + x[5] * y[5])
    };
    let negligible = f64::EPSILON * f64::EPSILON * r.norm_squared();
    for _sweep in 0..60 {
        let mut norms: [f64; 6] = std::array::from_fn(|i| dot6(&u[i], &u[i]));
        let mut largest_tangent: f64 = 0.0;
        for &(i, j) in &JACOBI_PAIRS {
            let g = dot6(&u[i], &u[j]);
            if g * g <= f64::EPSILON * f64::EPSILON * norms[i] * norms[j]
                || norms[i] <= negligible
                || norms[j] <= negligible
            {
                continue;
            }
            // The rotation that zeroes u_i . u_j: tan = t = 2g sign(d) / (|d| + h), h = sqrt(d^2 + 4g^2),
            // d = |u_j|^2 - |u_i|^2 (the smaller root of t^2 g + t d - g = 0). With p = |d| + h,
            // 1 + t^2 = 2h / p, so cos = p / sqrt(2hp) and sin = 2g sign(d) / sqrt(2hp): one
            // division fewer on the critical path than cos = 1 / sqrt(1 + t^2).
            let d = norms[j] - norms[i];
            let h = (d * d + 4.0 * g * g).sqrt();
            let p = d.abs() + h;
            let scale = 1.0 / (2.0 * h * p).sqrt();
            let (c, s) = (p * scale, 2.0 * g * d.signum() * scale);
            rotate(&mut u, i, j, c, s);
            if let Some(v) = v.as_deref_mut() {
                rotate(v, i, j, c, s);
            }
            // t g = 2 g^2 sign(d) / p moves the squared norms.
            let t = 2.0 * g * d.signum() / p;
            norms[i] -= t * g;
            norms[j] += t * g;
            largest_tangent = largest_tangent.max(t.abs());
        }
        // Cyclic Jacobi converges quadratically: after a sweep whose rotations were all below
        // 1e-8 the next one would rotate by ~1e-16, below rounding, so it is skipped.
        if largest_tangent < 1e-8 {
            break;
        }
    }
    Vector6::from_fn(|i, _| dot6(&u[i], &u[i]).sqrt())
}

/// Columns `i < j` of `u` (column-major) rotated: `(u_i, u_j) <- (c u_i - s u_j, s u_i + c u_j)`.
#[inline(always)]
fn rotate(u: &mut [[f64; 6]; 6], i: usize, j: usize, c: f64, s: f64) {
    let (head, tail) = u.split_at_mut(j);
    let (ui, uj) = (&mut head[i], &mut tail[0]);
    for k in 0..6 {
        let (x, y) = (ui[k], uj[k]);
        ui[k] = c * x - s * y;
        uj[k] = s * x + c * y;
    }
}

/// `s_max / s_min` of a 6x6 matrix ([`singular_values`]): `+infinity` (or NaN for NaN input) when
/// singular.
pub(crate) fn cond(a: &Matrix6<f64>) -> f64 {
    let s = singular_values(a);
    s.max() / s.min()
}

/// The inverse of a 6x6 matrix by Gauss-Jordan elimination with partial pivoting, on a fixed-size
/// array (no allocation, no dimension bookkeeping); `None` when a pivot is exactly zero. Accurate
/// to `cond(a)` times rounding, as an LU-based inverse.
pub(crate) fn inverse(a: &Matrix6<f64>) -> Option<Matrix6<f64>> {
    // Rows of [a | I].
    let mut m: [[f64; 12]; 6] = std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            if j < 6 {
                a[(i, j)]
            } else {
                f64::from(u8::from(j - 6 == i))
            }
        })
    });
    for k in 0..6 {
        let mut p = k;
        for r in k + 1..6 {
            if m[r][k].abs() > m[p][k].abs() {
                p = r;
            }
        }
        if m[p][k] == 0.0 {
            return None;
        }
        m.swap(k, p);
        let inv = 1.0 / m[k][k];
        let pivot_row: [f64; 12] = std::array::from_fn(|c| m[k][c] * inv);
        m[k] = pivot_row;
        // Whole rows, a fixed length the compiler unrolls: columns left of k are never read
        // again, so updating them changes nothing else.
        for (r, row) in m.iter_mut().enumerate() {
            let f = row[k];
            if r != k && f != 0.0 {
                for (x, p) in row.iter_mut().zip(&pivot_row) {
                    *x -= f * p;
                }
            }
        }
    }
    Some(Matrix6::from_fn(|i, j| m[i][j + 6]))
}

/// `a y` of the column-major `m x 6` matrix `a` (m rows) and a 6x6 `y`, in a fixed order
/// (column j of the result is `sum_k y[k, j] a_k`, k ascending): the same bits on every processor,
/// unlike a general product that picks its kernel by the processor's features at run time.
pub(crate) fn times_6x6(a: &[f64], m: usize, y: &Matrix6<f64>) -> Vec<f64> {
    let mut out = vec![0.0; 6 * m];
    for (j, col) in out.chunks_exact_mut(m).enumerate() {
        for (k, a_k) in a.chunks_exact(m).enumerate() {
            axpy(y[(k, j)], a_k, col);
        }
    }
    out
}

/// `R_A` of the Householder QR `A = Q_A R_A` (6x6, upper triangular, `A^T A = R_A^T R_A`) of an
/// `m x 6` matrix; zero rows are appended to a matrix of fewer than 6 rows (they change neither).
pub(crate) fn triangular_factor(a: DMatrix<f64>) -> Matrix6<f64> {
    let m = a.nrows().max(6);
    let mut a = a.resize_vertically(m, 0.0);
    householder_qr(a.as_mut_slice(), m);
    upper_triangle(a.as_slice(), m)
}

/// The upper triangle `R` (6x6) of the in-place result of [`householder_qr`] on `a` with `m` rows.
pub(crate) fn upper_triangle(a: &[f64], m: usize) -> Matrix6<f64> {
    Matrix6::from_fn(|i, j| if i <= j { a[j * m + i] } else { 0.0 })
}

/// The Euclidean norms of the six columns of the column-major `a` with `m` rows (NaN or infinity
/// if an entry is not finite).
pub(crate) fn column_norms(a: &[f64], m: usize) -> Vector6<f64> {
    Vector6::from_fn(|j, _| {
        let c = &a[j * m..(j + 1) * m];
        dot(c, c).sqrt()
    })
}

/// `a . b` over the shorter length, with four partial sums (independent chains run in parallel).
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (a[..n].chunks_exact(4), b[..n].chunks_exact(4));
    let rest: f64 = a
        .remainder()
        .iter()
        .zip(b.remainder())
        .map(|(x, y)| x * y)
        .sum();
    let mut s = [0.0; 4];
    for (x, y) in a.zip(b) {
        for i in 0..4 {
            s[i] += x[i] * y[i];
        }
    }
    (s[0] + s[1]) + (s[2] + s[3]) + rest
}

pub(crate) fn axpy(alpha: f64, x: &[f64], y: &mut [f64]) {
    y.iter_mut().zip(x).for_each(|(y, x)| *y += alpha * x);
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, Rotation3, Vector3};

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
        let a = Matrix6::from_fn(|i, j| {
            ((i * 6 + j) as f64 * 0.37).cos() + f64::from(u8::from(i == j))
        });
        let (s, v) = singular_values_and_vectors(&a);
        assert!((v.transpose() * v - Matrix6::identity()).amax() < 1e-14);
        for k in 0..6 {
            assert!(((a * v.column(k)).norm() - s[k]).abs() < 1e-13 * s.max());
        }
    }
}
