//! Least squares in blocks of rows: `Psi` is never whole, the memory is that of one block.
//!
//! The problem `min |Psi h - delta|` is carried as `[R | c]` (6 x 7) with
//! `|Psi h - delta|^2 = |R h - c|^2 + const`. The next block `[Psi_b | delta_b]` is stacked under it
//! and the `(6 + b) x 7` matrix is reduced again by Householder QR (`crate::math::linalg`), so `R` is the
//! triangular factor of all rows so far (up to the signs of its rows) and `c` the first six entries
//! of `Q^T delta`: the QR of the whole `Psi`, never the normal equations (sequential QR, Golub &
//! Van Loan, Matrix Computations, 4th ed., Section 5.6; with independent blocks merged in a
//! reduction tree it is TSQR, Demmel et al. 2012, "Communication-optimal parallel and sequential
//! QR and LU factorizations"). Two reductions of disjoint rows merge the same way
//! ([`Reduced::merge`]), so blocks can be reduced in parallel and merged in a fixed order: the
//! result is then the same, to the bit, whatever the number of threads.

use super::checked_inverse;
use crate::math::householder::{householder_qr, upper_triangle};
use crate::math::linalg::column_norms;
use crate::{Error, Result};
use nalgebra::{DMatrix, DVector, Matrix6, Vector6};

/// A least-squares problem in six unknowns reduced to `[R | c]` (module docs).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Reduced {
    r: Matrix6<f64>,
    c: Vector6<f64>,
    rows: usize,
}

/// The least-squares solution of a [`Reduced`] problem.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    /// `h = R^-1 c = argmin |Psi h - delta|` (Eq. 13-14).
    pub h: Vector6<f64>,
    /// `(Psi^T Psi)^-1 = R^-1 R^-T`: the covariance of `h` per unit noise variance.
    pub unit_covariance: Matrix6<f64>,
    /// `cond_2(Psi) = cond_2(R)`.
    pub cond: f64,
}

impl Reduced {
    /// Adds the rows `psi` (b x 6) with right-hand side `delta` (b entries).
    ///
    /// # Panics
    /// If `psi` does not have six columns or `delta` not one entry per row.
    pub fn push(&mut self, psi: &DMatrix<f64>, delta: &DVector<f64>) {
        assert!(psi.ncols() == 6 && delta.len() == psi.nrows());
        self.stack(psi.nrows(), |j, i| match j {
            6 => delta[i],
            _ => psi[(i, j)],
        });
        self.rows += psi.nrows();
    }

    /// Adds the rows of another reduction (disjoint from these).
    pub fn merge(&mut self, other: &Reduced) {
        self.stack(6, |j, i| match j {
            6 => other.c[i],
            _ => other.r[(i, j)],
        });
        self.rows += other.rows;
    }

    /// The number of rows added.
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// `[R | c]` stacked on `b` rows given by `entry(column, row)`, reduced again by QR.
    fn stack(&mut self, b: usize, entry: impl Fn(usize, usize) -> f64) {
        let m = 6 + b;
        let mut a = vec![0.0; 7 * m];
        for (j, col) in a.chunks_exact_mut(m).enumerate() {
            for (i, x) in col[..6].iter_mut().enumerate() {
                *x = if j < 6 { self.r[(i, j)] } else { self.c[i] };
            }
            for (i, x) in col[6..].iter_mut().enumerate() {
                *x = entry(j, i);
            }
        }
        householder_qr(&mut a, m);
        self.r = upper_triangle(&a, m);
        self.c = Vector6::from_column_slice(&a[6 * m..6 * m + 6]);
    }

    /// The least-squares solution, with the checks and the rank rule of
    /// [`super::Factor::try_new`] (the column norms of `Psi` are those of `R`).
    ///
    /// # Errors
    /// As [`super::Factor::try_new`]: [`Error::TooFewRows`] for fewer than six rows,
    /// [`Error::NotFinite`], [`Error::Unidentifiable`] (with [`super::RANK_TOLERANCE`]).
    pub fn try_solve(&self) -> Result<Solution> {
        if self.rows < 6 {
            return Err(Error::TooFewRows { rows: self.rows });
        }
        let norms = column_norms(self.r.as_slice(), 6);
        let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
        if !finite(norms.as_slice()) && !finite(self.r.as_slice()) {
            return Err(Error::NotFinite {
                what: "the observation matrix".into(),
            });
        }
        let r_inv = checked_inverse(&self.r, &norms)?;
        Ok(Solution {
            h: r_inv * self.c,
            unit_covariance: r_inv * r_inv.transpose(),
            cond: crate::math::jacobi::cond(&self.r),
        })
    }
}
