//! The maximum-type criteria (`classical`, `zhang2021`: the worst posture's dexterity, times
//! `cond_2(Psi)` for `zhang2021`) searched in epigraph form by our SQP: one more variable `t`, the
//! objective `t + ln rest` (`rest = cond_2(Psi)`, or 1) and one smooth constraint per posture,
//! `ln k(J_N)_i - t <= 0`, beside the cell's. The maximum's kinks (two postures' dexterities
//! equal), where a gradient step of `ln F` zig-zags and BFGS stalls, become the corners of a
//! smooth problem: the QP sees every posture's dexterity at once and its multipliers say which
//! postures hold the maximum (Nocedal and Wright, Numerical Optimization, 2nd ed., Section 12.6,
//! minimax problems).
//!
//! Every point evaluated is recorded with its true criterion value at its postures, so the best
//! point seen is kept as in the plain search; `t` starts at the start group's worst `ln k(J_N)`.

use super::super::PENALTY;
use super::{log_value, postures, Problem};
use crate::evaluator::MaxSplit;
use crate::evaluator::PostureTerms;
use crate::search::sqp::{self, violation, Gradients, Nlp, Tolerances, Values, FEASIBLE};
use crate::search::termination::Termination;
use crate::search::Gradient;
use crate::Criterion;
use std::cell::RefCell;

/// The epigraph problem over a local search's [`Problem`]: the angles, then `t`.
pub(super) struct Epigraph<'p, 'a> {
    problem: &'p Problem<'a>,
    x0: Vec<f64>,
    lower: Vec<f64>,
    upper: Vec<f64>,
    /// The split of the last point evaluated, for its gradients.
    kept: RefCell<Option<(Vec<f64>, Option<MaxSplit>)>>,
}

impl<'p, 'a> Epigraph<'p, 'a> {
    /// Whether `problem` is searched in epigraph form: a maximum-type criterion with exact
    /// gradients.
    pub(crate) fn applies(problem: &Problem) -> bool {
        let maximum = matches!(
            problem.criterion,
            Criterion::Classical | Criterion::Zhang2021
        );
        maximum && problem.goal.calibration.is_none() && problem.options.gradient == Gradient::Exact
    }

    /// The problem from the angles `x0` (within the bounds), `t` at their worst `ln k(J_N)`.
    pub(super) fn new(problem: &'p Problem<'a>, x0: &[f64]) -> Self {
        let evaluator = &problem.evaluator;
        let worst = postures(x0)
            .iter()
            .map(|q| log_value(evaluator.dexterity(&evaluator.posture(q))))
            .fold(f64::NEG_INFINITY, f64::max);
        let with_t = |v: &[f64], t: f64| v.iter().copied().chain([t]).collect::<Vec<f64>>();
        Self {
            problem,
            x0: with_t(x0, worst),
            lower: with_t(&problem.lower, f64::NEG_INFINITY),
            upper: with_t(&problem.upper, f64::INFINITY),
            kept: RefCell::new(None),
        }
    }

    /// Runs our SQP from the start; why it stopped.
    pub(super) fn minimise(&self, tolerances: Tolerances) -> Termination {
        sqp::minimise(self, &self.x0, tolerances)
    }

    /// The criterion split at the angles `angles` ([`crate::Evaluator::max_split`]).
    fn split(&self, angles: &[f64]) -> Option<MaxSplit> {
        let evaluator = &self.problem.evaluator;
        let terms: Vec<PostureTerms> = postures(angles)
            .iter()
            .map(|q| evaluator.posture(q))
            .collect();
        let refs: Vec<&PostureTerms> = terms.iter().collect();
        evaluator.max_split(self.problem.criterion, &refs)
    }

    /// The angles of `x` (all but `t`).
    fn angles<'x>(&self, x: &'x [f64]) -> &'x [f64] {
        &x[..x.len() - 1]
    }
}

impl Nlp for Epigraph<'_, '_> {
    fn bounds(&self) -> (&[f64], &[f64]) {
        (&self.lower, &self.upper)
    }

    /// `t + ln rest`, the cell's constraints, then `ln k(J_N)_i - t` of every posture; a
    /// rank-deficient group or a singular posture counts [`PENALTY`] for `ln rest` and its
    /// `ln k(J_N)`.
    fn values(&self, x: &[f64]) -> Values {
        let (angles, t) = (self.angles(x), x[x.len() - 1]);
        let p = self.problem;
        let split = self.split(angles);
        let value = split.as_ref().map_or(f64::INFINITY, |s| s.value);
        p.record(angles.to_vec(), &postures(angles), value);
        let rest = split.as_ref().map_or(PENALTY, |s| s.rest.0);
        let mut c = p.constraint_values(angles);
        c.extend((0..p.n).map(|i| split.as_ref().map_or(PENALTY, |s| s.dexterities[i].0) - t));
        *self.kept.borrow_mut() = Some((x.to_vec(), split));
        Values { f: t + rest, c }
    }

    fn gradients(&self, x: &[f64], _: &Values) -> Gradients {
        let kept = self.kept.borrow_mut().take();
        let split = match kept {
            Some((at, split)) if at == x => split,
            _ => self.split(self.angles(x)),
        };
        let p = self.problem;
        let angles = 6 * p.n;
        let mut f = vec![0.0; angles + 1];
        f[angles] = 1.0;
        let mut c = p.constraint_rows(self.angles(x));
        if let Some(split) = &split {
            f[..angles]
                .iter_mut()
                .zip(split.rest.1.iter().flat_map(|g| g.iter()))
                .for_each(|(f, g)| *f = *g);
        }
        for i in 0..p.n {
            let mut row: Vec<(usize, f64)> = match &split {
                Some(s) => (0..6).map(|a| (6 * i + a, s.dexterities[i].1[a])).collect(),
                None => Vec::new(),
            };
            row.push((angles, -1.0));
            c.push(row);
        }
        Gradients { f, c }
    }

    fn can_evaluate(&self) -> bool {
        self.problem.can_evaluate()
    }

    /// The cell's constraints to [`FEASIBLE`]; the postures' `ln k(J_N)_i - t <= 0`, in the
    /// objective's units, to [`crate::SearchOptions::ftol`] (the QP keeps the maximum's
    /// postures active, and a step meets them to second order only: an exact test would never
    /// let the search stop).
    fn feasible(&self, c: &[f64]) -> bool {
        let cell = c.len() - self.problem.n;
        violation(&c[..cell]) <= FEASIBLE && violation(&c[cell..]) <= self.problem.options.ftol
    }
}
