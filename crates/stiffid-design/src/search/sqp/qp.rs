//! Dense strictly convex quadratic programs with bounds and sparse inequality rows, by the dual
//! active-set method of Goldfarb and Idnani, in range-space form.
//!
//! Minimises `g^T d + 1/2 d^T B d` subject to `lower <= d <= upper` and `a_j^T d <= b_j`, with `B`
//! symmetric positive definite (`n x n`, dense), given by its inverse `H = B^-1` (column-major):
//! the SQP keeps it up to date ([`super::hessian`]); [`inverse`] makes it from `B`.
//!
//! - **Method**: D. Goldfarb, A. Idnani, "A numerically stable dual method for solving strictly
//!   convex quadratic programs", Math. Programming 27 (1983) 1-33: start at the unconstrained
//!   minimum `-H g`, add the most violated constraint (bounds and rows alike, each measured in
//!   its normal's length), take full or partial steps and drop constraints whose multiplier would
//!   turn negative. The step directions are those of the paper, `z = H n_p - H N r` in the primal
//!   space and `r = (N^T H N)^-1 N^T H n_p` for the active multipliers (`N` the active normals,
//!   `n_p` the added one), from the Cholesky factor of `N^T H N`, which grows by one row when a
//!   constraint is added and is restored by Givens rotations when one is dropped (the range-space
//!   form; the paper keeps a factor of `B^-1` rotated instead, `O(n^2)` per change).
//! - **Cost**: `H g` once, `O(n^2)`; then `O(n q + q^2)` per active-set change with `q` active
//!   constraints: a bound's `H n` is a column of `H`, a row's a combination of as many columns as
//!   its nonzeros. Most of the searches' bounds are inactive, so `q` stays far below `n`.
//! - **Requirements**: `H` symmetric positive definite; finite data.
//! - **Result**: the minimiser, the multipliers of the rows (`>= 0`, 0 for inactive rows), or
//!   [`QpError::Infeasible`] when no `d` satisfies the constraints (a step of the dual that finds no
//!   primal direction), or [`QpError::IterationLimit`] (more than `10 (n + rows) + 100`
//!   active-set changes, which only cycling on degenerate constraints reaches).
//!
//! Deterministic: the same data give the same bits (fixed-order loops, ties to the lowest index).

use stiffid_core::math::linalg::{axpy, dot};

/// A sparse inequality row `a^T d <= b`: `(index, coefficient)` pairs, indices below `n`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Row {
    /// The nonzeros of `a`.
    pub a: Vec<(usize, f64)>,
    /// The bound `b`.
    pub b: f64,
}

/// Why a QP has no solution.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum QpError {
    /// No point satisfies the constraints.
    Infeasible,
    /// `B` is not (numerically) positive definite ([`inverse`]).
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
    /// The constraints active at the minimiser, to start the next QP of the same shape from
    /// ([`Qp::solve_from`]).
    pub active: Active,
    /// The active-set changes the dual method took (a warm start's additions not counted).
    pub changes: usize,
}

/// The active constraints of a QP's solution (bounds and rows), in the order they were added.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub(crate) struct Active(Vec<Constraint>);

/// A constraint: bound `i` below (`Lower`) or above, or row `j`; in the `n^T d >= c` form.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Constraint {
    Lower(usize),
    Upper(usize),
    Row(usize),
}

/// The data of a QP: `H = B^-1` (column-major `n x n`), `g`, the bounds on `d` and the rows.
pub(crate) struct Qp<'a> {
    /// `H = B^-1`, column-major `n x n`, symmetric positive definite.
    pub inverse: &'a [f64],
    /// The objective's gradient `g` (`n`).
    pub gradient: &'a [f64],
    /// The lower bounds on `d` (`n`).
    pub lower: &'a [f64],
    /// The upper bounds on `d` (`n`).
    pub upper: &'a [f64],
    /// The inequality rows.
    pub rows: &'a [Row],
}

/// Relative tolerance under which a constraint counts as satisfied, and a direction as zero.
const EPS: f64 = 1e-12;

/// A warm-start constraint whose pivot `n^T H n - |w|^2` is below this fraction of `n^T H n`
/// depends on those before it (to rounding) and is left out.
const WARM_INDEPENDENT: f64 = 1e-8;

/// `|z|` below this fraction of `|H n_p|`: `n_p` lies in the span of the active normals (up to
/// the rounding of the projection), there is no primal step.
const DEPENDENT: f64 = 1e-10;

impl Qp<'_> {
    /// Solves the QP (module docs).
    pub(crate) fn solve(&self) -> Result<Solution, QpError> {
        self.solve_from(&Active::default())
    }

    /// Solves the QP from the active set `warm` of a QP of the same shape (the last SQP step's):
    /// the dual method starts at the minimiser with those constraints held as equalities
    /// (`Qp::warm_start`) instead of the unconstrained minimum, so that an active set that
    /// changes little between steps costs few changes. The minimiser is the same (the QP is
    /// strictly convex); only the path to it is shorter.
    pub(crate) fn solve_from(&self, warm: &Active) -> Result<Solution, QpError> {
        let n = self.gradient.len();
        let mut s = State::new(self);
        self.warm_start(&mut s, &warm.0);
        let limit = 10 * (2 * n + self.rows.len()) + 100;
        let mut changes = 0;
        while let Some(p) = self.most_violated(&s) {
            s.u.push(0.0);
            let hn = self.h_times(p);
            loop {
                changes += 1;
                if changes > limit {
                    return Err(QpError::IterationLimit);
                }
                let nhn: Vec<f64> = s.hn.iter().map(|h| self.dot(p, h)).collect();
                let w = s.forward(&nhn);
                let r = s.backward(&w);
                let mut z = hn.clone();
                for (h, rk) in s.hn.iter().zip(&r) {
                    axpy(-rk, h, &mut z);
                }
                let (t1, k) = s.partial_step(&r);
                let nz = self.dot(p, &z);
                let primal = norm(&z) > DEPENDENT * norm(&hn);
                let t2 = match nz > EPS * s.norms[s.flag(p)] * norm(&z) && primal {
                    true => -self.slack(p, &s.x) / nz,
                    false => f64::INFINITY,
                };
                let t = t1.min(t2);
                if t == f64::INFINITY {
                    return Err(QpError::Infeasible);
                }
                s.step_dual(t, &r);
                if t2.is_finite() {
                    axpy(t, &z, &mut s.x);
                }
                if t == t2 {
                    s.add(p, hn, w, nz.sqrt());
                    break;
                }
                s.drop(k.expect("a partial step has an index"));
            }
        }
        Ok(self.solution(s, changes))
    }

    /// The solution from the final state: the point and the rows' multipliers.
    fn solution(&self, s: State, changes: usize) -> Solution {
        let mut multipliers = vec![0.0; self.rows.len()];
        for (c, u) in s.active.iter().zip(&s.u) {
            if let Constraint::Row(j) = *c {
                multipliers[j] = *u;
            }
        }
        Solution {
            d: s.x,
            multipliers,
            active: Active(s.active),
            changes,
        }
    }

    /// Makes the constraints of `warm` active (those of this QP's shape with a finite bound or a
    /// nonzero row, each independent of the ones before it), then drops the one with the most
    /// negative multiplier until none is negative: the equality-constrained minimiser
    /// `x = -H g + H N u`, `N^T H N u = -(N^T (-H g) - c)`, with `u >= 0` is a starting pair of
    /// the dual method (Goldfarb and Idnani 1983, Section 3).
    fn warm_start(&self, s: &mut State, warm: &[Constraint]) {
        let (n, rows) = (self.gradient.len(), self.rows.len());
        let x0 = s.x.clone();
        for &c in warm {
            let fits = match c {
                Constraint::Lower(i) | Constraint::Upper(i) => i < n,
                Constraint::Row(j) => j < rows,
            };
            if !fits || s.norms[s.flag(c)] == 0.0 || s.is_active(c) {
                continue;
            }
            let hn = self.h_times(c);
            let nhn: Vec<f64> = s.hn.iter().map(|h| self.dot(c, h)).collect();
            let w = s.forward(&nhn);
            let whole = self.dot(c, &hn);
            let pivot = whole - dot(&w, &w);
            if pivot > WARM_INDEPENDENT * whole && pivot.is_finite() {
                s.u.push(0.0);
                s.add(c, hn, w, pivot.sqrt());
            }
        }
        loop {
            let slack: Vec<f64> = s.active.iter().map(|&c| -self.slack(c, &x0)).collect();
            s.u = s.backward(&s.forward(&slack));
            let negative =
                s.u.iter()
                    .enumerate()
                    .filter(|(_, u)| **u < 0.0 || !u.is_finite())
                    .min_by(|a, b| a.1.total_cmp(b.1));
            match negative {
                Some((k, _)) => s.drop(k),
                None => break,
            }
        }
        s.x = x0;
        for (h, u) in s.hn.iter().zip(&s.u) {
            axpy(*u, h, &mut s.x);
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
            let norm = s.norms[s.flag(c)];
            if norm == 0.0 || s.is_active(c) {
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

    /// `H n_c`: a column of `H` for a bound, a combination of columns for a row.
    fn h_times(&self, c: Constraint) -> Vec<f64> {
        let n = self.gradient.len();
        let column = |i: usize| &self.inverse[n * i..n * i + n];
        match c {
            Constraint::Lower(i) => column(i).to_vec(),
            Constraint::Upper(i) => column(i).iter().map(|v| -v).collect(),
            Constraint::Row(r) => {
                let mut out = vec![0.0; n];
                for &(i, a) in &self.rows[r].a {
                    axpy(-a, column(i), &mut out);
                }
                out
            }
        }
    }
}

/// The iterate of the dual method: the point, the active constraints with their multipliers and
/// their `H n_k`, and the lower Cholesky factor `L` of `N^T H N` (row `k` holds `k + 1` entries).
struct State {
    x: Vec<f64>,
    active: Vec<Constraint>,
    u: Vec<f64>,
    hn: Vec<Vec<f64>>,
    l: Vec<Vec<f64>>,
    /// Whether each bound (lower, upper: `2i`, `2i + 1`) and row is active.
    flags: Vec<bool>,
    /// The length of each one's normal, in the same order ([`Qp::norm`]).
    norms: Vec<f64>,
}

impl State {
    /// The unconstrained minimum `-H g`, nothing active.
    fn new(qp: &Qp) -> Self {
        let n = qp.gradient.len();
        let mut x = vec![0.0; n];
        for (k, gk) in qp.gradient.iter().enumerate() {
            axpy(-gk, &qp.inverse[n * k..n * k + n], &mut x);
        }
        Self {
            x,
            active: Vec::new(),
            u: Vec::new(),
            hn: Vec::new(),
            l: Vec::new(),
            flags: vec![false; 2 * n + qp.rows.len()],
            norms: (0..n)
                .flat_map(|i| [Constraint::Lower(i), Constraint::Upper(i)])
                .chain((0..qp.rows.len()).map(Constraint::Row))
                .map(|c| qp.norm(c))
                .collect(),
        }
    }

    /// The index of `c` in [`State::flags`].
    fn flag(&self, c: Constraint) -> usize {
        let bounds = self.x.len();
        match c {
            Constraint::Lower(i) => 2 * i,
            Constraint::Upper(i) => 2 * i + 1,
            Constraint::Row(j) => 2 * bounds + j,
        }
    }

    fn is_active(&self, c: Constraint) -> bool {
        self.flags[self.flag(c)]
    }

    /// `L^-1 v`.
    fn forward(&self, v: &[f64]) -> Vec<f64> {
        let mut w = v.to_vec();
        for i in 0..w.len() {
            let row = &self.l[i];
            let v = (0..i).fold(w[i], |v, k| v - row[k] * w[k]);
            w[i] = v / row[i];
        }
        w
    }

    /// `L^-T w`.
    fn backward(&self, w: &[f64]) -> Vec<f64> {
        let mut r = w.to_vec();
        for i in (0..r.len()).rev() {
            let v = (i + 1..r.len()).fold(r[i], |v, k| v - self.l[k][i] * r[k]);
            r[i] = v / self.l[i][i];
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
        let q = self.active.len();
        for (u, r) in self.u[..q].iter_mut().zip(r) {
            *u -= t * r;
        }
        self.u[q] += t;
    }

    /// Makes `c` active: `L` gains the row `(w, pivot)` with `w = L^-1 N^T H n_c` and
    /// `pivot^2 = n_c^T H n_c - |w|^2 = n_c^T z`.
    fn add(&mut self, c: Constraint, hn: Vec<f64>, mut w: Vec<f64>, pivot: f64) {
        w.push(pivot);
        self.l.push(w);
        self.hn.push(hn);
        let f = self.flag(c);
        self.flags[f] = true;
        self.active.push(c);
    }

    /// Drops active constraint `k`: removes its row of `L` and its column by Givens rotations of
    /// the columns `k, k + 1, ...` of the rows below (which keep `L L^T`), and its multiplier.
    fn drop(&mut self, k: usize) {
        self.l.remove(k);
        for j in k..self.l.len() {
            let (a, b) = (self.l[j][j], self.l[j][j + 1]);
            if b == 0.0 {
                self.l[j].pop();
                continue;
            }
            let h = a.hypot(b);
            let (cos, sin) = (a / h, b / h);
            for row in &mut self.l[j..] {
                let (x, y) = (row[j], row[j + 1]);
                row[j] = cos * x + sin * y;
                row[j + 1] = -sin * x + cos * y;
            }
            self.l[j].pop();
        }
        let c = self.active.remove(k);
        let f = self.flag(c);
        self.flags[f] = false;
        self.hn.remove(k);
        self.u.remove(k);
    }
}

/// `H = B^-1` of a symmetric positive definite `B` (column-major `n x n`), from its Cholesky
/// factor.
///
/// # Errors
/// [`QpError::NotPositiveDefinite`] when a pivot is not positive (relative to `B`'s diagonal).
pub(crate) fn inverse(b: &[f64], n: usize) -> Result<Vec<f64>, QpError> {
    let j = inverse_cholesky(b, n)?;
    // H = J J^T with J = L^-T upper triangular.
    let mut h = vec![0.0; n * n];
    for k in 0..n {
        let column = &j[n * k..n * k + n];
        for i in 0..=k {
            axpy(column[i], &column[..=k], &mut h[n * i..n * i + k + 1]);
        }
    }
    Ok(h)
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
