//! Linear least squares for the observation matrix, by Householder QR (never normal equations).
//!
//! `Psi = Q R` with `Q` (m x 6) orthonormal columns and `R` (6x6) upper triangular. Then
//! `h = R^-1 Q^T delta` solves Eq. 13-14 without forming `Psi^T Psi` (whose condition number is
//! `cond^2(Psi)`, Eq. 19), and `(Psi^T Psi)^-1 = R^-1 R^-T`. The singular values of `R` are those of
//! `Psi`. A factor is made once per observation matrix and reused for many right-hand sides (Monte
//! Carlo runs).
//!
//! The six-column case is small enough that general-purpose routines spend most of their time on
//! bookkeeping, so [`Factor::try_new`] uses two specialised kernels: Householder QR in place on the
//! columns of a copy of `Psi` (LAPACK `dgeqrf` convention, `Q` kept as its six reflectors), and
//! one-sided Jacobi (Hestenes) for the singular values of `R`, which are accurate to a few ulps
//! relative to each singular value (Demmel & Veselic 1992), as good as the SVD.

use crate::{Error, Result};
use nalgebra::{DMatrix, DVector, Matrix6, Vector6};

/// Relative singular-value threshold below which `Psi` counts as rank deficient.
pub const RANK_TOLERANCE: f64 = 1e-10;

/// A QR factorisation of a full-column-rank `m x 6` observation matrix.
#[derive(Debug, Clone)]
pub struct Factor {
    /// `R` on and above the diagonal, the Householder vectors (without their leading 1) below.
    reflectors: DMatrix<f64>,
    /// `tau_k` of the reflectors `H_k = I - tau_k v_k v_k^T`, `Q = H_1 .. H_6`.
    taus: Vector6<f64>,
    r: Matrix6<f64>,
    r_inv: Matrix6<f64>,
    singular_values: Vector6<f64>,
}

impl Factor {
    /// Factors `psi` (m x 6, m >= 6).
    ///
    /// # Errors
    /// [`Error::TooFewRows`] for m < 6 (or a matrix without 6 columns), [`Error::NotFinite`] for NaN
    /// or infinite entries (checked before any decomposition), [`Error::Unidentifiable`] naming the
    /// joints whose column is zero (norm at most [`RANK_TOLERANCE`] times the largest column norm:
    /// no posture loads them or no measuring point moves with them) or
    /// whose columns are dependent (smallest singular value below [`RANK_TOLERANCE`] times the
    /// largest).
    pub fn try_new(psi: &DMatrix<f64>) -> Result<Self> {
        if psi.nrows() < 6 || psi.ncols() != 6 {
            return Err(Error::TooFewRows { rows: psi.nrows() });
        }
        let m = psi.nrows();
        let column = |j: usize| &psi.as_slice()[j * m..(j + 1) * m];
        let norms: [f64; 6] = std::array::from_fn(|j| dot(column(j), column(j)).sqrt());
        if !norms.iter().all(|n| n.is_finite()) && !psi.iter().all(|v| v.is_finite()) {
            return Err(Error::NotFinite {
                what: "the observation matrix".into(),
            });
        }
        let largest = norms.iter().fold(0.0, |a: f64, n| a.max(*n));
        let unloaded: Vec<usize> = (0..6)
            .filter(|&j| norms[j] <= largest * RANK_TOLERANCE)
            .map(|j| j + 1)
            .collect();
        if !unloaded.is_empty() {
            return Err(Error::Unidentifiable {
                joints: unloaded,
                reason: "no posture loads the joint or moves a measuring point with it (zero column of Psi)".into(),
            });
        }
        let mut reflectors = psi.clone();
        let taus = householder_qr(reflectors.as_mut_slice(), psi.nrows());
        let r = Matrix6::from_fn(|i, j| if i <= j { reflectors[(i, j)] } else { 0.0 });
        let singular_values = jacobi_singular_values(&r);
        if singular_values.min() <= singular_values.max() * RANK_TOLERANCE {
            return Err(dependent_columns(&r));
        }
        let r_inv = r
            .solve_upper_triangular(&Matrix6::identity())
            .ok_or_else(|| dependent_columns(&r))?;
        Ok(Self {
            reflectors,
            taus,
            r,
            r_inv,
            singular_values,
        })
    }

    /// The least-squares solution `h = argmin |Psi h - delta|` (Eq. 13-14). `delta` has m entries.
    ///
    /// # Panics
    /// If `delta` does not have as many entries as `Psi` has rows.
    pub fn solve(&self, delta: &DVector<f64>) -> Vector6<f64> {
        assert_eq!(
            delta.len(),
            self.reflectors.nrows(),
            "delta must have one entry per row of Psi"
        );
        let mut d = delta.clone();
        let m = d.len();
        let (a, d) = (self.reflectors.as_slice(), d.as_mut_slice());
        for k in 0..6 {
            let v = &a[k * m + k + 1..(k + 1) * m];
            let w = self.taus[k] * (d[k] + dot(v, &d[k + 1..]));
            d[k] -= w;
            axpy(-w, v, &mut d[k + 1..]);
        }
        self.r_inv * Vector6::from_column_slice(&d[..6])
    }

    /// `(Psi^T Psi)^-1 = R^-1 R^-T`: the covariance of `h` per unit noise variance.
    pub fn unit_covariance(&self) -> Matrix6<f64> {
        self.r_inv * self.r_inv.transpose()
    }

    /// The triangular factor `R` (6x6).
    pub fn r(&self) -> &Matrix6<f64> {
        &self.r
    }

    /// The singular values of `Psi`, in no particular order.
    pub fn singular_values(&self) -> &Vector6<f64> {
        &self.singular_values
    }

    /// The 2-norm condition number `cond_2(Psi) = s_max / s_min`.
    pub fn cond(&self) -> f64 {
        self.singular_values.max() / self.singular_values.min()
    }
}

/// Householder QR in place of the column-major `m x 6` matrix `a` (LAPACK `dgeqrf`): on return `R`
/// is on and above the diagonal and the reflector vectors `v_k` (with `v_k[k] = 1` implied) below
/// it. Returns the `tau_k`.
fn householder_qr(a: &mut [f64], m: usize) -> Vector6<f64> {
    let mut taus = Vector6::zeros();
    for k in 0..6 {
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
    taus
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
fn jacobi_singular_values(r: &Matrix6<f64>) -> Vector6<f64> {
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
            // The rotation that zeroes u_i . u_j: tan = t = 2g sign(d) / (|d| + sqrt(d^2 + 4g^2)),
            // d = |u_j|^2 - |u_i|^2 (the smaller root of t^2 g + t d - g = 0).
            let d = norms[j] - norms[i];
            let t = 2.0 * g * d.signum() / (d.abs() + (d * d + 4.0 * g * g).sqrt());
            let c = 1.0 / (1.0 + t * t).sqrt();
            let s = c * t;
            let (head, tail) = u.split_at_mut(j);
            let (ui, uj) = (&mut head[i], &mut tail[0]);
            for k in 0..6 {
                let (x, y) = (ui[k], uj[k]);
                ui[k] = c * x - s * y;
                uj[k] = s * x + c * y;
            }
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

/// The error for dependent columns of `Psi`: the joints with a large share in the right singular
/// vector of the smallest singular value of `R`.
fn dependent_columns(r: &Matrix6<f64>) -> Error {
    let joints = r
        .try_svd(false, true, f64::EPSILON, 200)
        .and_then(|svd| {
            let (imin, _) = svd.singular_values.argmin();
            let v = svd.v_t?.row(imin).transpose();
            Some(
                (0..6)
                    .filter(|&j| v[j].abs() > 0.1)
                    .map(|j| j + 1)
                    .collect(),
            )
        })
        .unwrap_or_else(|| (1..=6).collect());
    Error::Unidentifiable {
        joints,
        reason: "their columns of Psi are linearly dependent: choose postures that load them differently".into(),
    }
}

/// `a . b` over the shorter length, with four partial sums (independent chains run in parallel).
fn dot(a: &[f64], b: &[f64]) -> f64 {
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

fn axpy(alpha: f64, x: &[f64], y: &mut [f64]) {
    y.iter_mut().zip(x).for_each(|(y, x)| *y += alpha * x);
}
