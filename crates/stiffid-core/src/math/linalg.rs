//! Dense kernels for the `m x 6` least-squares problems of stiffid: Householder QR specialised to
//! six columns, the 6x6 inverse and fixed-order products (the singular values of the triangular
//! factor are [`crate::math::jacobi`]'s).
//!
//! The six-column case is small enough that general-purpose routines spend most of their time on
//! bookkeeping; these kernels keep [`crate::math::lsq::Factor`] and the design evaluator
//! (`stiffid_design::Evaluator`) within their microsecond budgets. Everything else uses nalgebra.

use nalgebra::allocator::Allocator;
use nalgebra::{
    DMatrix, DefaultAllocator, Dim, DimDiff, DimMin, DimMinimum, DimSub, Matrix6, OMatrix, Vector6,
    SVD, U1,
};

/// The iteration cap of every nalgebra SVD stiffid runs (`try_svd`'s `max_niter`): nalgebra's
/// default, 0, never stops on a matrix holding a NaN or an overflow, while a finite matrix of the
/// sizes stiffid factors converges in a few iterations per singular value.
pub(crate) const SVD_MAX_ITERATIONS: usize = 10_000;

/// nalgebra's SVD as stiffid runs it: machine epsilon and the cap `SVD_MAX_ITERATIONS` (10 000 iterations).
pub trait CappedSvd<R: DimMin<C>, C: Dim>
where
    DefaultAllocator: Allocator<DimMinimum<R, C>, C>
        + Allocator<R, DimMinimum<R, C>>
        + Allocator<DimMinimum<R, C>>,
{
    /// The SVD of `self`, with `U` if `u` and `V^T` if `v_t`; `None` if it does not converge
    /// within the cap (a matrix holding a NaN or an overflow).
    fn capped_svd(self, u: bool, v_t: bool) -> Option<SVD<f64, R, C>>;
}

impl<R: DimMin<C>, C: Dim> CappedSvd<R, C> for OMatrix<f64, R, C>
where
    DimMinimum<R, C>: DimSub<U1>,
    DefaultAllocator: Allocator<R, C>
        + Allocator<C>
        + Allocator<R>
        + Allocator<DimDiff<DimMinimum<R, C>, U1>>
        + Allocator<DimMinimum<R, C>, C>
        + Allocator<R, DimMinimum<R, C>>
        + Allocator<DimMinimum<R, C>>,
{
    fn capped_svd(self, u: bool, v_t: bool) -> Option<SVD<f64, R, C>> {
        self.try_svd(u, v_t, f64::EPSILON, SVD_MAX_ITERATIONS)
    }
}

/// Householder QR in place of the column-major `m x 6` matrix `a` (LAPACK `dgeqrf`): on return `R`
/// is on and above the diagonal and the reflector vectors `v_k` (with `v_k[k] = 1` implied) below
/// it. Returns the `tau_k`.
pub(crate) fn householder_qr(a: &mut [f64], m: usize) -> Vector6<f64> {
    let mut taus = Vector6::zeros();
    householder_qr_columns(a, m, taus.as_mut_slice());
    taus
}

/// `householder_qr` of the column-major `m x n` matrix `a`, `n = taus.len() <= m` columns (the
/// same operations in the same order for six): the `tau_k` are written to `taus`.
#[inline(always)]
pub fn householder_qr_columns(a: &mut [f64], m: usize, taus: &mut [f64]) {
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
pub fn times_6x6(a: &[f64], m: usize, y: &Matrix6<f64>) -> Vec<f64> {
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

/// The Euclidean norms of the six columns of the column-major `a` with `m` rows (NaN or infinity
/// if an entry is not finite).
pub(crate) fn column_norms(a: &[f64], m: usize) -> Vector6<f64> {
    Vector6::from_fn(|j, _| {
        let c = &a[j * m..(j + 1) * m];
        dot(c, c).sqrt()
    })
}

/// `a . b` over the shorter length, with four partial sums (independent chains run in parallel).
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
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

/// `y += alpha x`, element by element.
pub fn axpy(alpha: f64, x: &[f64], y: &mut [f64]) {
    y.iter_mut().zip(x).for_each(|(y, x)| *y += alpha * x);
}
