//! Non-negative least squares for six compliances: the active-set method of Lawson and Hanson
//! ("Solving Least Squares Problems", 1974, ch. 23, algorithm NNLS), the method of SciPy's
//! `scipy.optimize.nnls` and MATLAB's `lsqnonneg`.
//!
//! It solves `min |A x - b|` subject to `x >= 0` for the 6x6 triangular factor `A = R` of the
//! observation matrix and `b = c` (first six entries of `Q^T delta`), which has the same minimiser
//! as the full problem `min |Psi h - delta|` and needs no normal equations. Starting from `x = 0`
//! with every variable at its bound, it frees the variable with the largest gradient of the
//! objective `w = A^T (b - A x)` and solves the least-squares problem of the free variables (by
//! QR); a free variable that would turn negative stops the step at the bound and is held there
//! again. It ends when no held variable has a positive gradient (the Karush-Kuhn-Tucker conditions
//! of the bounded problem, convex: the minimum is global). For 6 unknowns it takes a few steps;
//! it stops at `MAX_STEPS_PER_UNKNOWN` steps per unknown otherwise ([`Stop::IterationLimit`],
//! with a [`warning`]).

use nalgebra::{DMatrix, DVector, Matrix6, Vector6};
use stiffid_core::common::stop::Stop;
use stiffid_core::common::warning::{Warning, WarningKind};

/// The most active-set steps (a variable freed) per unknown.
pub(crate) const MAX_STEPS_PER_UNKNOWN: usize = 30;

/// The bounded fit.
#[derive(Debug, Clone, PartialEq)]
pub struct Bounded {
    /// The minimiser, every entry `>= 0`.
    pub h: Vector6<f64>,
    /// Which entries are held at the bound 0 (the active constraints).
    pub active: [bool; 6],
    /// Why the active-set steps stopped: [`Stop::Converged`], the Karush-Kuhn-Tucker conditions
    /// met (the bounded minimum); or [`Stop::IterationLimit`].
    pub stop: Stop,
}

/// The bounded fit of any number of unknowns ([`solve_general`]).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct BoundedGeneral {
    /// The minimiser, every entry `>= 0`.
    pub h: DVector<f64>,
    /// Which entries are held at the bound 0 (the active constraints).
    pub active: Vec<bool>,
    /// Why the active-set steps stopped (as [`Bounded::stop`]).
    pub stop: Stop,
}

/// `min |a x - b|` subject to `x >= 0` (module docs). `a` must have full rank (a [`stiffid_core::math::lsq::Factor`]'s `R`).
pub fn solve(a: &Matrix6<f64>, b: &Vector6<f64>) -> Bounded {
    let a = DMatrix::from_column_slice(6, 6, a.as_slice());
    let fit = solve_general(&a, &DVector::from_column_slice(b.as_slice()));
    Bounded {
        h: Vector6::from_column_slice(fit.h.as_slice()),
        active: std::array::from_fn(|j| fit.active[j]),
        stop: fit.stop,
    }
}

/// `min |a x - b|` subject to `x >= 0` for an `m x n` matrix `a` of full column rank (module docs;
/// any `m >= n`: the triangular factor or the whole observation matrix).
pub(crate) fn solve_general(a: &DMatrix<f64>, b: &DVector<f64>) -> BoundedGeneral {
    solve_within(a, b, MAX_STEPS_PER_UNKNOWN * a.ncols())
}

/// [`solve_general`] in at most `steps` active-set steps (each frees one unknown): `a` is `m x n`
/// with `m >= n` and full column rank, `b` has `m` entries. A fit cut at the limit says so in its
/// `stop` ([`Stop::IterationLimit`]), with the unknowns freed so far.
pub(crate) fn solve_within(a: &DMatrix<f64>, b: &DVector<f64>, steps: usize) -> BoundedGeneral {
    let n = a.ncols();
    let tolerance =
        10.0 * f64::EPSILON * a.abs().column_sum().max() * n as f64 * b.norm().max(1e-300);
    let mut x = DVector::zeros(n);
    let mut free = vec![false; n];
    let mut stop = Stop::IterationLimit;
    for _ in 0..steps {
        let w = a.tr_mul(&(b - a * &x));
        let entering = (0..n)
            .filter(|&j| !free[j] && w[j] > tolerance)
            .max_by(|&i, &j| w[i].total_cmp(&w[j]));
        let Some(t) = entering else {
            stop = Stop::Converged;
            break;
        };
        free[t] = true;
        loop {
            let z = free_solution(a, b, &free);
            if (0..n).all(|j| !free[j] || z[j] > 0.0) {
                x = z;
                break;
            }
            // Step from x toward z until the first free variable reaches 0.
            let alpha = (0..n)
                .filter(|&j| free[j] && z[j] <= 0.0)
                .map(|j| x[j] / (x[j] - z[j]))
                .fold(f64::INFINITY, f64::min);
            x += (z - &x) * alpha;
            for j in 0..n {
                if free[j] && x[j] <= 0.0 {
                    free[j] = false;
                    x[j] = 0.0;
                }
            }
            if !free.iter().any(|f| *f) {
                break;
            }
        }
    }
    // The last step may have met the conditions.
    if stop == Stop::IterationLimit && kkt(a, b, &x, &free, tolerance) {
        stop = Stop::Converged;
    }
    BoundedGeneral {
        h: x,
        active: free.iter().map(|f| !f).collect(),
        stop,
    }
}

/// Whether no held variable of `x` has a gradient `w = a^T (b - a x)` above `tolerance`.
fn kkt(
    a: &DMatrix<f64>,
    b: &DVector<f64>,
    x: &DVector<f64>,
    free: &[bool],
    tolerance: f64,
) -> bool {
    let w = a.tr_mul(&(b - a * x));
    (0..free.len()).all(|j| free[j] || w[j] <= tolerance)
}

/// A warning ([`WarningKind::NotConverged`]) when the non-negative least squares of `unknowns`
/// compliances stopped at its step limit: the compliances may not be the bounded minimum.
pub fn warning(stop: Stop, unknowns: usize) -> Option<Warning> {
    (stop != Stop::Converged).then(|| {
        Warning::new(
            WarningKind::NotConverged,
            format!(
                "the non-negative least squares stopped at its limit of {} active-set steps without meeting its optimality conditions: the compliances may not be the bounded minimum; fit without the bounds (least squares), or look at the model",
                MAX_STEPS_PER_UNKNOWN * unknowns
            ),
        )
    })
}

/// The least-squares solution over the free variables (by QR), zero elsewhere.
fn free_solution(a: &DMatrix<f64>, b: &DVector<f64>, free: &[bool]) -> DVector<f64> {
    let index: Vec<usize> = (0..free.len()).filter(|&j| free[j]).collect();
    let qr = a.select_columns(&index).qr();
    let qtb = qr.q().tr_mul(b);
    let z = qr
        .r()
        .solve_upper_triangular(&qtb)
        .unwrap_or_else(|| DVector::zeros(qtb.len()));
    let mut x = DVector::zeros(free.len());
    for (value, j) in z.iter().zip(index) {
        x[j] = *value;
    }
    x
}

/// The columns of `a` that are free, as a 6 x k matrix.
fn free_columns(a: &Matrix6<f64>, free: &[bool; 6]) -> DMatrix<f64> {
    let index: Vec<usize> = (0..6).filter(|&j| free[j]).collect();
    DMatrix::from_fn(6, index.len(), |i, k| a[(i, index[k])])
}

/// `(A_F^T A_F)^-1` of the free columns `F` (those not `active`), embedded in a 6x6 matrix with
/// zero rows and columns for the active ones: the covariance per unit noise variance of the
/// compliances with the active ones fixed at their bound.
pub(crate) fn unit_covariance(a: &Matrix6<f64>, active: &[bool; 6]) -> Matrix6<f64> {
    let free = active.map(|a| !a);
    let mut out = Matrix6::zeros();
    if !free.iter().any(|f| *f) {
        return out;
    }
    let r = free_columns(a, &free).qr().r();
    let k = r.nrows();
    let r_inv = r
        .solve_upper_triangular(&DMatrix::identity(k, k))
        .unwrap_or_else(|| DMatrix::from_element(k, k, f64::NAN));
    let small = &r_inv * r_inv.transpose();
    let index: Vec<usize> = (0..6).filter(|&j| free[j]).collect();
    for (a, &i) in index.iter().enumerate() {
        for (b, &j) in index.iter().enumerate() {
            out[(i, j)] = small[(a, b)];
        }
    }
    out
}
