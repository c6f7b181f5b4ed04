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
//! of the bounded problem, convex: the minimum is global). For 6 unknowns it takes a few steps.

use nalgebra::{DMatrix, DVector, Matrix6, Vector6};

/// The bounded fit.
#[derive(Debug, Clone, PartialEq)]
pub struct Bounded {
    /// The minimiser, every entry `>= 0`.
    pub h: Vector6<f64>,
    /// Which entries are held at the bound 0 (the active constraints).
    pub active: [bool; 6],
}

/// The bounded fit of any number of unknowns ([`solve_general`]).
#[derive(Debug, Clone, PartialEq)]
pub struct BoundedGeneral {
    /// The minimiser, every entry `>= 0`.
    pub h: DVector<f64>,
    /// Which entries are held at the bound 0 (the active constraints).
    pub active: Vec<bool>,
}

/// `min |a x - b|` subject to `x >= 0` (module docs). `a` must have full rank (a [`crate::math::lsq::Factor`]'s `R`).
pub fn solve(a: &Matrix6<f64>, b: &Vector6<f64>) -> Bounded {
    let a = DMatrix::from_column_slice(6, 6, a.as_slice());
    let fit = solve_general(&a, &DVector::from_column_slice(b.as_slice()));
    Bounded {
        h: Vector6::from_column_slice(fit.h.as_slice()),
        active: std::array::from_fn(|j| fit.active[j]),
    }
}

/// `min |a x - b|` subject to `x >= 0` for an `m x n` matrix `a` of full column rank (module docs;
/// any `m >= n`: the triangular factor or the whole observation matrix).
pub fn solve_general(a: &DMatrix<f64>, b: &DVector<f64>) -> BoundedGeneral {
    let n = a.ncols();
    let tolerance =
        10.0 * f64::EPSILON * a.abs().column_sum().max() * n as f64 * b.norm().max(1e-300);
    let mut x = DVector::zeros(n);
    let mut free = vec![false; n];
    for _ in 0..30 * n {
        let w = a.tr_mul(&(b - a * &x));
        let entering = (0..n)
            .filter(|&j| !free[j] && w[j] > tolerance)
            .max_by(|&i, &j| w[i].total_cmp(&w[j]));
        let Some(t) = entering else { break };
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
    BoundedGeneral {
        h: x,
        active: free.iter().map(|f| !f).collect(),
    }
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
pub fn unit_covariance(a: &Matrix6<f64>, active: &[bool; 6]) -> Matrix6<f64> {
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
