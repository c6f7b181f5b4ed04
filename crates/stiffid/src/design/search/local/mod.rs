//! Local search: SQP ([`super::sqp`]) from a start group, with exact gradients or forward finite
//! differences.

mod epigraph;

use super::constraints::{
    design_checker, inequalities, inequalities_and_gradients, kinds, most_failed, violation,
    CellConstraints,
};
use super::sqp::{self, Gradients, Nlp, SparseRows, Values};
use super::termination::{from_slsqp, Termination};
use super::{combine, Goal, Gradient, SearchOptions, SearchOutcome, Solver};
use crate::cell::{CheckKind, Checker};
use crate::design::PostureTerms;
use crate::design::{Criterion, Evaluator};
use crate::setup::Setup;
use crate::{Error, Result};
use epigraph::Epigraph;
use nalgebra::Vector6;
use std::cell::RefCell;
use std::collections::HashMap;

/// What the SQP minimises for a criterion value `v`: `ln v`, and this penalty for `+infinity`
/// (rank-deficient groups), above `ln f64::MAX ~ 709.8` so any finite value is better.
const PENALTY: f64 = 1e3;

/// Minimises `criterion` by SQP (the counterpart of the MATLAB `fmincon` of Zhang et al. 2021,
/// Section III-B step 5: [`SearchOptions::solver`], by default chosen per criterion by
/// [`Solver::resolve`]) over the `6n` axis angles of the `n` postures of `start` (rad), within the setup's
/// bounds.
///
/// - The objective is `ln(criterion)` (scale-free steps; a rank-deficient group, `+infinity`,
///   counts as a large finite penalty, never NaN, with a zero gradient). Its gradient is exact
///   ([`crate::design::Evaluator::value_and_gradient`], [`Gradient::Exact`], the default) or by
///   forward differences of step [`SearchOptions::fd_step`] ([`Gradient::FiniteDifference`]),
///   backwards where the forward probe would leave the bounds; a probe that hits a rank-deficient
///   group takes the other side, or a zero component.
/// - Every point evaluated is clamped into the bounds; the best point evaluated is returned, so the
///   result never leaves the bounds and is never worse than the start.
/// - The cell's feasibility checks ([`crate::cell::Checker`]: floor, obstacles, self-collision,
///   rope, line of sight, incidence, `[constraints]`) become one smooth inequality constraint per
///   check and posture (the smooth minimum of the check's pair margins, never above the exact
///   minimum); a point that violates the exact checks less always beats one that violates them
///   more, so the best exactly feasible point seen is returned.
/// - Stops at [`SearchOptions::ftol`] / [`SearchOptions::xtol`] (confirmed once from a fresh
///   Hessian approximation) or after at most [`SearchOptions::max_evals`] criterion evaluations
///   (finite differences included); [`SearchOutcome::termination`] says which.
///
/// # Errors
/// [`Error::InvalidField`] for `options` outside their limits ([`SearchOptions::validate`]), fewer
/// than 2 postures, or the `test-pose` criterion on a setup without test postures;
/// [`Error::OutsideBox`] for a start angle outside the bounds or not finite (naming the posture,
/// the axis and the value); [`Error::MissingField`] for a criterion the setup lacks a field for
/// ([`Criterion::check`]);
/// [`Error::Infeasible`] naming the check failed by the most postures when no point seen passes
/// every check.
///
/// # Examples
/// From a seeded start group of 8 postures on the paper's setup, SQP on `relative-a` ends lower,
/// within the bounds.
/// ```
/// use stiffid::design::{local, random_group, Criterion, SearchOptions};
/// let setup = stiffid::setup::builtin("zhang2021-comau-nj165")?;
/// let start = random_group(&setup, 8, 1);
/// let options = SearchOptions { max_evals: 200, ..SearchOptions::default() };
/// let out = local(&setup, Criterion::RelativeA, &start, &options)?;
/// assert!(out.value < out.start_value);
/// assert!(out.postures.iter().all(|q| setup.bounds().contains(q)));
/// # Ok::<(), stiffid::Error>(())
/// ```
pub fn local(
    setup: &Setup,
    criterion: Criterion,
    start: &[Vector6<f64>],
    options: &SearchOptions,
) -> Result<SearchOutcome> {
    local_for(setup, &Goal::stiffness(criterion), start, options)
}

/// [`local`] of any [`Goal`]: a stiffness criterion, a calibration criterion, or both.
///
/// # Errors
/// Those of [`local`]; [`Error::InvalidField`] (`postures`) for a group too small to separate
/// the calibration's kept parameters.
pub fn local_for(
    setup: &Setup,
    goal: &Goal,
    start: &[Vector6<f64>],
    options: &SearchOptions,
) -> Result<SearchOutcome> {
    options.validate()?;
    check_start(setup, goal, start)?;
    let checker = design_checker(setup, options.margin);
    let outcome = local_in(&checker, goal, start, options);
    infeasible(&checker, std::iter::once(&outcome))?;
    Ok(outcome)
}

/// [`local`] with a checker built once, from a checked start; the result may be infeasible.
pub(super) fn local_in(
    checker: &Checker,
    goal: &Goal,
    start: &[Vector6<f64>],
    options: &SearchOptions,
) -> SearchOutcome {
    Problem::new(checker, *goal, start.len(), options).run(start)
}

/// [`Error::Infeasible`] if the best of `outcomes` (the least violating) fails a check, naming the
/// check failed by the most postures of all of them.
pub(super) fn infeasible<'o>(
    checker: &Checker,
    outcomes: impl Iterator<Item = &'o SearchOutcome> + Clone,
) -> Result<()> {
    let feasible = |o: &SearchOutcome| o.postures.iter().all(|q| checker.violation(q) == 0.0);
    if !checker.constrains() || outcomes.clone().any(feasible) {
        return Ok(());
    }
    let groups = outcomes.map(|o| o.postures.as_slice());
    let (check, failed, postures) =
        most_failed(checker, groups).unwrap_or((CheckKind::Bounds, 0, 0));
    let check = match checker.keep() > 0.0 {
        false => check.key().to_string(),
        true => format!(
            "{} with its {} mm margin",
            check.key(),
            checker.keep() * 1e3
        ),
    };
    Err(Error::Infeasible {
        check,
        failed,
        postures,
    })
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
pub(super) fn check_start(setup: &Setup, goal: &Goal, start: &[Vector6<f64>]) -> Result<()> {
    check_count(setup, goal, start.len())?;
    for (i, q) in start.iter().enumerate() {
        let field = |a: usize| format!("start posture {}, q{}_deg", i + 1, a + 1);
        setup.bounds().check(q, "the setup's bounds", field)?;
    }
    Ok(())
}

/// Checks a group size and that the setup can evaluate the goal's criteria
/// ([`Criterion::check`]; a calibration needs at least as many coordinates as kept parameters).
pub(in crate::design) fn check_count(setup: &Setup, goal: &Goal, n: usize) -> Result<()> {
    if let Some(c) = goal.calibration {
        let (rows, kept) = (3 * c.design.model().points(), c.design.kept().len());
        if n >= 2 && n * rows < kept {
            return Err(Error::InvalidField {
                field: "postures".into(),
                message: format!(
                    "{n} given: the calibration's {kept} parameters need at least {} postures ({rows} coordinates each)",
                    kept.div_ceil(rows)
                ),
            });
        }
        if !goal.has_stiffness() {
            return check_size(n);
        }
    }
    let criterion = goal.stiffness;
    criterion.check(setup)?;
    check_size(n)?;
    // A posture gives at most min(3p, 6) independent rows of Psi.
    let rows = (3 * setup.tool().measuring_points.len()).min(6);
    let parameters = setup.model().len();
    if n * rows < parameters {
        return Err(Error::InvalidField {
            field: "postures".into(),
            message: format!(
                "{n} given: the model's {parameters} parameters need at least {} postures ({rows} independent rows each)",
                parameters.div_ceil(rows)
            ),
        });
    }
    if criterion == Criterion::TestPose && setup.test_postures().is_empty() {
        return Err(Error::InvalidField {
            field: "test.postures_deg".into(),
            message: "the test-pose criterion needs test postures in the setup".into(),
        });
    }
    Ok(())
}

/// At least 2 postures.
fn check_size(n: usize) -> Result<()> {
    match n < 2 {
        true => Err(Error::InvalidField {
            field: "postures".into(),
            message: format!("{n} given: a search needs at least 2 postures"),
        }),
        false => Ok(()),
    }
}

/// The SQP problem of one local search.
struct Problem<'a> {
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
    fn new(checker: &'a Checker<'a>, goal: Goal<'a>, n: usize, options: &'a SearchOptions) -> Self {
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

    fn run(self, start: &[Vector6<f64>]) -> SearchOutcome {
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

    /// The forward-difference gradient of `ln(criterion)` at `x`, where it is `f`. A probe changes
    /// one posture, so the other postures' terms are reused.
    fn fd_objective_gradient(&self, x: &[f64], f: f64) -> Vec<f64> {
        let postures = postures(x);
        if self.goal.calibration.is_some() {
            let mut g = vec![0.0; x.len()];
            self.fd_gradient(x, f, &mut g, |_, probe| {
                let probed = self::postures(probe);
                let value = self.goal_value(&probed);
                log_value(self.record(probe.to_vec(), &probed, value))
            });
            return g;
        }
        let terms: Vec<PostureTerms> = postures.iter().map(|q| self.evaluator.posture(q)).collect();
        let refs: Vec<&PostureTerms> = terms.iter().collect();
        let mut g = vec![0.0; x.len()];
        self.fd_gradient(x, f, &mut g, |k, probe| {
            let i = k / 6;
            let mut probed = postures.clone();
            probed[i] = Vector6::from_column_slice(&probe[6 * i..6 * i + 6]);
            let changed = self.evaluator.posture(&probed[i]);
            let mut refs = refs.clone();
            refs[i] = &changed;
            let value = self.evaluator.value_of(self.criterion, &refs);
            log_value(self.record(probe.to_vec(), &probed, value))
        });
        g
    }

    /// Forward differences of `f` at `x` (where it is `fx`), backwards at an upper bound or where
    /// the forward probe hits the penalty; 0 where both do. `f` gets the index changed and the
    /// probe.
    fn fd_gradient(
        &self,
        x: &[f64],
        fx: f64,
        g: &mut [f64],
        mut f: impl FnMut(usize, &[f64]) -> f64,
    ) {
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

    /// The cell's constraints of every posture of the angles `x` (the first `6n` entries),
    /// posture-major.
    fn constraint_values(&self, x: &[f64]) -> Vec<f64> {
        match self.options.gradient {
            Gradient::Exact => (0..self.n)
                .flat_map(|i| self.posture_constraints(i, posture(x, i), |c| c.values.clone()))
                .collect(),
            Gradient::FiniteDifference => (0..self.n)
                .flat_map(|i| inequalities(self.checker, &self.kinds, &posture(x, i)))
                .collect(),
        }
    }

    /// The gradients of [`Problem::constraint_values`], each on its posture's six angles.
    fn constraint_rows(&self, x: &[f64]) -> SparseRows {
        let mut c: SparseRows = Vec::with_capacity(self.n * self.kinds.len());
        for i in 0..self.n {
            self.posture_constraints(i, posture(x, i), |constraints| {
                c.extend(
                    constraints
                        .gradients
                        .iter()
                        .map(|g| g.iter().enumerate().map(|(a, v)| (6 * i + a, *v)).collect()),
                )
            });
        }
        c
    }

    /// `f` of the constraints of posture `i` at `q` (worked out together and reused).
    fn posture_constraints<R>(
        &self,
        i: usize,
        q: Vector6<f64>,
        f: impl FnOnce(&PostureConstraints) -> R,
    ) -> R {
        let mut cache = self.cache.borrow_mut();
        if cache.constraints[i].as_ref().is_none_or(|c| c.at != q) {
            let constraints = self.constraints_at(i, &q);
            if let Some(v) = constraints.violation {
                cache.remember(&q, v);
            }
            cache.constraints[i] = Some(constraints);
        }
        f(cache.constraints[i].as_ref().expect("just filled"))
    }

    /// Every constraint of posture `i` at `q`, and their gradients in `q`: exact
    /// ([`inequalities_and_gradients`]) with [`Gradient::Exact`], else by forward differences.
    fn constraints_at(&self, i: usize, q: &Vector6<f64>) -> PostureConstraints {
        if self.options.gradient == Gradient::Exact {
            let CellConstraints {
                values,
                gradients,
                violation,
            } = inequalities_and_gradients(self.checker, &self.kinds, q);
            return PostureConstraints {
                at: *q,
                values,
                gradients,
                violation: Some(violation),
            };
        }
        let values = inequalities(self.checker, &self.kinds, q);
        let mut gradients = vec![Vector6::zeros(); values.len()];
        let h = self.options.fd_step;
        for a in 0..6 {
            let step = if q[a] + h <= self.upper[6 * i + a] {
                h
            } else {
                -h
            };
            let mut probe = *q;
            probe[a] += step;
            let probed = inequalities(self.checker, &self.kinds, &probe);
            for (g, (p, v)) in gradients.iter_mut().zip(probed.iter().zip(&values)) {
                g[a] = (p - v) / step;
            }
        }
        PostureConstraints {
            at: *q,
            values,
            gradients,
            violation: None,
        }
    }
}

impl Nlp for Problem<'_> {
    fn bounds(&self) -> (&[f64], &[f64]) {
        (&self.lower, &self.upper)
    }

    /// `ln(criterion)` and the constraints of every posture, posture-major.
    fn values(&self, x: &[f64]) -> Values {
        let f = self.objective(x);
        Values {
            f,
            c: self.constraint_values(x),
        }
    }

    fn gradients(&self, x: &[f64], values: &Values) -> Gradients {
        let kept = self.gradient.borrow_mut().take();
        let f = match kept {
            Some((at, g)) if at == x => g,
            _ => self.fd_objective_gradient(x, values.f),
        };
        Gradients {
            f,
            c: self.constraint_rows(x),
        }
    }

    /// Whether a point and its gradient fit in the budget ([`evals_per_step`]).
    fn can_evaluate(&self) -> bool {
        let spent = self.state.borrow().evaluations;
        spent + evals_per_step(self.options, self.n) <= self.options.max_evals
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
