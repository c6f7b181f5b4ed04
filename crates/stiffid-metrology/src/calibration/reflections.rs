//! The Golub-Kahan bidiagonalisation `S = W B Z^T` ([`Bidiagonal`], LAPACK's `dgebd2`) of a
//! choice's columns of a maps split's `R` and of the fit's `R` at each iteration, its orthogonal
//! factors kept as reflections (each one's vector below the diagonal, or right of the
//! superdiagonal, where it zeroed) and applied to vectors, never formed; and Eldén's ridge steps
//! on it ([`bidiagonal_ridge`]: every ridge or damping `lambda` in `O(k)` once `B` is known). The
//! reflections are the core's ([`stiffid_core::math::householder`]), applied four columns at a
//! time.

use stiffid_core::math::householder::{reflect, reflect_columns, reflector};
use stiffid_core::math::linalg::{axpy, axpy4};

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
