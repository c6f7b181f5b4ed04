//! The problem's derivatives and constraints as the SQP asks for them ([`Nlp`]): forward
//! differences where the gradient is not exact, the constraints of every posture.

use super::super::PENALTY;
use super::{log_value, posture, postures, PostureConstraints, Problem};
use crate::evaluator::PostureTerms;
use crate::search::constraints::{inequalities, inequalities_and_gradients, CellConstraints};
use crate::search::local::evals_per_step;
use crate::search::sqp::{Gradients, Nlp, SparseRows, Values};
use crate::search::Gradient;
use nalgebra::Vector6;

impl Problem<'_> {
    /// The forward-difference gradient of `ln(criterion)` at `x`, where it is `f`. A probe changes
    /// one posture, so the other postures' terms are reused.
    pub(super) fn fd_objective_gradient(&self, x: &[f64], f: f64) -> Vec<f64> {
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
    pub(super) fn fd_gradient(
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
    pub(super) fn constraint_values(&self, x: &[f64]) -> Vec<f64> {
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
    pub(super) fn constraint_rows(&self, x: &[f64]) -> SparseRows {
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
    pub(super) fn posture_constraints<R>(
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
    pub(super) fn constraints_at(&self, i: usize, q: &Vector6<f64>) -> PostureConstraints {
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
