//! Householder reductions of the maps' splits and of the fit's triangular factor, their
//! orthogonal factors kept as reflections (LAPACK's storage: each reflection's vector below the
//! diagonal, or right of the superdiagonal, where it zeroed) and applied to vectors, never
//! formed:
//! - [`qr`], the QR of a split's projected map columns with its right-hand side as one more
//!   column, of the fit's Jacobian with its residuals and of the identifiability analysis's
//!   scaled Jacobian (`dgeqr2`'s operations, each trailing column taken through a block of reflections at a
//!   time while it sits in cache: the same operations in the same order as column after column);
//! - [`Bidiagonal`], the Golub-Kahan bidiagonalisation `S = W B Z^T` (`dgebd2`) of a choice's
//!   columns of a split's `R` and of the fit's `R` at each iteration, for Eldén's ridge steps
//!   ([`bidiagonal_ridge`]: every ridge or damping `lambda` in `O(k)` once `B` is known).
//!
//! Column-major slices throughout, with the core's four-way `dot` and `axpy`; a reflection is
//! applied to four columns at a time ([`reflect_columns`]), each column's result that of the
//! reflection applied to it alone, to the last bit.

use stiffid_core::math::linalg::{axpy, axpy4, dot, dot4};

/// The reflections a trailing column is taken through while it sits in cache: a block of them
/// is `BLOCK` columns of the matrix (2400 rows: 600 KiB, within a 1 MiB L2).
const BLOCK: usize = 32;

/// Makes `x` into a reflection `H = I - tau v v^T` with `H x = beta e_1`: returns `tau`, leaves
/// `beta` in `x[0]` and `v[1..]` in `x[1..]` (`v[0] = 1`); `tau = 0` (the identity, `x` unchanged)
/// where `x[1..]` is zero.
fn reflector(x: &mut [f64]) -> f64 {
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
pub(super) fn reflect(tail: &[f64], tau: f64, y: &mut [f64]) {
    let w = tau * (y[0] + dot(tail, &y[1..]));
    y[0] -= w;
    axpy(-w, tail, &mut y[1..]);
}

/// Each of the column-major `columns` (`m` rows each), from its row `from`, taken through the
/// reflection of [`reflect`] (`tail` of `m - from - 1` entries): four columns at a time, their
/// dots with `tail` summed together ([`dot4`]), each column's result that of [`reflect`] alone.
pub(super) fn reflect_columns(tail: &[f64], tau: f64, columns: &mut [f64], m: usize, from: usize) {
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
pub(super) fn qr(a: &mut [f64], m: usize, reflections: usize) -> Vec<f64> {
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

/// The bidiagonalisation `S = W B Z^T` of an `m x n` matrix, `m >= n >= 1`: `B` upper bidiagonal,
/// `W = H_0 .. H_{n-1}` and `Z = G_0 .. G_{n-2}` kept as their reflections.
pub(super) struct Bidiagonal {
    /// The reflections, in `S`'s place: `H_i`'s below the diagonal of column `i` (`G_i`'s right
    /// of the superdiagonal of row `i`, also in `right_tails`).
    a: Vec<f64>,
    m: usize,
    n: usize,
    left: Vec<f64>,
    right: Vec<f64>,
    /// `G_i`'s vector after its first entry (1).
    right_tails: Vec<Vec<f64>>,
    /// `B`'s diagonal (`n`).
    pub(super) diagonal: Vec<f64>,
    /// `B`'s superdiagonal (`n - 1`).
    pub(super) upper: Vec<f64>,
}

impl Bidiagonal {
    /// Bidiagonalises the column-major `a` of `m` rows (`m >= columns >= 1`).
    pub(super) fn new(mut a: Vec<f64>, m: usize) -> Self {
        let n = a.len() / m;
        let (mut left, mut right) = (vec![0.0; n], vec![0.0; n.saturating_sub(1)]);
        let (mut diagonal, mut upper) = (vec![0.0; n], vec![0.0; n.saturating_sub(1)]);
        let mut row = Vec::with_capacity(n);
        let mut right_tails = Vec::with_capacity(n.saturating_sub(1));
        let mut w = vec![0.0; m];
        for i in 0..n {
            let (done, rest) = a.split_at_mut((i + 1) * m);
            let col = &mut done[i * m + i..];
            left[i] = reflector(col);
            diagonal[i] = col[0];
            if left[i] != 0.0 {
                reflect_columns(&col[1..], left[i], rest, m, i);
            }
            if i + 1 == n {
                break;
            }
            // Row `i` right of the diagonal, reduced by `G_i`, applied to the rows below.
            row.clear();
            row.extend(rest.chunks_exact(m).map(|c| c[i]));
            right[i] = reflector(&mut row);
            upper[i] = row[0];
            for (c, &v) in rest.chunks_exact_mut(m).zip(&row) {
                c[i] = v;
            }
            right_tails.push(row[1..].to_vec());
            if right[i] == 0.0 {
                continue;
            }
            // `A_2 = A_2 (I - tau v v^T)`, `A_2` rows `i + 1..`: `w = A_2 v`, `A_2 -= tau w v^T`.
            let w = &mut w[..m - i - 1];
            w.fill(0.0);
            let v = |k: usize| if k == 0 { 1.0 } else { row[k] };
            let mut columns = rest.chunks_exact(4 * m);
            for (g, four) in (&mut columns).enumerate() {
                let c = |j: usize| &four[j * m + i + 1..(j + 1) * m];
                let k = 4 * g;
                axpy4(
                    [v(k), v(k + 1), v(k + 2), v(k + 3)],
                    [c(0), c(1), c(2), c(3)],
                    w,
                );
            }
            let done = rest.len() / (4 * m) * 4;
            for (k, c) in columns.remainder().chunks_exact(m).enumerate() {
                axpy(v(done + k), &c[i + 1..], w);
            }
            for (k, c) in rest.chunks_exact_mut(m).enumerate() {
                let v = if k == 0 { 1.0 } else { row[k] };
                axpy(-right[i] * v, w, &mut c[i + 1..]);
            }
        }
        Bidiagonal {
            a,
            m,
            n,
            left,
            right,
            right_tails,
            diagonal,
            upper,
        }
    }

    /// `x = W^T x` (`m` entries).
    pub(super) fn left_tr(&self, x: &mut [f64]) {
        for i in (0..self.n).filter(|&i| self.left[i] != 0.0) {
            let tail = &self.a[i * self.m + i + 1..(i + 1) * self.m];
            reflect(tail, self.left[i], &mut x[i..]);
        }
    }

    /// `x = W x` (`m` entries).
    pub(super) fn left(&self, x: &mut [f64]) {
        for i in (0..self.n).rev().filter(|&i| self.left[i] != 0.0) {
            let tail = &self.a[i * self.m + i + 1..(i + 1) * self.m];
            reflect(tail, self.left[i], &mut x[i..]);
        }
    }

    /// `x = Z^T x` (`n` entries).
    pub(super) fn right_tr(&self, x: &mut [f64]) {
        for i in (0..self.n.saturating_sub(1)).filter(|&i| self.right[i] != 0.0) {
            reflect(&self.right_tails[i], self.right[i], &mut x[i + 1..]);
        }
    }

    /// `x = Z x` (`n` entries).
    pub(super) fn right(&self, x: &mut [f64]) {
        for i in (0..self.n.saturating_sub(1)).rev() {
            if self.right[i] != 0.0 {
                reflect(&self.right_tails[i], self.right[i], &mut x[i + 1..]);
            }
        }
    }
}

/// `argmin |B z - c|^2 + lambda |z|^2` for `B` upper bidiagonal (`d` its diagonal, `e` its
/// superdiagonal; `lambda >= 0`), by Givens rotations of `[B; sqrt(lambda) I]` (Eldén, "Algorithms
/// for the regularization of ill-conditioned least squares problems", BIT 17, 1977): per column
/// one rotation of `B`'s row into the ridge row (leaving a fill in the next column) and one of
/// that fill into the next ridge row, then back substitution on the upper bidiagonal `R`. A
/// column with neither data nor ridge (`R`'s diagonal zero) takes no step.
pub(super) fn bidiagonal_ridge(d: &[f64], e: &[f64], c: &[f64], lambda: f64) -> Vec<f64> {
    let k = d.len();
    let mu = lambda.max(0.0).sqrt();
    let (mut diagonal, mut upper, mut rhs) = (vec![0.0; k], vec![0.0; k], vec![0.0; k]);
    // The ridge row of the current column: its entry there and its right-hand side.
    let (mut beta, mut g) = (mu, 0.0);
    for i in 0..k {
        let (cos, sin, r) = givens(d[i], beta);
        diagonal[i] = r;
        rhs[i] = cos * c[i] + sin * g;
        if i + 1 < k {
            upper[i] = cos * e[i];
            // The ridge row left with `-sin e_i` in column `i + 1` and `cos g - sin c_i`,
            // rotated into the next ridge row (`mu` there, right-hand side 0).
            let left = cos * g - sin * c[i];
            let (_, sin_next, t) = givens(mu, -sin * e[i]);
            (beta, g) = (t, sin_next * left);
        }
    }
    let mut z = vec![0.0; k];
    for i in (0..k).rev() {
        let next = if i + 1 < k { upper[i] * z[i + 1] } else { 0.0 };
        z[i] = if diagonal[i] > 0.0 {
            (rhs[i] - next) / diagonal[i]
        } else {
            0.0
        };
    }
    z
}

/// The rotation `(cos, sin)` taking `(a, b)` to `(r, 0)`, `r = |(a, b)|`; the identity for
/// `(0, 0)`.
fn givens(a: f64, b: f64) -> (f64, f64, f64) {
    let r = a.hypot(b);
    match r > 0.0 {
        true => (a / r, b / r, r),
        false => (1.0, 0.0, 0.0),
    }
}
