//! The SQP problem of one local search: the criterion's logarithm, the cell's constraints per
//! posture, the best point seen and the evaluations spent.

mod epigraph;
mod nlp;

use epigraph::Epigraph;

use super::{evals_per_step, PENALTY};
use crate::evaluator::PostureTerms;
use crate::search::constraints::{kinds, violation};
use crate::search::sqp::{self, Nlp};
use crate::search::termination::{from_slsqp, Termination};
use crate::search::{combine, Goal, Gradient, SearchOptions, SearchOutcome, Solver};
use crate::{Criterion, Evaluator};
use nalgebra::Vector6;
use std::cell::RefCell;
use std::collections::HashMap;
use stiffid_core::cell::{CheckKind, Checker};

/// The SQP problem of one local search.
pub(super) struct Problem<'a> {
    evaluator: Evaluator<'a>,
    checker: &'a Checker<'a>,
    criterion: Criterion,
    goal: Goal<'a>,
    n: usize,
    lower: Vec<f64>,
    upper: Vec<f64>,
    kinds: Vec<CheckKind>,
    options: &'a SearchOptions,
    state: RefCell<State>,
    cache: RefCell<Cache>,
    /// The point of the last exact objective evaluation and its gradient.
    gradient: RefCell<Option<(Vec<f64>, Vec<f64>)>>,
}

/// The best point seen and the evaluations spent.
struct State {
    evaluations: usize,
    start: Option<f64>,
    best: Option<(f64, f64, Vec<f64>)>,
}

/// Most postures whose exact violation is remembered (a probe changes one posture of a group).
const REMEMBERED: usize = 4096;

/// Per-posture results reused between calls: exact violations, and the constraint values with
/// their gradients of the postures last asked for.
#[derive(Default)]
struct Cache {
    violations: HashMap<[u64; 6], f64>,
    constraints: Vec<Option<PostureConstraints>>,
}

/// The constraints of one posture and their gradients in its six angles, and its exact violation
/// when worked out from the same margins.
#[derive(Clone)]
struct PostureConstraints {
    at: Vector6<f64>,
    values: Vec<f64>,
    gradients: Vec<Vector6<f64>>,
    violation: Option<f64>,
}

impl<'a> Problem<'a> {
    pub(super) fn new(
        checker: &'a Checker<'a>,
        goal: Goal<'a>,
        n: usize,
        options: &'a SearchOptions,
    ) -> Self {
        let setup = checker.setup();
        let b = &setup.bounds();
        Self {
            evaluator: Evaluator::new(setup),
            checker,
            criterion: goal.stiffness,
            goal,
            n,
            lower: (0..6 * n).map(|k| b.lower[k % 6]).collect(),
            upper: (0..6 * n).map(|k| b.upper[k % 6]).collect(),
            kinds: kinds(checker),
            options,
            state: RefCell::new(State {
                evaluations: 0,
                start: None,
                best: None,
            }),
            gradient: RefCell::new(None),
            cache: RefCell::new(Cache {
                constraints: vec![None; n],
                ..Cache::default()
            }),
        }
    }

    pub(super) fn run(self, start: &[Vector6<f64>]) -> SearchOutcome {
        let x0: Vec<f64> = start.iter().flat_map(|q| q.iter().copied()).collect();
        let stop = match self.goal.solver(self.options.solver) {
            Solver::ActiveSet if self.can_evaluate() => match Epigraph::applies(&self) {
                true => Epigraph::new(&self, &self.clamp(&x0)).minimise(self.tolerances()),
                false => sqp::minimise(&self, &self.clamp(&x0), self.tolerances()),
            },
            Solver::ActiveSet => {
                self.value(&x0);
                Termination::EvaluationLimit
            }
            // `resolve` never returns `Auto`.
            Solver::Slsqp | Solver::Auto => {
                self.value(&x0);
                let iterations =
                    self.options.max_evals.saturating_sub(1) / evals_per_step(self.options, self.n);
                match iterations {
                    0 => Termination::EvaluationLimit,
                    _ => self.slsqp(&x0, iterations),
                }
            }
        };
        let state = self.state.into_inner();
        let start_value = state.start.expect("the start was evaluated");
        let (violation, value, x) = state.best.expect("the start was evaluated");
        let termination = match violation > 0.0 {
            true => Termination::Infeasible,
            false => stop,
        };
        SearchOutcome {
            postures: postures(&x),
            start_value,
            value,
            evaluations: state.evaluations,
            termination,
            terminations: vec![termination],
        }
    }

    /// The goal's value at `postures` ([`Goal::value`]).
    fn goal_value(&self, postures: &[Vector6<f64>]) -> f64 {
        self.goal.value(&self.evaluator, postures)
    }

    /// The goal's value at `postures` and the gradient of its logarithm.
    fn goal_value_and_log_gradient(&self, postures: &[Vector6<f64>]) -> (f64, Vec<Vector6<f64>>) {
        let stiffness = || {
            let terms: Vec<PostureTerms> =
                postures.iter().map(|q| self.evaluator.posture(q)).collect();
            let refs: Vec<&PostureTerms> = terms.iter().collect();
            self.evaluator.value_and_log_gradient(self.criterion, &refs)
        };
        let Some(c) = self.goal.calibration else {
            return stiffness();
        };
        let (v, g) = c.design.value_and_log_gradient(c.criterion, postures);
        if !self.goal.has_stiffness() {
            return (v, g);
        }
        let (vs, gs) = stiffness();
        let w = c.weight;
        let gradient = (g.iter().zip(&gs))
            .map(|(gc, gs)| gc * w + gs * (1.0 - w))
            .collect();
        (combine(vs, v, w), gradient)
    }

    /// The stops of our SQP.
    fn tolerances(&self) -> sqp::Tolerances {
        sqp::Tolerances {
            ftol: self.options.ftol,
            xtol: self.options.xtol,
        }
    }

    /// Runs SLSQP from `x0` for at most `iterations` calls; why it stopped.
    fn slsqp(&self, x0: &[f64], iterations: usize) -> Termination {
        let bounds: Vec<(f64, f64)> = self
            .lower
            .iter()
            .copied()
            .zip(self.upper.iter().copied())
            .collect();
        let objective =
            |x: &[f64], grad: Option<&mut [f64]>, _: &mut ()| self.slsqp_objective(x, grad);
        let constraints: Vec<_> = (0..self.n)
            .flat_map(|i| (0..self.kinds.len()).map(move |k| (i, k)))
            .map(|(i, k)| {
                move |x: &[f64], grad: Option<&mut [f64]>, _: &mut ()| {
                    self.slsqp_constraint(i, k, x, grad)
                }
            })
            .collect();
        let cons: Vec<&dyn slsqp::Func<()>> = constraints
            .iter()
            .map(|c| c as &dyn slsqp::Func<()>)
            .collect();
        let tolerances = slsqp::StopTols {
            ftol_abs: self.options.ftol,
            xtol_abs: vec![self.options.xtol; x0.len()],
            ..Default::default()
        };
        // The best point is tracked in `state`; slsqp's outcome gives the stop reason.
        let outcome = slsqp::minimize(
            objective,
            x0,
            &bounds,
            &cons,
            (),
            iterations,
            Some(tolerances),
        );
        from_slsqp(&outcome)
    }

    /// `ln(criterion)` at `x` (clamped) for SLSQP, and its gradient if asked for.
    fn slsqp_objective(&self, x: &[f64], grad: Option<&mut [f64]>) -> f64 {
        let x = self.clamp(x);
        let f = self.objective(&x);
        if let Some(g) = grad {
            let kept = self.gradient.borrow_mut().take();
            match kept {
                Some((at, kept)) if at == x => g.copy_from_slice(&kept),
                _ => g.copy_from_slice(&self.fd_objective_gradient(&x, f)),
            }
        }
        f
    }

    /// Constraint `k` (of [`Problem::kinds`]) of posture `i` at `x` for SLSQP: `c <= 0` (m, or
    /// rad for angles), with its gradient (nonzero on the six angles of posture i only).
    fn slsqp_constraint(&self, i: usize, k: usize, x: &[f64], grad: Option<&mut [f64]>) -> f64 {
        let x = self.clamp(x);
        self.posture_constraints(i, posture(&x, i), |c| {
            if let Some(g) = grad {
                g.fill(0.0);
                g[6 * i..6 * i + 6].copy_from_slice(c.gradients[k].as_slice());
            }
            c.values[k]
        })
    }

    fn clamp(&self, x: &[f64]) -> Vec<f64> {
        x.iter()
            .enumerate()
            .map(|(k, v)| v.clamp(self.lower[k], self.upper[k]))
            .collect()
    }

    /// The criterion at `x` (clamped), recorded if best so far.
    fn value(&self, x: &[f64]) -> f64 {
        let x = self.clamp(x);
        let postures = postures(&x);
        let value = self.goal_value(&postures);
        self.record(x, &postures, value)
    }

    /// Counts an evaluation and keeps `x` if it is the best so far (least constraint violation,
    /// then lowest value). Returns `value`.
    fn record(&self, x: Vec<f64>, postures: &[Vector6<f64>], value: f64) -> f64 {
        if self.options.gradient == Gradient::Exact {
            // The constraints with their gradients, needed at this point too, bring the exact
            // violation from the same margins.
            for (i, q) in postures.iter().enumerate() {
                self.posture_constraints(i, *q, |_| ());
            }
        }
        let violation = self.violation(postures);
        let mut state = self.state.borrow_mut();
        state.evaluations += 1;
        state.start.get_or_insert(value);
        let replace = match &state.best {
            None => true,
            Some((v, f, _)) => violation < *v || (violation == *v && value < *f),
        };
        if replace {
            state.best = Some((violation, value, x));
        }
        value
    }

    /// The exact violation of a group: the sum of its postures' (remembered per posture).
    fn violation(&self, postures: &[Vector6<f64>]) -> f64 {
        if self.kinds.is_empty() {
            return 0.0;
        }
        let mut cache = self.cache.borrow_mut();
        postures
            .iter()
            .map(|q| match cache.violations.get(&key(q)) {
                Some(&v) => v,
                None => cache.remember(q, violation(self.checker, q)),
            })
            .sum()
    }

    /// `ln(criterion)` at `x` (clamped): with its exact gradient, kept for [`sqp::Nlp::gradients`],
    /// under [`Gradient::Exact`]; alone (from [`Evaluator::value`], which keeps no terms) under
    /// [`Gradient::FiniteDifference`].
    fn objective(&self, x: &[f64]) -> f64 {
        let postures = postures(x);
        if self.options.gradient == Gradient::FiniteDifference {
            let value = self.goal_value(&postures);
            return log_value(self.record(x.to_vec(), &postures, value));
        }
        let (value, gradient) = self.goal_value_and_log_gradient(&postures);
        let f = log_value(self.record(x.to_vec(), &postures, value));
        let g = match f >= PENALTY {
            true => vec![0.0; x.len()],
            false => gradient.iter().flat_map(|d| d.iter().copied()).collect(),
        };
        *self.gradient.borrow_mut() = Some((x.to_vec(), g));
        f
    }
}

impl Cache {
    /// Remembers the exact violation `v` of posture `q` (forgetting all when full); returns `v`.
    fn remember(&mut self, q: &Vector6<f64>, v: f64) -> f64 {
        if self.violations.len() >= REMEMBERED {
            self.violations.clear();
        }
        self.violations.insert(key(q), v);
        v
    }
}

/// The bits of a posture's angles, the key of [`Cache::violations`].
fn key(q: &Vector6<f64>) -> [u64; 6] {
    q.map(f64::to_bits).into()
}

/// Posture `i` of the variables `x`.
fn posture(x: &[f64], i: usize) -> Vector6<f64> {
    Vector6::from_column_slice(&x[6 * i..6 * i + 6])
}

/// The postures of the variables `x` (6 angles each).
fn postures(x: &[f64]) -> Vec<Vector6<f64>> {
    x.chunks(6).map(Vector6::from_column_slice).collect()
}

/// `ln v`, or [`PENALTY`] for `+infinity` or NaN.
fn log_value(v: f64) -> f64 {
    if v.is_finite() && v > 0.0 {
        v.ln()
    } else {
        PENALTY
    }
}
