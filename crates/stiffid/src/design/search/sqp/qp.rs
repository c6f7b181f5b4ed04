//! Dense strictly convex quadratic programs with bounds and sparse inequality rows, by the dual
//! active-set method of Goldfarb and Idnani.
//!
//! Minimises `g^T d + 1/2 d^T B d` subject to `lower <= d <= upper` and `a_j^T d <= b_j`, with `B`
//! symmetric positive definite (`n x n`, dense, column-major).
//!
//! - **Method**: D. Goldfarb, A. Idnani, "A numerically stable dual method for solving strictly
//!   convex quadratic programs", Math. Programming 27 (1983) 1-33, in the form of Powell's and
//!   Turlach's `quadprog`: start at the unconstrained minimum `-B^-1 g`, add the most violated
//!   constraint (bounds and rows alike, each measured in its normal's length), take full or partial
//!   steps and drop constraints whose multiplier would turn negative. The factor `J = L^-T Q`
//!   (`B = L L^T`) and the triangular `R` of the active normals are updated by Givens rotations, so
//!   adding or dropping a constraint costs `O(n^2)`; a bound's normal is a unit vector, so its
//!   `J^T e_i` is a row of `J`.
//! - **Cost**: one Cholesky factor and triangular inverse, `n^3 / 2` multiply-adds, then `O(n^2)` per
//!   active-set change.
//! - **Requirements**: `B` positive definite (a damped BFGS matrix is); finite data.
//! - **Result**: the minimiser, the multipliers of the rows (`>= 0`, 0 for inactive rows), or
//!   [`QpError::Infeasible`] when no `d` satisfies the constraints (a step of the dual that finds no
//!   primal direction), [`QpError::NotPositiveDefinite`], or [`QpError::IterationLimit`] (more
//!   than `10 (n + rows) + 100` active-set changes, which only cycling on degenerate constraints
//!   reaches).
//!
//! Deterministic: the same data give the same bits (fixed-order loops, ties to the lowest index).

use crate::linalg::{axpy, dot};

/// A sparse inequality row `a^T d <= b`: `(index, coefficient)` pairs, indices below `n`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Row {
    pub a: Vec<(usize, f64)>,
    pub b: f64,
}

/// Why a QP has no solution.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum QpError {
    /// No point satisfies the constraints.
    Infeasible,
    /// `B` is not (numerically) positive definite.
    NotPositiveDefinite,
    /// The active set changed more than the limit.
    IterationLimit,
}

/// The solution of a QP.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Solution {
    /// The minimiser (`n`).
    pub d: Vec<f64>,
    /// The multiplier of every row (`>= 0`; 0 if inactive).
    pub multipliers: Vec<f64>,
}

/// A constraint: bound `i` below (`Lower`) or above, or row `j`; in the `n^T d >= c` form.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Constraint {
    Lower(usize),
    Upper(usize),
    Row(usize),
}

/// The data of a QP: `B` (column-major `n x n`), `g`, the bounds on `d` and the rows.
pub(crate) struct Qp<'a> {
    pub hessian: &'a [f64],
    pub gradient: &'a [f64],
    pub lower: &'a [f64],
    pub upper: &'a [f64],
    pub rows: &'a [Row],
}

/// Relative tolerance under which a constraint counts as satisfied, and a direction as zero.
const EPS: f64 = 1e-12;

impl Qp<'_> {
    /// Solves the QP (module docs).
    pub(crate) fn solve(&self) -> Result<Solution, QpError> {
        let n = self.gradient.len();
        let mut s = State::new(self, inverse_cholesky(self.hessian, n)?);
        let limit = 10 * (2 * n + self.rows.len()) + 100;
        let mut changes = 0;
        while let Some(p) = self.most_violated(&s) {
            s.u.push(0.0);
            loop {
                changes += 1;
                if changes > limit {
                    return Err(QpError::IterationLimit);
                }
                let d = self.j_transpose(&s.j, n, p);
                let z = s.primal_direction(&d);
                let r = s.dual_direction(&d);
                let (t1, k) = s.partial_step(&r);
                let nz = self.dot(p, &z);
                let t2 = match nz > EPS * self.norm(p) * norm(&z) && norm(&z) > 0.0 {
                    true => -self.slack(p, &s.x) / nz,
                    false => f64::INFINITY,
                };
                let t = t1.min(t2);
                if t == f64::INFINITY {
                    return Err(QpError::Infeasible);
                }
                s.step_dual(t, &r);
                if t2.is_finite() {
                    s.x.iter_mut().zip(&z).for_each(|(x, z)| *x += t * z);
                }
                if t == t2 {
                    s.add(p, d);
                    break;
                }
                s.drop(k.expect("a partial step has an index"));
            }
        }
        Ok(self.solution(s))
    }

    /// The solution from the final state: the point and the rows' multipliers.
    fn solution(&self, s: State) -> Solution {
        let mut multipliers = vec![0.0; self.rows.len()];
        for (c, u) in s.active.iter().zip(&s.u) {
            if let Constraint::Row(j) = *c {
                multipliers[j] = *u;
            }
        }
        Solution {
            d: s.x,
            multipliers,
        }
    }

    /// The most violated inactive constraint at `s.x` (slack over the normal's length), if any
    /// is violated beyond the tolerance; the lowest index on ties.
    fn most_violated(&self, s: &State) -> Option<Constraint> {
        let n = self.gradient.len();
        let scale = 1.0 + s.x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let mut best: Option<(f64, Constraint)> = None;
        let candidates = (0..n)
            .flat_map(|i| [Constraint::Lower(i), Constraint::Upper(i)])
            .chain((0..self.rows.len()).map(Constraint::Row));
        for c in candidates {
            let norm = self.norm(c);
            if norm == 0.0 || s.active.contains(&c) {
                continue;
            }
            let violation = -self.slack(c, &s.x) / norm;
            if violation > EPS * scale && best.is_none_or(|(v, _)| violation > v) {
                best = Some((violation, c));
            }
        }
        best.map(|(_, c)| c)
    }

    /// `n_c^T x - c_c`: the slack of constraint `c` in the `>=` form (negative when violated).
    fn slack(&self, c: Constraint, x: &[f64]) -> f64 {
        match c {
            Constraint::Lower(i) => x[i] - self.lower[i],
            Constraint::Upper(i) => self.upper[i] - x[i],
            Constraint::Row(j) => self.rows[j].b + self.dot(c, x),
        }
    }

    /// `n_c^T v` with the `>=`-form normal `n_c`.
    fn dot(&self, c: Constraint, v: &[f64]) -> f64 {
        match c {
            Constraint::Lower(i) => v[i],
            Constraint::Upper(i) => -v[i],
            Constraint::Row(j) => -self.rows[j].a.iter().map(|&(i, a)| a * v[i]).sum::<f64>(),
        }
    }

    /// The length of the normal of `c`, or 0 for an infinite bound (never active).
    fn norm(&self, c: Constraint) -> f64 {
        match c {
            Constraint::Lower(i) if self.lower[i].is_finite() => 1.0,
            Constraint::Upper(i) if self.upper[i].is_finite() => 1.0,
            Constraint::Row(j) => self.rows[j]
                .a
                .iter()
                .map(|(_, a)| a * a)
                .sum::<f64>()
                .sqrt(),
            _ => 0.0,
        }
    }

    /// `J^T n_c`.
    fn j_transpose(&self, j: &[f64], n: usize, c: Constraint) -> Vec<f64> {
        let row = |i: usize, sign: f64| (0..n).map(|k| sign * j[i + n * k]).collect::<Vec<f64>>();
        match c {
            Constraint::Lower(i) => row(i, 1.0),
            Constraint::Upper(i) => row(i, -1.0),
            Constraint::Row(r) => {
                let mut d = vec![0.0; n];
                for &(i, a) in &self.rows[r].a {
                    for (k, dk) in d.iter_mut().enumerate() {
                        *dk -= a * j[i + n * k];
                    }
                }
                d
            }
        }
    }
}

/// The iterate of the dual method: the point, `J` (column-major `n x n`), `R` (column-major, its
/// leading `q x q` block upper triangular), the active constraints and their multipliers.
struct State {
    n: usize,
    x: Vec<f64>,
    j: Vec<f64>,
    r: Vec<f64>,
    active: Vec<Constraint>,
    u: Vec<f64>,
}

impl State {
    /// The unconstrained minimum `-J J^T g` with `J = L^-T`.
    fn new(qp: &Qp, j: Vec<f64>) -> Self {
        let n = qp.gradient.len();
        let jtg: Vec<f64> = (0..n)
            .map(|k| dot(&j[n * k..n * k + n], qp.gradient))
            .collect();
        let mut x = vec![0.0; n];
        for (k, c) in jtg.iter().enumerate() {
            axpy(-c, &j[n * k..n * k + n], &mut x);
        }
        Self {
            n,
            x,
            j,
            r: vec![0.0; n * n],
            active: Vec::new(),
            u: Vec::new(),
        }
    }

    fn q(&self) -> usize {
        self.active.len()
    }

    /// `z = J_2 d_2`: the step in the primal space (the columns of `J` past the active ones).
    fn primal_direction(&self, d: &[f64]) -> Vec<f64> {
        let (n, q) = (self.n, self.q());
        let mut z = vec![0.0; n];
        for (k, dk) in d.iter().enumerate().skip(q) {
            axpy(*dk, &self.j[n * k..n * k + n], &mut z);
        }
        z
    }

    /// `r = R^-1 d_1`: the change of the active multipliers per unit step.
    fn dual_direction(&self, d: &[f64]) -> Vec<f64> {
        let (n, q) = (self.n, self.q());
        let mut r = d[..q].to_vec();
        for i in (0..q).rev() {
            let v = (i + 1..q).fold(r[i], |v, k| v - self.r[i + n * k] * r[k]);
            r[i] = v / self.r[i + n * i];
        }
        r
    }

    /// The longest dual step keeping the active multipliers non-negative, and the active index
    /// that limits it (the lowest on ties).
    fn partial_step(&self, r: &[f64]) -> (f64, Option<usize>) {
        let mut best = (f64::INFINITY, None);
        for (k, (&rk, &uk)) in r.iter().zip(&self.u).enumerate() {
            if rk > 0.0 && uk / rk < best.0 {
                best = (uk / rk, Some(k));
            }
        }
        best
    }

    /// `u+ <- u+ + t (-r, 1)`.
    fn step_dual(&mut self, t: f64, r: &[f64]) {
        let q = self.q();
        for (u, r) in self.u[..q].iter_mut().zip(r) {
            *u -= t * r;
        }
        self.u[q] += t;
    }

    /// Makes `c` active: rotates `d = J^T n_c` so that its entries past `q` vanish (the same
    /// rotations on `J`'s columns), and appends `d_1` as `R`'s new column.
    fn add(&mut self, c: Constraint, mut d: Vec<f64>) {
        let (n, q) = (self.n, self.q());
        for k in (q + 1..n).rev() {
            if d[k] == 0.0 {
                continue;
            }
            let h = d[k - 1].hypot(d[k]);
            let (cos, sin) = (d[k - 1] / h, d[k] / h);
            d[k - 1] = h;
            d[k] = 0.0;
            rotate_columns(&mut self.j, n, k - 1, cos, sin);
        }
        self.r[n * q..n * q + q + 1].copy_from_slice(&d[..=q]);
        self.active.push(c);
    }

    /// Drops active constraint `k`: removes its column of `R`, restores `R`'s triangle by Givens
    /// rotations of its rows (the same on `J`'s columns) and drops its multiplier.
    fn drop(&mut self, k: usize) {
        let (n, q) = (self.n, self.q());
        for col in k..q - 1 {
            self.r
                .copy_within(n * (col + 1)..n * (col + 1) + q, n * col);
        }
        for i in k..q - 1 {
            let (a, b) = (self.r[i + n * i], self.r[i + 1 + n * i]);
            if b == 0.0 {
                continue;
            }
            let h = a.hypot(b);
            let (cos, sin) = (a / h, b / h);
            for col in i..q - 1 {
                let (x, y) = (self.r[i + n * col], self.r[i + 1 + n * col]);
                self.r[i + n * col] = cos * x + sin * y;
                self.r[i + 1 + n * col] = -sin * x + cos * y;
            }
            rotate_columns(&mut self.j, n, i, cos, sin);
        }
        self.r[n * (q - 1)..n * q].fill(0.0);
        self.active.remove(k);
        self.u.remove(k);
    }
}

/// Columns `k` and `k + 1` of the column-major `n x n` matrix `j` replaced by `c j_k + s j_k+1`
/// and `-s j_k + c j_k+1`.
fn rotate_columns(j: &mut [f64], n: usize, k: usize, c: f64, s: f64) {
    let (left, right) = j.split_at_mut(n * (k + 1));
    let a = &mut left[n * k..];
    let b = &mut right[..n];
    for (x, y) in a.iter_mut().zip(b.iter_mut()) {
        let (u, v) = (*x, *y);
        *x = c * u + s * v;
        *y = -s * u + c * v;
    }
}

/// `J = L^-T` (column-major, upper triangular) for `B = L L^T`.
fn inverse_cholesky(b: &[f64], n: usize) -> Result<Vec<f64>, QpError> {
    // Lower Cholesky factor, column-major.
    let mut l = vec![0.0; n * n];
    for k in 0..n {
        let mut diag = b[k + n * k];
        for p in 0..k {
            diag -= l[k + n * p] * l[k + n * p];
        }
        let positive = diag > EPS * b[k + n * k].abs();
        if !positive || !diag.is_finite() {
            return Err(QpError::NotPositiveDefinite);
        }
        let diag = diag.sqrt();
        l[k + n * k] = diag;
        for i in k + 1..n {
            let mut v = b[i + n * k];
            for p in 0..k {
                v -= l[i + n * p] * l[k + n * p];
            }
            l[i + n * k] = v / diag;
        }
    }
    // J = L^-T: column k of J solves L^T j_k = e_k, i.e. row k of L^-1.
    let mut j = vec![0.0; n * n];
    for k in 0..n {
        // Solve L^T y = e_k (upper triangular L^T) into column k of j.
        let col = &mut j[n * k..n * k + n];
        col[k] = 1.0 / l[k + n * k];
        for i in (0..k).rev() {
            let mut v = 0.0;
            for p in i + 1..=k {
                v -= l[p + n * i] * col[p];
            }
            col[i] = v / l[i + n * i];
        }
    }
    Ok(j)
}

fn norm(v: &[f64]) -> f64 {
    dot(v, v).sqrt()
}
