//! Local search: SLSQP from a start group, with exact gradients or forward finite differences.

use super::constraints::{kinds, Kind};
use super::{Gradient, SearchOptions, SearchOutcome};
use crate::design::PostureTerms;
use crate::design::{Criterion, Evaluator};
use crate::setup::Setup;
use crate::{Error, Result};
use nalgebra::Vector6;
use std::cell::RefCell;

/// What the SQP minimises for a criterion value `v`: `ln v`, and this penalty for `+infinity`
/// (rank-deficient groups), above `ln f64::MAX ~ 709.8` so any finite value is better.
const PENALTY: f64 = 1e3;

/// Minimises `criterion` by SQP (SLSQP through the `slsqp` crate, the counterpart of the MATLAB
/// `fmincon` of Zhang et al. 2021, Section III-B step 5) over the `6n` axis angles of the `n`
/// postures of `start` (rad), within the setup's bounds.
///
/// - The objective is `ln(criterion)` (scale-free steps; a rank-deficient group, `+infinity`,
///   counts as a large finite penalty, never NaN, with a zero gradient). Its gradient is exact
///   ([`crate::design::Evaluator::value_and_gradient`], [`Gradient::Exact`], the default) or by
///   forward differences of step [`SearchOptions::fd_step`] ([`Gradient::FiniteDifference`]),
///   backwards where the forward probe would leave the bounds; a probe that hits a rank-deficient
///   group takes the other side, or a zero component.
/// - Every point evaluated is clamped into the bounds; the best point evaluated is returned, so the
///   result never leaves the bounds and is never worse than the start.
/// - The setup's [`crate::setup::CellConstraints`] become inequality constraints per posture
///   (loading point at or above `loading_point_min_z`, rope anchor at or below the loading point);
///   a point that satisfies them better always beats one that satisfies them worse.
/// - Stops at [`SearchOptions::ftol`] / [`SearchOptions::xtol`] or after at most
///   [`SearchOptions::max_evals`] criterion evaluations (finite differences included).
///
/// # Errors
/// [`Error::InvalidField`] for fewer than 2 postures, a non-finite angle or one outside the bounds
/// (naming the posture and axis), or the `test-pose` criterion on a setup without test postures.
pub fn local(
    setup: &Setup,
    criterion: Criterion,
    start: &[Vector6<f64>],
    options: &SearchOptions,
) -> Result<SearchOutcome> {
    check_start(setup, criterion, start)?;
    let problem = Problem::new(setup, criterion, start.len(), options);
    Ok(problem.run(start))
}

/// Criterion evaluations of one SQP call for `n` postures: 1 with the exact gradient, `6n + 1`
/// with finite differences.
pub(super) fn evals_per_step(options: &SearchOptions, n: usize) -> usize {
    match options.gradient {
        Gradient::Exact => 1,
        Gradient::FiniteDifference => 6 * n + 1,
    }
}

/// Checks a start group: at least 2 postures, finite, within the bounds.
pub(super) fn check_start(
    setup: &Setup,
    criterion: Criterion,
    start: &[Vector6<f64>],
) -> Result<()> {
    check_count(setup, criterion, start.len())?;
    for (i, q) in start.iter().enumerate() {
        for a in 0..6 {
            let (l, u) = (setup.bounds.lower[a], setup.bounds.upper[a]);
            if !(q[a].is_finite() && q[a] >= l && q[a] <= u) {
                return Err(Error::InvalidField {
                    field: format!("start posture {}, axis {}", i + 1, a + 1),
                    message: format!(
                        "{:.3} deg: expected within the bounds [{:.2}, {:.2}] deg",
                        q[a].to_degrees(),
                        l.to_degrees(),
                        u.to_degrees()
                    ),
                });
            }
        }
    }
    Ok(())
}

/// Checks a group size and that the setup can evaluate the criterion.
pub(in crate::design) fn check_count(setup: &Setup, criterion: Criterion, n: usize) -> Result<()> {
    if n < 2 {
        return Err(Error::InvalidField {
            field: "postures".into(),
            message: format!("{n} given: a search needs at least 2 postures"),
        });
    }
    if criterion == Criterion::TestPose && setup.test_postures.is_empty() {
        return Err(Error::InvalidField {
            field: "test.postures_deg".into(),
            message: "the test-pose criterion needs test postures in the setup".into(),
        });
    }
    Ok(())
}

/// The SQP problem of one local search.
struct Problem<'a> {
    evaluator: Evaluator<'a>,
    criterion: Criterion,
    n: usize,
    lower: Vec<f64>,
    upper: Vec<f64>,
    kinds: Vec<Kind>,
    options: &'a SearchOptions,
    state: RefCell<State>,
}

/// The best point seen and the evaluations spent.
struct State {
    evaluations: usize,
    best: Option<(f64, f64, Vec<f64>)>,
}

impl<'a> Problem<'a> {
    fn new(setup: &'a Setup, criterion: Criterion, n: usize, options: &'a SearchOptions) -> Self {
        let b = &setup.bounds;
        Self {
            evaluator: Evaluator::new(setup),
            criterion,
            n,
            lower: (0..6 * n).map(|k| b.lower[k % 6]).collect(),
            upper: (0..6 * n).map(|k| b.upper[k % 6]).collect(),
            kinds: kinds(setup),
            options,
            state: RefCell::new(State {
                evaluations: 0,
                best: None,
            }),
        }
    }

    fn run(self, start: &[Vector6<f64>]) -> SearchOutcome {
        let x0: Vec<f64> = start.iter().flat_map(|q| q.iter().copied()).collect();
        let start_value = self.value(&x0);
        let iterations =
            self.options.max_evals.saturating_sub(1) / evals_per_step(self.options, self.n);
        if iterations > 0 {
            self.minimise(&x0, iterations);
        }
        let state = self.state.into_inner();
        let (_, value, x) = state.best.expect("the start was evaluated");
        SearchOutcome {
            postures: postures(&x),
            start_value,
            value,
            evaluations: state.evaluations,
        }
    }

    fn minimise(&self, x0: &[f64], iterations: usize) {
        let bounds: Vec<(f64, f64)> = self
            .lower
            .iter()
            .copied()
            .zip(self.upper.iter().copied())
            .collect();
        let objective = |x: &[f64], grad: Option<&mut [f64]>, _: &mut ()| self.objective(x, grad);
        let constraints: Vec<_> = (0..self.n)
            .flat_map(|i| self.kinds.iter().map(move |&k| (i, k)))
            .map(|(i, k)| {
                move |x: &[f64], grad: Option<&mut [f64]>, _: &mut ()| {
                    self.constraint(i, k, x, grad)
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
        // The best point is tracked in `state`; slsqp's own outcome (success or failure status)
        // adds nothing to it.
        let _ = slsqp::minimize(
            objective,
            x0,
            &bounds,
            &cons,
            (),
            iterations,
            Some(tolerances),
        );
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
        let value = self.evaluator.value(self.criterion, &postures);
        self.record(x, &postures, value)
    }

    /// Counts an evaluation and keeps `x` if it is the best so far (least constraint violation,
    /// then lowest value). Returns `value`.
    fn record(&self, x: Vec<f64>, postures: &[Vector6<f64>], value: f64) -> f64 {
        let violation = self.violation(postures);
        let mut state = self.state.borrow_mut();
        state.evaluations += 1;
        let replace = match &state.best {
            None => true,
            Some((v, f, _)) => violation < *v || (violation == *v && value < *f),
        };
        if replace {
            state.best = Some((violation, value, x));
        }
        value
    }

    fn violation(&self, postures: &[Vector6<f64>]) -> f64 {
        if self.kinds.is_empty() {
            return 0.0;
        }
        let setup = self.evaluator.setup();
        postures.iter().map(|q| super::violation(setup, q)).sum()
    }

    /// `ln(criterion)` at `x`, and its gradient if asked for ([`SearchOptions::gradient`]).
    fn objective(&self, x: &[f64], grad: Option<&mut [f64]>) -> f64 {
        match (grad, self.options.gradient) {
            (Some(g), Gradient::Exact) => self.exact_objective(x, g),
            (grad, _) => self.fd_objective(x, grad),
        }
    }

    /// `ln(criterion)` at `x` and its exact gradient into `g` (zeros at the penalty).
    fn exact_objective(&self, x: &[f64], g: &mut [f64]) -> f64 {
        let x = self.clamp(x);
        let postures = postures(&x);
        let terms: Vec<PostureTerms> = postures.iter().map(|q| self.evaluator.posture(q)).collect();
        let refs: Vec<&PostureTerms> = terms.iter().collect();
        let (value, gradient) = self.evaluator.value_and_log_gradient(self.criterion, &refs);
        let f = log_value(self.record(x, &postures, value));
        for (gi, d) in g.chunks_mut(6).zip(&gradient) {
            gi.copy_from_slice(d.as_slice());
        }
        if f >= PENALTY {
            g.fill(0.0);
        }
        f
    }

    /// `ln(criterion)` at `x`, and its forward-difference gradient if asked for. A probe changes
    /// one posture, so the other postures' terms are reused.
    fn fd_objective(&self, x: &[f64], grad: Option<&mut [f64]>) -> f64 {
        let x = self.clamp(x);
        let postures = postures(&x);
        let terms: Vec<PostureTerms> = postures.iter().map(|q| self.evaluator.posture(q)).collect();
        let refs: Vec<&PostureTerms> = terms.iter().collect();
        let value = self.evaluator.value_of(self.criterion, &refs);
        let f = log_value(self.record(x.clone(), &postures, value));
        if let Some(g) = grad {
            self.gradient(&x, f, g, |k, probe| {
                let i = k / 6;
                let mut probed = postures.clone();
                probed[i] = Vector6::from_column_slice(&probe[6 * i..6 * i + 6]);
                let changed = self.evaluator.posture(&probed[i]);
                let mut refs = refs.clone();
                refs[i] = &changed;
                let value = self.evaluator.value_of(self.criterion, &refs);
                log_value(self.record(probe.to_vec(), &probed, value))
            });
        }
        f
    }

    /// Forward differences of `f` at `x` (where it is `fx`), backwards at an upper bound or where
    /// the forward probe hits the penalty; 0 where both do. `f` gets the index changed and the
    /// probe.
    fn gradient(&self, x: &[f64], fx: f64, g: &mut [f64], mut f: impl FnMut(usize, &[f64]) -> f64) {
        let h = self.options.fd_step;
        let mut probe = x.to_vec();
        for k in 0..x.len() {
            g[k] = 0.0;
            if fx >= PENALTY {
                continue;
            }
            let first = if x[k] + h <= self.upper[k] { h } else { -h };
            for step in [first, -first] {
                probe[k] = (x[k] + step).clamp(self.lower[k], self.upper[k]);
                let d = probe[k] - x[k];
                if d == 0.0 {
                    continue;
                }
                let fp = f(k, &probe);
                if fp < PENALTY {
                    g[k] = (fp - fx) / d;
                    break;
                }
            }
            probe[k] = x[k];
        }
    }

    /// Constraint `k` of posture `i` at `x`: `c <= 0`, m, with its gradient (nonzero on the six
    /// angles of posture i only).
    fn constraint(&self, i: usize, k: Kind, x: &[f64], grad: Option<&mut [f64]>) -> f64 {
        let x = self.clamp(x);
        let setup = self.evaluator.setup();
        let c = |q: &[f64]| {
            let q = Vector6::from_column_slice(q);
            k.value(
                setup,
                setup.robot.frames(&q).point(&setup.tool.loading_point).z,
            )
        };
        let q = &x[6 * i..6 * i + 6];
        let value = c(q);
        if let Some(g) = grad {
            g.fill(0.0);
            let h = self.options.fd_step;
            let mut probe = q.to_vec();
            for a in 0..6 {
                let step = if q[a] + h <= self.upper[6 * i + a] {
                    h
                } else {
                    -h
                };
                probe[a] = q[a] + step;
                g[6 * i + a] = (c(&probe) - value) / step;
                probe[a] = q[a];
            }
        }
        value
    }
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
