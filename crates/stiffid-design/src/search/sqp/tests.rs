//! The SQP and its quadratic programs (`crate::search::sqp`).

//! The QP against known solutions and the KKT conditions; the SQP on small problems with known
//! minimisers, active constraints and an infeasible start.

use crate::search::sqp::hessian::Hessian;
use crate::search::sqp::qp::{inverse, Qp, QpError, Row};
use crate::search::sqp::*;
use crate::Termination;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::cell::Cell;

fn identity(n: usize) -> Vec<f64> {
    let mut b = vec![0.0; n * n];
    (0..n).for_each(|k| b[k + n * k] = 1.0);
    b
}

fn solve(b: &[f64], g: &[f64], lower: &[f64], upper: &[f64], rows: &[Row]) -> qp::Solution {
    let h = inverse(b, g.len()).unwrap();
    Qp {
        inverse: &h,
        gradient: g,
        lower,
        upper,
        rows,
    }
    .solve()
    .unwrap()
}

fn close(a: &[f64], b: &[f64], tol: f64) {
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(b) {
        assert!((x - y).abs() <= tol, "{a:?} against {b:?}");
    }
}

#[test]
fn unconstrained_minimum_is_minus_b_inverse_g() {
    // B = [[4, 1], [1, 3]], g = (1, 2): B^-1 g = (1/11, 7/11).
    let b = [4.0, 1.0, 1.0, 3.0];
    let inf = [f64::INFINITY; 2];
    let s = solve(&b, &[1.0, 2.0], &[-10.0; 2], &inf, &[]);
    close(&s.d, &[-1.0 / 11.0, -7.0 / 11.0], 1e-15);
}

/// quadprog's documented example: `min -(0, 5, 0)^T x + 1/2 x^T x` with `A^T x >= b0`,
/// `A = [[-4, -3, 0], [2, 1, 0], [0, -2, 1]]` (columns), `b0 = (-8, 2, 0)`: solution
/// `(0.4761905, 1.0476190, 2.0952381)`, multipliers `(0, 0.2380952, 2.0952381)`.
#[test]
fn quadprog_example_with_two_active_rows() {
    let columns = [[-4.0, -3.0, 0.0], [2.0, 1.0, 0.0], [0.0, -2.0, 1.0]];
    let b0 = [-8.0, 2.0, 0.0];
    let rows: Vec<Row> = columns
        .iter()
        .zip(b0)
        .map(|(c, b)| Row {
            a: c.iter().enumerate().map(|(i, v)| (i, -v)).collect(),
            b: -b,
        })
        .collect();
    let inf = [f64::INFINITY; 3];
    let s = solve(&identity(3), &[0.0, -5.0, 0.0], &[-inf[0]; 3], &inf, &rows);
    close(&s.d, &[10.0 / 21.0, 22.0 / 21.0, 44.0 / 21.0], 1e-14);
    close(&s.multipliers, &[0.0, 5.0 / 21.0, 44.0 / 21.0], 1e-14);
}

#[test]
fn bounds_become_active() {
    // min (x - 2)^2 + (y + 1)^2 within [0, 1]^2: (1, 0).
    let s = solve(&identity(2), &[-2.0, 1.0], &[0.0; 2], &[1.0; 2], &[]);
    close(&s.d, &[1.0, 0.0], 1e-15);
}

#[test]
fn incompatible_constraints_are_infeasible() {
    let rows = [Row {
        a: vec![(0, 1.0), (1, 1.0)],
        b: -1.0,
    }];
    let qp = Qp {
        inverse: &identity(2),
        gradient: &[0.0, 0.0],
        lower: &[0.0; 2],
        upper: &[1.0; 2],
        rows: &rows,
    };
    assert_eq!(qp.solve(), Err(QpError::Infeasible));
}

/// A random strictly convex QP with bounds and sparse rows, feasible at 0.
struct RandomQp {
    b: Vec<f64>,
    g: Vec<f64>,
    lower: Vec<f64>,
    upper: Vec<f64>,
    rows: Vec<Row>,
}

fn random_qp(rng: &mut ChaCha8Rng) -> RandomQp {
    let n = rng.random_range(2..14);
    let m: Vec<f64> = (0..n * n).map(|_| rng.random_range(-1.0..1.0)).collect();
    let mut b = identity(n);
    for i in 0..n {
        for j in 0..n {
            b[i + n * j] += (0..n).map(|k| m[i + n * k] * m[j + n * k]).sum::<f64>();
        }
    }
    let g: Vec<f64> = (0..n).map(|_| rng.random_range(-5.0..5.0)).collect();
    let lower: Vec<f64> = (0..n).map(|_| rng.random_range(-1.0..0.0)).collect();
    let upper: Vec<f64> = (0..n).map(|_| rng.random_range(0.0..1.0)).collect();
    let rows: Vec<Row> = (0..rng.random_range(0..2 * n))
        .map(|_| Row {
            a: (0..3)
                .map(|_| (rng.random_range(0..n), rng.random_range(-1.0..1.0)))
                .collect(),
            b: rng.random_range(0.0..0.5),
        })
        .collect();
    RandomQp {
        b,
        g,
        lower,
        upper,
        rows,
    }
}

/// Random strictly convex QPs with bounds and sparse rows (feasible at 0): the solution satisfies
/// the KKT conditions, `B d + g + sum lambda_j a_j` non-negative at a lower bound, non-positive at
/// an upper one and zero between, with complementary slackness and `lambda >= 0`.
#[test]
fn random_problems_satisfy_the_kkt_conditions() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for _ in 0..200 {
        let RandomQp {
            b,
            g,
            lower,
            upper,
            rows,
        } = random_qp(&mut rng);
        let n = g.len();
        let s = solve(&b, &g, &lower, &upper, &rows);
        let mut r: Vec<f64> = (0..n)
            .map(|i| g[i] + (0..n).map(|k| b[i + n * k] * s.d[k]).sum::<f64>())
            .collect();
        for (row, &l) in rows.iter().zip(&s.multipliers) {
            assert!(l >= 0.0);
            let ad: f64 = row.a.iter().map(|&(i, a)| a * s.d[i]).sum();
            assert!(ad <= row.b + 1e-10, "row violated by {}", ad - row.b);
            assert!(
                l * (row.b - ad) <= 1e-9,
                "complementarity {}",
                l * (row.b - ad)
            );
            row.a.iter().for_each(|&(i, a)| r[i] += l * a);
        }
        for i in 0..n {
            assert!(s.d[i] >= lower[i] - 1e-12 && s.d[i] <= upper[i] + 1e-12);
            let at_lower = s.d[i] <= lower[i] + 1e-12;
            let at_upper = s.d[i] >= upper[i] - 1e-12;
            match (at_lower, at_upper) {
                (true, _) => assert!(r[i] >= -1e-9, "{}", r[i]),
                (_, true) => assert!(r[i] <= 1e-9, "{}", r[i]),
                _ => assert!(r[i].abs() <= 1e-9, "stationarity {}", r[i]),
            }
        }
    }
}

/// The damped BFGS pair against the textbook update of the matrix itself, over more steps than
/// its re-inversion interval: `B` equals it and `H` stays its inverse (`H B = I`).
#[test]
fn bfgs_pair_is_the_bfgs_update_and_keeps_its_inverse() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let n = 9;
    let mut pair = Hessian::identity(n);
    let mut b = identity(n);
    for step in 0..150 {
        let s: Vec<f64> = (0..n).map(|_| rng.random_range(-1.0..1.0)).collect();
        // Curvature from a fixed positive definite matrix, sometimes negative (damped).
        let mut y: Vec<f64> = (0..n)
            .map(|i| (1.0 + i as f64) * s[i] + 0.3 * s[(i + 1) % n])
            .collect();
        if step % 7 == 3 {
            y.iter_mut().for_each(|v| *v = -*v);
        }
        textbook(&mut b, &s, &y, step == 0);
        pair.update(&s, &y);
        let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (x, y) in pair.matrix().iter().zip(&b) {
            assert!(
                (x - y).abs() <= 1e-9 * scale,
                "step {step}: {x} against {y}"
            );
        }
        let h = pair.inverse();
        for p in 0..n {
            for q in 0..n {
                let hb: f64 = (0..n).map(|k| h[p + n * k] * b[k + n * q]).sum();
                let expected = if p == q { 1.0 } else { 0.0 };
                assert!(
                    (hb - expected).abs() < 1e-8,
                    "step {step}: (H B)_{p}{q} = {hb}"
                );
            }
        }
    }
}

/// Powell's damped BFGS update of the explicit matrix `b` (the first scaled).
fn textbook(b: &mut [f64], s: &[f64], y: &[f64], first: bool) {
    let n = s.len();
    let sy0: f64 = s.iter().zip(y).map(|(a, b)| a * b).sum();
    if first && sy0 > 0.0 {
        let scale = y.iter().map(|v| v * v).sum::<f64>() / sy0;
        b.fill(0.0);
        (0..n).for_each(|k| b[k + n * k] = scale);
    }
    let bs: Vec<f64> = (0..n)
        .map(|i| (0..n).map(|k| b[i + n * k] * s[k]).sum())
        .collect();
    let sbs: f64 = s.iter().zip(&bs).map(|(a, b)| a * b).sum();
    let mut y = y.to_vec();
    if sy0 < 0.2 * sbs {
        let theta = 0.8 * sbs / (sbs - sy0);
        y.iter_mut()
            .zip(&bs)
            .for_each(|(y, b)| *y = theta * *y + (1.0 - theta) * b);
    }
    let sy: f64 = s.iter().zip(&y).map(|(a, b)| a * b).sum();
    for k in 0..n {
        for i in 0..n {
            b[i + n * k] += y[i] * y[k] / sy - bs[i] * bs[k] / sbs;
        }
    }
}

/// A smooth two-variable problem for the SQP, counting its evaluations against a budget.
struct Small<F, C> {
    f: F,
    c: C,
    lower: [f64; 2],
    upper: [f64; 2],
    evaluations: Cell<usize>,
    budget: usize,
}

impl<F, C> Nlp for Small<F, C>
where
    F: Fn(&[f64]) -> (f64, [f64; 2]),
    C: Fn(&[f64]) -> Vec<(f64, [f64; 2])>,
{
    fn bounds(&self) -> (&[f64], &[f64]) {
        (&self.lower, &self.upper)
    }
    fn values(&self, x: &[f64]) -> Values {
        self.evaluations.set(self.evaluations.get() + 1);
        Values {
            f: (self.f)(x).0,
            c: (self.c)(x).iter().map(|c| c.0).collect(),
        }
    }
    fn gradients(&self, x: &[f64], _: &Values) -> Gradients {
        Gradients {
            f: (self.f)(x).1.to_vec(),
            c: (self.c)(x)
                .iter()
                .map(|c| vec![(0, c.1[0]), (1, c.1[1])])
                .collect(),
        }
    }
    fn can_evaluate(&self) -> bool {
        self.evaluations.get() < self.budget
    }
}

const TIGHT: Tolerances = Tolerances {
    ftol: 1e-14,
    xtol: 1e-12,
};

/// Rosenbrock's function within the unit disc (MATLAB's `fmincon` example): minimum at
/// (0.786415, 0.617698), the disc active, from an infeasible start outside it.
#[test]
fn rosenbrock_in_the_unit_disc_from_an_infeasible_start() {
    let problem = Small {
        f: |x: &[f64]| {
            let (a, b) = (1.0 - x[0], x[1] - x[0] * x[0]);
            let f = a * a + 100.0 * b * b;
            (f, [-2.0 * a - 400.0 * x[0] * b, 200.0 * b])
        },
        c: |x: &[f64]| vec![(x[0] * x[0] + x[1] * x[1] - 1.0, [2.0 * x[0], 2.0 * x[1]])],
        lower: [-2.0; 2],
        upper: [2.0; 2],
        evaluations: Cell::new(0),
        budget: 500,
    };
    let x0 = [1.5, -1.5];
    let x = run(&problem, &x0);
    close(&x, &[0.786415, 0.617698], 2e-6);
    // KKT: grad f + lambda grad c = 0 with lambda > 0.
    let (_, g) = (problem.f)(&x);
    let lambda = -g[0] / (2.0 * x[0]);
    assert!(lambda > 0.0);
    assert!((g[1] + lambda * 2.0 * x[1]).abs() < 1e-5);
}

/// The budget is tested where a step needs an evaluation, after the stops that need none: on
/// Rosenbrock's problem in the unit disc, a budget of exactly the evaluations the converged run
/// spent ends converged too (its last stop and the confirmation from `B = I` are the QP's
/// predicted change, no evaluation), where a budget test at the start of every step said
/// `evaluation-limit`.
#[test]
fn a_stop_cut_short_by_the_budget_is_still_a_stop() {
    let problem = |budget| Small {
        f: |x: &[f64]| {
            let (a, b) = (1.0 - x[0], x[1] - x[0] * x[0]);
            (
                a * a + 100.0 * b * b,
                [-2.0 * a - 400.0 * x[0] * b, 200.0 * b],
            )
        },
        c: |x: &[f64]| vec![(x[0] * x[0] + x[1] * x[1] - 1.0, [2.0 * x[0], 2.0 * x[1]])],
        lower: [-2.0; 2],
        upper: [2.0; 2],
        evaluations: Cell::new(0),
        budget,
    };
    let full = problem(500);
    assert!(minimise(&full, &[1.5, -1.5], TIGHT).is_converged());
    let spent = full.evaluations.get();
    let exact = problem(spent);
    let stop = minimise(&exact, &[1.5, -1.5], TIGHT);
    assert_eq!(stop, Termination::Converged, "budget {spent}");
    assert_eq!(exact.evaluations.get(), spent);
}

/// A linear objective over the unit disc and a box: `min x + y` at `(-1/sqrt 2, -1/sqrt 2)`; with
/// the box `x >= -0.5` the bound is active too, at `(-0.5, -sqrt 0.75)`.
#[test]
fn active_constraint_and_active_bound() {
    for (lower, expected) in [
        (-2.0, [-0.5f64.sqrt(), -0.5f64.sqrt()]),
        (-0.5, [-0.5, -0.75f64.sqrt()]),
    ] {
        let problem = Small {
            f: |x: &[f64]| (x[0] + x[1], [1.0, 1.0]),
            c: |x: &[f64]| vec![(x[0] * x[0] + x[1] * x[1] - 1.0, [2.0 * x[0], 2.0 * x[1]])],
            lower: [lower, -2.0],
            upper: [2.0; 2],
            evaluations: Cell::new(0),
            budget: 500,
        };
        let x = run(&problem, &[0.3, 0.2]);
        close(&x, &expected, 1e-7);
    }
}

/// Runs the SQP, checks it converged within the budget and returns the last point it evaluated
/// that is feasible and lowest.
fn run<F, C>(problem: &Small<F, C>, x0: &[f64]) -> Vec<f64>
where
    F: Fn(&[f64]) -> (f64, [f64; 2]),
    C: Fn(&[f64]) -> Vec<(f64, [f64; 2])>,
{
    let best = std::cell::RefCell::new(None::<(f64, Vec<f64>)>);
    let recording = Recording {
        inner: problem,
        best: &best,
    };
    let stop = minimise(&recording, x0, TIGHT);
    assert!(stop.is_converged(), "{stop}");
    let first = best.borrow().clone().unwrap().1;
    // The same problem gives the same bits.
    problem.evaluations.set(0);
    let again = std::cell::RefCell::new(None);
    let repeat = Recording {
        inner: problem,
        best: &again,
    };
    assert_eq!(minimise(&repeat, x0, TIGHT), stop);
    assert_eq!(again.borrow().clone().unwrap().1, first);
    first
}

/// A problem that keeps its best feasible point.
struct Recording<'a, P> {
    inner: &'a P,
    best: &'a std::cell::RefCell<Option<(f64, Vec<f64>)>>,
}

impl<P: Nlp> Nlp for Recording<'_, P> {
    fn bounds(&self) -> (&[f64], &[f64]) {
        self.inner.bounds()
    }
    fn values(&self, x: &[f64]) -> Values {
        let v = self.inner.values(x);
        let feasible = v.c.iter().all(|&c| c <= 1e-12);
        let better = self.best.borrow().as_ref().is_none_or(|(f, _)| v.f < *f);
        if feasible && better {
            *self.best.borrow_mut() = Some((v.f, x.to_vec()));
        }
        v
    }
    fn gradients(&self, x: &[f64], values: &Values) -> Gradients {
        self.inner.gradients(x, values)
    }
    fn can_evaluate(&self) -> bool {
        self.inner.can_evaluate()
    }
}

/// A QP started from an active set (its own, or that of a QP with another gradient) ends at the
/// same minimiser and multipliers as from nothing (the QP is strictly convex); from its own, with
/// no active-set change at all, where the cold start needed some.
#[test]
fn warm_starts_end_at_the_cold_solution() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let mut changed = 0;
    for _ in 0..200 {
        let RandomQp {
            b,
            g,
            lower,
            upper,
            rows,
        } = random_qp(&mut rng);
        let h = inverse(&b, g.len()).unwrap();
        let qp = |g: &[f64]| {
            Qp {
                inverse: &h,
                gradient: g,
                lower: &lower,
                upper: &upper,
                rows: &rows,
            }
            .solve()
            .unwrap()
        };
        let cold = qp(&g);
        let shifted: Vec<f64> = g.iter().map(|v| v + rng.random_range(-1.0..1.0)).collect();
        let other = qp(&shifted).active;
        let warm = |active: &qp::Active| {
            Qp {
                inverse: &h,
                gradient: &g,
                lower: &lower,
                upper: &upper,
                rows: &rows,
            }
            .solve_from(active)
            .unwrap()
        };
        let own = warm(&cold.active);
        for s in [&own, &warm(&other)] {
            close(&s.d, &cold.d, 1e-10);
            close(&s.multipliers, &cold.multipliers, 1e-8);
        }
        assert_eq!(own.changes, 0, "cold: {} changes", cold.changes);
        changed += (cold.changes > 0) as usize;
    }
    assert!(
        changed > 100,
        "{changed} of 200 cold starts changed the active set"
    );
}
