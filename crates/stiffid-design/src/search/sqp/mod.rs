//! Sequential quadratic programming for the posture searches: minimise `f(x)` subject to
//! `c_j(x) <= 0` and `lower <= x <= upper`, with smooth `f` and `c_j`.
//!
//! - **Method** (Powell 1978, "A fast algorithm for nonlinearly constrained optimization
//!   calculations", Lecture Notes in Mathematics 630; Nocedal and Wright, Numerical Optimization,
//!   2nd ed., Algorithm 18.3): each step solves the QP `min g^T d + 1/2 d^T B d` subject to the
//!   linearised constraints `c_j + a_j^T d <= 0` and the bounds, by the dual active-set method of
//!   Goldfarb and Idnani ([`qp`]); when the linearised constraints are incompatible, the QP is
//!   relaxed as in Kraft's SLSQP (1988): `c_j (1 - xi) + a_j^T d <= 0` for the violated `c_j`,
//!   `0 <= xi <= 1`, with `xi` weighted `RELAXATION` times `B`'s largest diagonal.
//! - **Hessian**: `B` starts as the identity and is updated by damped BFGS on the Lagrangian's
//!   gradient ([`hessian`]: Powell's damping keeps `B` positive definite; `B` and its inverse are
//!   both updated in `O(n^2)`, so a step factors no matrix).
//! - **Line search**: backtracking on the L1 merit function `f + sum_j mu_j max(0, c_j)`
//!   (Han 1977), `mu_j = max(lambda_j, (mu_j + lambda_j) / 2)` from the QP's multipliers
//!   `lambda_j` (Powell 1978); Armijo's condition with 0.1, quadratic interpolation clamped to
//!   `[0.1, 0.5]` of the last step, at most `BACKTRACKS` trials.
//! - **Stops** ([`Termination`]): at a point whose constraints hold ([`Nlp::feasible`]: their
//!   violations summed at most [`FEASIBLE`] unless the problem says otherwise) when a step
//!   changes `f` by less than `ftol` or the QP's predicted change `|g^T d| + sum lambda_j |c_j|`
//!   is below `ftol` ([`Termination::Converged`]), or every variable moves by less than `xtol`
//!   ([`Termination::StepTolerance`]); when the problem's budget is spent
//!   ([`Termination::EvaluationLimit`], tested where a step needs an evaluation, after the stops
//!   that need none); when the line search fails twice, the second time from `B = I`
//!   ([`Termination::LineSearchFailed`]); when the QP fails from `B = I`
//!   ([`Termination::SubproblemFailed`]). A stop with `B` other than the identity is confirmed
//!   from `B = I`: the search stops when that step fails or meets a stop too, or when the budget
//!   runs out first, for the reason being confirmed, and goes on otherwise.
//! - **Requirements**: `x0` within the bounds (finite); `f` and `c_j` finite where evaluated (a
//!   problem maps a failed evaluation to a large finite value).
//! - **Deterministic**: one thread, fixed-order arithmetic: the same problem gives the same bits.

pub(crate) mod hessian;
pub(crate) mod qp;

use super::termination::Termination;
use hessian::Hessian;
use qp::{Active, Qp, QpError, Row};
use stiffid_core::math::linalg::dot;

/// The constraint gradients' nonzeros: `(index, coefficient)` pairs, one list per constraint.
pub(crate) type SparseRows = Vec<Vec<(usize, f64)>>;

/// The values at a point: the objective and every constraint (`c_j <= 0` is feasible).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Values {
    /// The objective.
    pub f: f64,
    /// Every constraint, in order.
    pub c: Vec<f64>,
}

/// The gradients at a point: the objective's (dense) and the constraints' (sparse).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Gradients {
    /// The objective's gradient, one entry per variable.
    pub f: Vec<f64>,
    /// Each constraint's gradient, its nonzeros.
    pub c: SparseRows,
}

/// A problem for [`minimise`]: its bounds, values and gradients, and its evaluation budget.
pub(crate) trait Nlp {
    /// The bounds on the variables (`lower <= upper`; infinite for a free variable).
    fn bounds(&self) -> (&[f64], &[f64]);
    /// The values at `x` (within the bounds).
    fn values(&self, x: &[f64]) -> Values;
    /// The gradients at `x`, where [`Nlp::values`] gave `values`.
    fn gradients(&self, x: &[f64], values: &Values) -> Gradients;
    /// Whether the budget allows one more point: its values and, if accepted, its gradients.
    fn can_evaluate(&self) -> bool;
    /// Whether the constraint values `c` count as met for the stops: by default their violations
    /// summed are at most [`FEASIBLE`]. A problem whose constraints are in the objective's units
    /// may allow the objective's tolerance (a nonlinear constraint the QP keeps active is met to
    /// second order in the step, not exactly).
    fn feasible(&self, c: &[f64]) -> bool {
        violation(c) <= FEASIBLE
    }
}

/// Tolerances of [`minimise`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Tolerances {
    /// Stop when a step changes `f` by less than this.
    pub ftol: f64,
    /// Stop when a step moves every variable by less than this.
    pub xtol: f64,
}

/// Largest summed constraint violation of a point that counts as feasible for the stops, unless
/// the problem says otherwise ([`Nlp::feasible`]).
pub(crate) const FEASIBLE: f64 = 1e-10;
/// Weight of the relaxation variable of an incompatible QP, relative to `B`'s largest diagonal.
const RELAXATION: f64 = 1e4;
/// Most trial points of one line search.
const BACKTRACKS: usize = 10;
/// Armijo's sufficient-decrease fraction.
const ARMIJO: f64 = 0.1;

/// Minimises the problem from `x0` (module docs); returns why it stopped. The problem keeps the
/// points it evaluated (the best one is the caller's to choose).
pub(crate) fn minimise(nlp: &impl Nlp, x0: &[f64], tolerances: Tolerances) -> Termination {
    let mut search = Search::new(nlp, x0);
    loop {
        if let Some(stop) = search.step(tolerances) {
            return stop;
        }
    }
}

/// The state of an SQP run.
struct Search<'p, P: Nlp> {
    nlp: &'p P,
    x: Vec<f64>,
    values: Values,
    gradients: Gradients,
    hessian: Hessian,
    penalties: Vec<f64>,
    /// The stop being confirmed from `B = I`, if any ([`Search::restart`]).
    confirming: Option<Termination>,
    /// The active set of the last QP, where the next one starts ([`Qp::solve_from`]).
    active: Active,
}

impl<'p, P: Nlp> Search<'p, P> {
    fn new(nlp: &'p P, x0: &[f64]) -> Self {
        let values = nlp.values(x0);
        let gradients = nlp.gradients(x0, &values);
        Self {
            nlp,
            x: x0.to_vec(),
            penalties: vec![0.0; values.c.len()],
            values,
            gradients,
            hessian: Hessian::identity(x0.len()),
            confirming: None,
            active: Active::default(),
        }
    }

    /// One SQP step; `Some` reason when the search stops.
    fn step(&mut self, tol: Tolerances) -> Option<Termination> {
        let Some((d, lambda, active)) = self.direction() else {
            // The retry from B = I starts its QP cold.
            self.active = Active::default();
            return self.restart(Termination::SubproblemFailed);
        };
        self.active = active;
        let feasible = self.nlp.feasible(&self.values.c);
        let predicted = dot(&self.gradients.f, &d).abs()
            + lambda
                .iter()
                .zip(&self.values.c)
                .map(|(l, c)| l * c.abs())
                .sum::<f64>();
        if feasible && predicted < tol.ftol {
            return self.restart(Termination::Converged);
        }
        for (mu, l) in self.penalties.iter_mut().zip(&lambda) {
            *mu = l.max(0.5 * (*mu + l));
        }
        let Some((x, values)) = self.line_search(&d) else {
            return match self.nlp.can_evaluate() {
                true => self.restart(Termination::LineSearchFailed),
                false => Some(self.out_of_budget()),
            };
        };
        let gradients = self.nlp.gradients(&x, &values);
        let s: Vec<f64> = x.iter().zip(&self.x).map(|(a, b)| a - b).collect();
        let y: Vec<f64> = lagrangian(&gradients, &lambda)
            .iter()
            .zip(lagrangian(&self.gradients, &lambda))
            .map(|(a, b)| a - b)
            .collect();
        let from_identity = self.hessian.fresh;
        self.hessian.update(&s, &y);
        let change = (values.f - self.values.f).abs();
        let moved = s.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        (self.x, self.values, self.gradients) = (x, values, gradients);
        let feasible = self.nlp.feasible(&self.values.c);
        let stop = match (feasible, change < tol.ftol, moved < tol.xtol) {
            (true, true, _) => Termination::Converged,
            (true, false, true) => Termination::StepTolerance,
            _ => {
                self.confirming = None;
                return None;
            }
        };
        self.restart_after(stop, from_identity)
    }

    /// Why the search stops when the budget is spent: the stop being confirmed, if any (the
    /// search had stopped; only its confirmation was cut short), else
    /// [`Termination::EvaluationLimit`].
    fn out_of_budget(&self) -> Termination {
        self.confirming.unwrap_or(Termination::EvaluationLimit)
    }

    /// After a failure or a stop before a step: [`Search::restart_after`] from the current `B`.
    fn restart(&mut self, reason: Termination) -> Option<Termination> {
        self.restart_after(reason, self.hessian.fresh)
    }

    /// After a failure or a stop: stop if the step was taken from `B = I` (`from_identity`), else
    /// start `B` again (a stop of a search through a kink, where BFGS has stalled, is confirmed
    /// from `B = I`). The reason is the stop being confirmed, if any, else `reason`.
    fn restart_after(&mut self, reason: Termination, from_identity: bool) -> Option<Termination> {
        if from_identity {
            return Some(self.confirming.take().unwrap_or(reason));
        }
        self.hessian = Hessian::identity(self.x.len());
        self.confirming = Some(reason);
        None
    }

    /// The QP's step, the multipliers of the constraints and the active set, relaxed if
    /// incompatible (a relaxed QP's active set is not kept: it has one more variable).
    fn direction(&self) -> Option<(Vec<f64>, Vec<f64>, Active)> {
        let (lower, upper) = self.nlp.bounds();
        let lower: Vec<f64> = lower.iter().zip(&self.x).map(|(l, x)| l - x).collect();
        let upper: Vec<f64> = upper.iter().zip(&self.x).map(|(u, x)| u - x).collect();
        let rows: Vec<Row> = self
            .gradients
            .c
            .iter()
            .zip(&self.values.c)
            .map(|(a, c)| Row {
                a: a.clone(),
                b: -c,
            })
            .collect();
        let qp = Qp {
            inverse: self.hessian.inverse(),
            gradient: &self.gradients.f,
            lower: &lower,
            upper: &upper,
            rows: &rows,
        };
        match qp.solve_from(&self.active) {
            Ok(s) => Some((s.d, s.multipliers, s.active)),
            Err(QpError::Infeasible) => self
                .relaxed(&lower, &upper, rows)
                .map(|(d, m)| (d, m, Active::default())),
            Err(_) => None,
        }
    }

    /// The relaxed QP (module docs): one more variable `xi`, the violated rows relaxed by it.
    fn relaxed(
        &self,
        lower: &[f64],
        upper: &[f64],
        mut rows: Vec<Row>,
    ) -> Option<(Vec<f64>, Vec<f64>)> {
        let n = self.x.len();
        let m = n + 1;
        let (h, mut inverse) = (self.hessian.inverse(), vec![0.0; m * m]);
        for k in 0..n {
            inverse[m * k..m * k + n].copy_from_slice(&h[n * k..n * k + n]);
        }
        let largest = self.hessian.largest_diagonal().max(1.0);
        inverse[m * m - 1] = 1.0 / (RELAXATION * largest);
        for (row, &c) in rows.iter_mut().zip(&self.values.c) {
            if c > 0.0 {
                row.a.push((n, -c));
            }
        }
        let gradient: Vec<f64> = self.gradients.f.iter().copied().chain([0.0]).collect();
        let lower: Vec<f64> = lower.iter().copied().chain([0.0]).collect();
        let upper: Vec<f64> = upper.iter().copied().chain([1.0]).collect();
        let qp = Qp {
            inverse: &inverse,
            gradient: &gradient,
            lower: &lower,
            upper: &upper,
            rows: &rows,
        };
        let mut s = qp.solve().ok()?;
        s.d.truncate(n);
        Some((s.d, s.multipliers))
    }

    /// Backtracking on the L1 merit function along `d`: the accepted point and its values.
    fn line_search(&self, d: &[f64]) -> Option<(Vec<f64>, Values)> {
        let merit0 = merit(&self.values, &self.penalties);
        let slope = dot(&self.gradients.f, d) - penalty(&self.values.c, &self.penalties);
        let (lower, upper) = self.nlp.bounds();
        let mut alpha = 1.0;
        for _ in 0..BACKTRACKS {
            if !self.nlp.can_evaluate() {
                return None;
            }
            let x: Vec<f64> = (0..d.len())
                .map(|k| (self.x[k] + alpha * d[k]).clamp(lower[k], upper[k]))
                .collect();
            let values = self.nlp.values(&x);
            let m = merit(&values, &self.penalties);
            if m <= merit0 + ARMIJO * alpha * slope {
                return Some((x, values));
            }
            let excess = m - merit0 - slope * alpha;
            let quadratic = match excess > 0.0 && excess.is_finite() {
                true => -slope * alpha / (2.0 * excess),
                false => 0.1,
            };
            alpha *= quadratic.clamp(0.1, 0.5);
        }
        None
    }
}

/// The gradient of the Lagrangian `f + sum_j lambda_j c_j`.
fn lagrangian(g: &Gradients, lambda: &[f64]) -> Vec<f64> {
    let mut out = g.f.clone();
    for (row, &l) in g.c.iter().zip(lambda) {
        if l != 0.0 {
            row.iter().for_each(|&(i, a)| out[i] += l * a);
        }
    }
    out
}

/// The summed violation `sum_j max(0, c_j)`.
pub(crate) fn violation(c: &[f64]) -> f64 {
    c.iter().map(|c| c.max(0.0)).sum()
}

/// `sum_j mu_j max(0, c_j)`.
fn penalty(c: &[f64], mu: &[f64]) -> f64 {
    c.iter().zip(mu).map(|(c, m)| m * c.max(0.0)).sum()
}

/// The L1 merit function.
fn merit(v: &Values, mu: &[f64]) -> f64 {
    v.f + penalty(&v.c, mu)
}

#[cfg(test)]
mod tests;
