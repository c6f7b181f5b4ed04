//! Singular values and right singular vectors of a square matrix by one-sided (Hestenes) Jacobi,
//! one kernel for the 6x6 triangular factors of the six-parameter model (fixed-size columns, the
//! microsecond budget of [`crate::math::lsq::Factor`] and `stiffid_design::Evaluator`) and the
//! `n x n` factors of models with virtual springs.
//!
//! Plane rotations of column pairs until every pair is orthogonal to working precision
//! (`|u_i . u_j| <= eps |u_i| |u_j|`); the column norms are then the singular values, in no
//! particular order, and the product of the rotations is `V` (`A V = U diag(s)`). Pairs are taken
//! in round-robin order (the circle method: rounds of disjoint pairs, whose rotations are
//! independent and overlap in the processor). Demmel and Veselic, "Jacobi's method is more accurate
//! than QR", SIAM J. Matrix Anal. Appl. 13 (1992): every singular value to high relative accuracy
//! for a graded triangular factor.

use nalgebra::{DMatrix, DVector, Matrix6, Vector6};

/// The 15 column pairs of a 6-column matrix in five rounds of three disjoint pairs:
/// [`round_robin`]`(6)`, spelt out so the six-column kernel allocates nothing.
pub(crate) const PAIRS_6: [(usize, usize); 15] = [
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

/// Every pair `i < j` of `n` columns once, in rounds of disjoint pairs (the circle method: column 0
/// fixed, the others turning one place a round; for odd `n` a missing column `n` sits out a pair a
/// round).
pub(crate) fn round_robin(n: usize) -> Vec<(usize, usize)> {
    let m = n + n % 2;
    let mut pairs = Vec::with_capacity(n * n.saturating_sub(1) / 2);
    for round in 0..m.saturating_sub(1) {
        let ring = |k: usize| 1 + (k + m - 1 - round) % (m - 1);
        let mut push = |a: usize, b: usize| {
            if a < n && b < n {
                pairs.push((a.min(b), a.max(b)));
            }
        };
        push(0, ring(0));
        for k in 1..m / 2 {
            push(ring(k), ring(m - 1 - k));
        }
    }
    pairs
}

/// The columns one-sided Jacobi rotates: a fixed-size 6x6 array or a dynamic square matrix.
trait Columns {
    /// `u_i . u_j`.
    fn dot(&self, i: usize, j: usize) -> f64;
    /// Columns `i < j` rotated: `(u_i, u_j) <- (c u_i - s u_j, s u_i + c u_j)`.
    fn rotate(&mut self, i: usize, j: usize, c: f64, s: f64);
}

/// Six columns of six, column-major.
impl Columns for [[f64; 6]; 6] {
    #[inline(always)]
    fn dot(&self, i: usize, j: usize) -> f64 {
        let (x, y) = (&self[i], &self[j]);
        (x[0] * y[0] + x[1] * y[1]) + (x[2] * y[2] + x[3] * y[3]) + (x[4] * y[4] + x[5] * y[5])
    }

    #[inline(always)]
    fn rotate(&mut self, i: usize, j: usize, c: f64, s: f64) {
        let (head, tail) = self.split_at_mut(j);
        let (ui, uj) = (&mut head[i], &mut tail[0]);
        for k in 0..6 {
            let (x, y) = (ui[k], uj[k]);
            ui[k] = c * x - s * y;
            uj[k] = s * x + c * y;
        }
    }
}

impl Columns for DMatrix<f64> {
    fn dot(&self, i: usize, j: usize) -> f64 {
        crate::math::linalg::dot(self.column(i).as_slice(), self.column(j).as_slice())
    }

    fn rotate(&mut self, i: usize, j: usize, c: f64, s: f64) {
        let m = self.nrows();
        let (head, tail) = self.as_mut_slice().split_at_mut(j * m);
        let (ui, uj) = (&mut head[i * m..(i + 1) * m], &mut tail[..m]);
        for (x, y) in ui.iter_mut().zip(uj.iter_mut()) {
            (*x, *y) = (c * *x - s * *y, s * *x + c * *y);
        }
    }
}

/// The kernel: sweeps over `pairs` of the columns of `u` (rotated in place; the same rotations
/// applied to `v` if given) until a sweep rotates by less than 1e-8; `s` (one entry per column)
/// receives the singular values. Columns whose squared norm is below `eps^2 |A|_F^2` are
/// numerically zero and left alone (a rank-deficient matrix would otherwise rotate rounding noise
/// for the full 60 sweeps).
fn sweep<C: Columns>(u: &mut C, mut v: Option<&mut C>, pairs: &[(usize, usize)], s: &mut [f64]) {
    let eps2 = f64::EPSILON * f64::EPSILON;
    let squared = |u: &C, s: &mut [f64]| (0..s.len()).for_each(|i| s[i] = u.dot(i, i));
    squared(u, s);
    let negligible = eps2 * s.iter().sum::<f64>();
    for sweep in 0..60 {
        if sweep > 0 {
            squared(u, s);
        }
        let mut largest_tangent: f64 = 0.0;
        for &(i, j) in pairs {
            let g = u.dot(i, j);
            if g * g <= eps2 * s[i] * s[j] || s[i] <= negligible || s[j] <= negligible {
                continue;
            }
            // The rotation that zeroes u_i . u_j: tan = t = 2g sign(d) / (|d| + h), h = sqrt(d^2 + 4g^2),
            // d = |u_j|^2 - |u_i|^2 (the smaller root of t^2 g + t d - g = 0). With p = |d| + h,
            // 1 + t^2 = 2h / p, so cos = p / sqrt(2hp) and sin = 2g sign(d) / sqrt(2hp): one
            // division fewer on the critical path than cos = 1 / sqrt(1 + t^2).
            let d = s[j] - s[i];
            let h = (d * d + 4.0 * g * g).sqrt();
            let p = d.abs() + h;
            let scale = 1.0 / (2.0 * h * p).sqrt();
            let (c, sn) = (p * scale, 2.0 * g * d.signum() * scale);
            u.rotate(i, j, c, sn);
            if let Some(v) = v.as_deref_mut() {
                v.rotate(i, j, c, sn);
            }
            // t g = 2 g^2 sign(d) / p moves the squared norms.
            let t = 2.0 * g * d.signum() / p;
            s[i] -= t * g;
            s[j] += t * g;
            largest_tangent = largest_tangent.max(t.abs());
        }
        // Cyclic Jacobi converges quadratically: after a sweep whose rotations were all below
        // 1e-8 the next one would rotate by ~1e-16, below rounding, so it is skipped.
        if largest_tangent < 1e-8 {
            break;
        }
    }
    (0..s.len()).for_each(|i| s[i] = u.dot(i, i).sqrt());
}

/// The six columns of `r`, column-major.
fn columns_6(r: &Matrix6<f64>) -> [[f64; 6]; 6] {
    std::array::from_fn(|j| std::array::from_fn(|i| r[(i, j)]))
}

/// The singular values of a 6x6 matrix, in no particular order (NaN for NaN input).
pub(crate) fn singular_values(r: &Matrix6<f64>) -> Vector6<f64> {
    let mut s = Vector6::zeros();
    sweep(&mut columns_6(r), None, &PAIRS_6, s.as_mut_slice());
    s
}

/// The singular values of a 6x6 matrix `r` (by `singular_values`) and its right singular vectors:
/// column k of the matrix is the unit vector `v_k` with `|r v_k| = s_k`.
pub fn singular_values_and_vectors(r: &Matrix6<f64>) -> (Vector6<f64>, Matrix6<f64>) {
    let mut v = columns_6(&Matrix6::identity());
    let mut s = Vector6::zeros();
    sweep(&mut columns_6(r), Some(&mut v), &PAIRS_6, s.as_mut_slice());
    (s, Matrix6::from_fn(|i, j| v[j][i]))
}

/// `s_max / s_min` of a 6x6 matrix (by `singular_values`): `+infinity` (or NaN for NaN input) when
/// singular.
pub fn cond(a: &Matrix6<f64>) -> f64 {
    let s = singular_values(a);
    s.max() / s.min()
}

/// The singular values (no particular order) and right singular vectors (columns, unit, `|a v_k| =
/// s_k`) of a square `n x n` matrix: [`singular_values_and_vectors`] for any `n`.
pub fn singular_values_and_vectors_n(a: &DMatrix<f64>) -> (DVector<f64>, DMatrix<f64>) {
    let n = a.ncols();
    let mut v = DMatrix::identity(n, n);
    let mut s = DVector::zeros(n);
    sweep(
        &mut a.clone(),
        Some(&mut v),
        &round_robin(n),
        s.as_mut_slice(),
    );
    (s, v)
}

/// `s_max / s_min` of a square matrix ([`singular_values_and_vectors_n`]).
pub fn cond_n(a: &DMatrix<f64>) -> f64 {
    let mut s = DVector::zeros(a.ncols());
    sweep(
        &mut a.clone(),
        None,
        &round_robin(a.ncols()),
        s.as_mut_slice(),
    );
    s.max() / s.min()
}
