//! Dense kernels for the `m x 6` least-squares problems of stiffid: the 6x6 inverse, fixed-order
//! products, column norms, and the vector kernels every reduction runs on (`dot`, `dot4`, `axpy`,
//! `axpy4`, with AVX where the processor has it); the QR is [`crate::math::householder`]'s and the
//! singular values of its triangular factor are [`crate::math::jacobi`]'s.
//!
//! The six-column case is small enough that general-purpose routines spend most of their time on
//! bookkeeping; these kernels keep [`crate::math::lsq::Factor`] and the design evaluator
//! (`stiffid_design::Evaluator`) within their microsecond budgets. Everything else uses nalgebra.

use nalgebra::allocator::Allocator;
use nalgebra::{
    DefaultAllocator, Dim, DimDiff, DimMin, DimMinimum, DimSub, Matrix6, OMatrix, Vector6, SVD, U1,
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

/// The Euclidean norms of the six columns of the column-major `a` with `m` rows (NaN or infinity
/// if an entry is not finite).
pub(crate) fn column_norms(a: &[f64], m: usize) -> Vector6<f64> {
    Vector6::from_fn(|j, _| {
        let c = &a[j * m..(j + 1) * m];
        dot(c, c).sqrt()
    })
}

/// The shortest vectors [`dot`] and [`axpy`] take through their AVX code on a processor that has
/// it: below it the call costs more than the wider instructions save.
const WIDE: usize = 32;

/// `a . b` over the shorter length, with four partial sums (independent chains run in parallel).
///
/// On an x86-64 processor with AVX, vectors of 32 entries or more are summed with packed AVX
/// instructions (the compiler packs the four sums two to an instruction): the same four partial
/// sums in the same order, multiplications and additions
/// separately rounded (no fused multiply-add), so the result is the same to the last bit on
/// every processor.
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    #[cfg(target_arch = "x86_64")]
    if a.len().min(b.len()) >= WIDE && std::arch::is_x86_feature_detected!("avx") {
        // SAFETY: the processor has AVX (checked above).
        return unsafe { dot_avx(a, b) };
    }
    dot_portable(a, b)
}

/// [`dot`] compiled for AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
fn dot_avx(a: &[f64], b: &[f64]) -> f64 {
    dot_portable(a, b)
}

/// [`dot`]'s arithmetic, inlined into each of its compilations.
#[inline(always)]
fn dot_portable(a: &[f64], b: &[f64]) -> f64 {
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

/// The dots of `a` with each of four vectors `b` (over the shortest length of all five), each
/// summed as [`dot`] sums it, so each equals [`dot`]`(a, b[j])` to the last bit: computed
/// together, their four chains of partial sums run side by side (a [`dot`] alone waits on its
/// one chain's additions).
pub(crate) fn dot4(a: &[f64], b: [&[f64]; 4]) -> [f64; 4] {
    #[cfg(target_arch = "x86_64")]
    if a.len() >= WIDE && std::arch::is_x86_feature_detected!("avx") {
        // SAFETY: the processor has AVX (checked above).
        return unsafe { dot4_avx(a, b) };
    }
    dot4_portable(a, b)
}

/// [`dot4`] compiled for AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
fn dot4_avx(a: &[f64], b: [&[f64]; 4]) -> [f64; 4] {
    dot4_portable(a, b)
}

/// [`dot4`]'s arithmetic, inlined into each of its compilations: the five vectors walked in
/// chunks of four zipped together, into four separate sums of four, the form the compiler turns
/// into one 256-bit multiplication and addition per vector and chunk (with a 4 x 4 array of sums
/// and computed indices `b[j][4 c + i]` it kept the loop scalar in some builds, at twice the
/// CPU of the maps' choice's reductions; the ladder benchmark shows it).
#[inline(always)]
fn dot4_portable(a: &[f64], b: [&[f64]; 4]) -> [f64; 4] {
    let n = b.iter().map(|v| v.len()).fold(a.len(), usize::min);
    let whole = n - n % 4;
    let [c0, c1, c2, c3] = b.map(|v| v[..whole].chunks_exact(4));
    let columns = (c0.zip(c1)).zip(c2.zip(c3));
    let (mut s0, mut s1, mut s2, mut s3) = ([0.0; 4], [0.0; 4], [0.0; 4], [0.0; 4]);
    for (x, ((y0, y1), (y2, y3))) in a[..whole].chunks_exact(4).zip(columns) {
        for i in 0..4 {
            s0[i] += x[i] * y0[i];
            s1[i] += x[i] * y1[i];
            s2[i] += x[i] * y2[i];
            s3[i] += x[i] * y3[i];
        }
    }
    let s = [s0, s1, s2, s3];
    std::array::from_fn(|j| {
        let rest: f64 = (a[whole..n].iter().zip(&b[j][whole..n]))
            .map(|(x, y)| x * y)
            .sum();
        (s[j][0] + s[j][1]) + (s[j][2] + s[j][3]) + rest
    })
}

/// `y += alpha x`, element by element (with AVX-512 or AVX where the processor has it: the same
/// result, each element one multiplication and one addition).
pub fn axpy(alpha: f64, x: &[f64], y: &mut [f64]) {
    #[cfg(target_arch = "x86_64")]
    if y.len().min(x.len()) >= WIDE {
        if std::arch::is_x86_feature_detected!("avx512f") {
            // SAFETY: the processor has AVX-512 (checked above).
            return unsafe { axpy_avx512(alpha, x, y) };
        }
        if std::arch::is_x86_feature_detected!("avx") {
            // SAFETY: the processor has AVX (checked above).
            return unsafe { axpy_avx(alpha, x, y) };
        }
    }
    axpy_portable(alpha, x, y)
}

/// [`axpy`] compiled for AVX-512.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn axpy_avx512(alpha: f64, x: &[f64], y: &mut [f64]) {
    axpy_portable(alpha, x, y)
}

/// [`axpy`] compiled for AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
fn axpy_avx(alpha: f64, x: &[f64], y: &mut [f64]) {
    axpy_portable(alpha, x, y)
}

/// [`axpy`]'s arithmetic, inlined into each of its compilations.
#[inline(always)]
fn axpy_portable(alpha: f64, x: &[f64], y: &mut [f64]) {
    y.iter_mut().zip(x).for_each(|(y, x)| *y += alpha * x);
}

/// `y += alpha[0] x[0]`, then `+= alpha[1] x[1]`, ... (over the shortest length): four [`axpy`]
/// in one pass over `y`, each element summed in the same order, so the same result to the last
/// bit.
pub fn axpy4(alpha: [f64; 4], x: [&[f64]; 4], y: &mut [f64]) {
    #[cfg(target_arch = "x86_64")]
    if y.len() >= WIDE {
        if std::arch::is_x86_feature_detected!("avx512f") {
            // SAFETY: the processor has AVX-512 (checked above).
            return unsafe { axpy4_avx512(alpha, x, y) };
        }
        if std::arch::is_x86_feature_detected!("avx") {
            // SAFETY: the processor has AVX (checked above).
            return unsafe { axpy4_avx(alpha, x, y) };
        }
    }
    axpy4_portable(alpha, x, y)
}

/// [`axpy4`] compiled for AVX-512.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn axpy4_avx512(alpha: [f64; 4], x: [&[f64]; 4], y: &mut [f64]) {
    axpy4_portable(alpha, x, y)
}

/// [`axpy4`] compiled for AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
fn axpy4_avx(alpha: [f64; 4], x: [&[f64]; 4], y: &mut [f64]) {
    axpy4_portable(alpha, x, y)
}

/// [`axpy4`]'s arithmetic, inlined into each of its compilations.
#[inline(always)]
fn axpy4_portable(alpha: [f64; 4], x: [&[f64]; 4], y: &mut [f64]) {
    let n = x.iter().map(|v| v.len()).fold(y.len(), usize::min);
    let (x0, x1, x2, x3) = (&x[0][..n], &x[1][..n], &x[2][..n], &x[3][..n]);
    for (i, y) in y[..n].iter_mut().enumerate() {
        *y = *y + alpha[0] * x0[i] + alpha[1] * x1[i] + alpha[2] * x2[i] + alpha[3] * x3[i];
    }
}
