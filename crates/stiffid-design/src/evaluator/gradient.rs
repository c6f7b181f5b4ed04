//! Exact gradients of the design criteria with respect to the axis angles of every posture.
//!
//! Every criterion F is differentiated as `ln F`, in reverse mode: first the derivative of `ln F`
//! with respect to the observation matrix, `d ln F = <Psi Y, dPsi>` with a symmetric 6x6 `Y` from
//! the triangular factor (`M = Psi^T Psi = R^T R`, `S = Psi D`, `D = diag(h) / sigma`,
//! `C = (S^T S)^-1 = R_s^-1 R_s^-T`):
//!
//! - `d-optimal`, `ln F = -(1/12) ln det M + const`, `d ln det M = tr(M^-1 dM) = 2 <Psi M^-1, dPsi>`:
//!   `Y = -M^-1 / 6`;
//! - `relative-a`, `ln F = (1/2) ln tr C + const`, `d tr C = -tr(C d(S^T S) C) = -2 <Psi D C^2 D, dPsi>`:
//!   `Y = -D C^2 D / tr C`;
//! - `test-pose`, `ln F = (1/2) ln tr(B M^-1) + const` with `B = A^T A` of the test rows A,
//!   `d tr(B M^-1) = -tr(M^-1 B M^-1 dM)`: `Y = -M^-1 B M^-1 / tr(B M^-1)`, computed from
//!   `Z = R_A R^-1` (`B = R_A^T R_A`): `tr(B M^-1) = |Z|_F^2`, `M^-1 B M^-1 = X^T X`, `X = Z R^-T`;
//! - `cond_2` of `Psi D` (`D = I` for `zhang2021`, `diag(h) / sigma` for `scaled-cond`): a simple
//!   singular value s with right singular vector v moves by `ds = u^T dPsi D v`, `u = Psi D v / s`,
//!   so `d ln cond = d ln s_max - d ln s_min` gives `Y = D (v_max v_max^T / s_max^2 - v_min v_min^T / s_min^2) D`
//!   (v from the Jacobi rotations of `R` or `R_s`).
//!
//! Each posture's block `B_i` of `Psi` then carries the weight `B_i Y`, and
//! [`stiffid_core::observation::rope_block_gradient`] takes it through the Jacobians and the rope wrench to
//! the six axis angles of the posture; with virtual springs (`n > 6` parameters, `Y` is `n x n`
//! and `d-optimal`'s is `-M^-1 / n`), their columns of the weight reach the axis angles through
//! `springs::spring_gradient`. The `classical` index (a maximum over the postures) adds
//! `d ln k(J_N)` of the active posture (the first with the largest dexterity) through
//! [`stiffid_core::robot::kinematics::dexterity_log_gradient`]; it is smooth except where two postures tie, and
//! `cond_2` except where its extreme singular values are repeated.

use super::wide::{self, WideGroup};
use super::{springs, Evaluator, Factored, Group, PostureTerms};

/// A maximum-type criterion split for an epigraph search ([`Evaluator::max_split`]).
#[derive(Debug, Clone)]
pub(crate) struct MaxSplit {
    /// The criterion.
    pub value: f64,
    /// `ln rest` and its gradient (per rad), one vector per posture.
    pub rest: (f64, Vec<Vector6<f64>>),
    /// Each posture's `ln k(J_N)` and its gradient in the posture's six angles (per rad).
    pub dexterities: Vec<(f64, Vector6<f64>)>,
}
use crate::criteria::PLACEHOLDER_LENGTH;
use crate::Criterion;
use nalgebra::{DMatrix, Matrix6, MatrixXx6, Vector3, Vector6};
use stiffid_core::math::jacobi::singular_values_and_vectors;
use stiffid_core::math::linalg::times_6x6;
use stiffid_core::observation::{posture_block, rope_block_gradient};
use stiffid_core::robot::kinematics::dexterity_log_gradient;

impl Evaluator<'_> {
    /// The value of `criterion` for `postures` (axis angles, rad), as [`Evaluator::value`], and its
    /// gradient with respect to the six axis angles of each posture (criterion units per rad, one
    /// vector per posture). Exact (closed form, see the module source), at about the cost of 3-5
    /// evaluations; zeros when the value is `+infinity` (no gradient exists).
    pub fn value_and_gradient(
        &self,
        criterion: Criterion,
        postures: &[Vector6<f64>],
    ) -> (f64, Vec<Vector6<f64>>) {
        let terms: Vec<PostureTerms> = postures.iter().map(|q| self.posture(q)).collect();
        let refs: Vec<&PostureTerms> = terms.iter().collect();
        let (value, mut gradient) = self.value_and_log_gradient(criterion, &refs);
        if value.is_finite() {
            gradient.iter_mut().for_each(|g| *g *= value);
        }
        (value, gradient)
    }

    /// The value of `criterion` for the postures' terms and the gradient of its logarithm
    /// (per rad); zeros when the value is `+infinity`.
    pub(crate) fn value_and_log_gradient(
        &self,
        criterion: Criterion,
        terms: &[&PostureTerms],
    ) -> (f64, Vec<Vector6<f64>>) {
        let zeros = || vec![Vector6::zeros(); terms.len()];
        let mut gradient = zeros();
        let group = match criterion {
            Criterion::Classical => None,
            _ => match self.group(terms) {
                Some(group) => Some(group),
                None => return (f64::INFINITY, zeros()),
            },
        };
        let value = match &group {
            Some(group) => self.score(criterion, group, || self.classical(terms)),
            None => self.classical(terms),
        };
        if !value.is_finite() {
            return (value, zeros());
        }
        if matches!(criterion, Criterion::Classical | Criterion::Zhang2021) {
            let dexterity = |t: &PostureTerms| self.classical(&[t]);
            let mut active = 0;
            for (i, t) in terms.iter().enumerate() {
                if dexterity(t) > dexterity(terms[active]) {
                    active = i;
                }
            }
            gradient[active] += self.dexterity_log_gradient(terms[active]);
        }
        if let Some(group) = group {
            self.add_psi_log_gradient(criterion, &group, terms, &mut gradient);
        }
        (value, gradient)
    }

    /// A criterion that is a maximum over the postures ([`Criterion::Classical`],
    /// [`Criterion::Zhang2021`]) split for a search that keeps the maximum as constraints (an
    /// epigraph): `F = max_i k(J_N)_i * rest`, with `rest = cond_2(Psi)` for `zhang2021` and 1 for
    /// `classical`. `None` for the other criteria and where `F` is not finite.
    pub(crate) fn max_split(
        &self,
        criterion: Criterion,
        terms: &[&PostureTerms],
    ) -> Option<MaxSplit> {
        let mut rest = vec![Vector6::zeros(); terms.len()];
        let (value, ln_rest) = match criterion {
            Criterion::Classical => (self.classical(terms), 0.0),
            Criterion::Zhang2021 => {
                let group = self.group(terms)?;
                let cond = group.cond_psi();
                self.add_psi_log_gradient(criterion, &group, terms, &mut rest);
                (self.classical(terms) * cond, cond.ln())
            }
            _ => return None,
        };
        let dexterities = terms
            .iter()
            .map(|t| (self.dexterity(t).ln(), self.dexterity_log_gradient(t)))
            .collect::<Vec<_>>();
        let finite = dexterities.iter().all(|(d, _)| d.is_finite());
        (value.is_finite() && ln_rest.is_finite() && finite).then_some(MaxSplit {
            value,
            rest: (ln_rest, rest),
            dexterities,
        })
    }

    /// Adds `d ln F` through `Psi` (`<Psi Y, dPsi>`, module docs) of a full-rank group to each
    /// posture's gradient.
    fn add_psi_log_gradient(
        &self,
        criterion: Criterion,
        group: &Factored,
        terms: &[&PostureTerms],
        gradient: &mut [Vector6<f64>],
    ) {
        match group {
            Factored::Six(group) => {
                if let Some(y) = self.psi_weight(criterion, group) {
                    for (t, g) in terms.iter().zip(gradient.iter_mut()) {
                        let block = posture_block(
                            self.setup.arm(),
                            &t.frames,
                            &self.setup.rope_wrench(&t.frames),
                        );
                        let weight =
                            MatrixXx6::from_vec(times_6x6(block.as_slice(), block.nrows(), &y));
                        *g += rope_block_gradient(self.setup, &t.frames, &weight);
                    }
                }
            }
            Factored::Wide(group) => {
                if let Some(y) = self.wide_psi_weight(criterion, group) {
                    for (t, g) in terms.iter().zip(gradient.iter_mut()) {
                        *g += self.wide_block_gradient(&t.frames, &y);
                    }
                }
            }
        }
    }

    /// The gradient of `<B Y, dB>` for the `3p x n` block B of the posture `frames`: the drive
    /// columns through [`rope_block_gradient`], the virtual springs' through
    /// [`springs::spring_gradient`].
    fn wide_block_gradient(&self, frames: &stiffid_core::Frames, y: &DMatrix<f64>) -> Vector6<f64> {
        let block = posture_block(self.setup.arm(), frames, &self.setup.rope_wrench(frames));
        let weight = wide::product(&block, y);
        let drives = MatrixXx6::from_column_slice(&weight.as_slice()[..6 * weight.nrows()]);
        rope_block_gradient(self.setup, frames, &drives)
            + springs::spring_gradient(self.setup, frames, |s, m| {
                Vector3::from(weight.fixed_view::<3, 1>(3 * m, 6 + s))
            })
    }

    /// [`Evaluator::psi_weight`] over the `n` parameters of a model with virtual springs.
    fn wide_psi_weight(&self, criterion: Criterion, group: &WideGroup) -> Option<DMatrix<f64>> {
        let d = &self.wide.as_ref()?.scaling;
        let scaled = |mut y: DMatrix<f64>| {
            for i in 0..y.nrows() {
                for j in 0..y.ncols() {
                    y[(i, j)] *= d[i] * d[j];
                }
            }
            y
        };
        let n = group.n() as f64;
        Some(match criterion {
            Criterion::Classical => return None,
            Criterion::Zhang2021 => wide::cond_weight(&group.r),
            Criterion::ScaledCond => scaled(wide::cond_weight(&group.rs)),
            Criterion::DOptimal => wide::product(&group.r_inv, &group.r_inv.transpose()) / -n,
            Criterion::RelativeA => {
                let c = wide::product(&group.rs_inv, &group.rs_inv.transpose());
                let trace = c.trace();
                scaled(wide::product(&c, &c)) / -trace
            }
            Criterion::TestPose => {
                let z = self.wide_test_weight(group);
                let trace = z.norm_squared();
                if trace <= 0.0 {
                    return None;
                }
                let x = wide::product(&z, &group.r_inv.transpose());
                wide::product(&x.transpose(), &x) / -trace
            }
        })
    }

    /// `d ln k(J_N)` of one posture (zeros where the dexterity has no gradient).
    fn dexterity_log_gradient(&self, t: &PostureTerms) -> Vector6<f64> {
        let setup = self.setup;
        let jacobian = t.frames.jacobian(&setup.tool().tcp, setup.springs());
        let l = setup.characteristic_length().unwrap_or(PLACEHOLDER_LENGTH);
        match dexterity_log_gradient(&jacobian, l) {
            Some(w) => t.frames.jacobian_gradient(
                &setup.tool().tcp,
                setup.springs(),
                &w,
                &Default::default(),
            ),
            None => Vector6::zeros(),
        }
    }

    /// The `Y` of `d ln F = <Psi Y, dPsi>` (module docs); `None` for `classical`, which does not
    /// depend on `Psi`, and for `test-pose` without test postures (constant 0).
    fn psi_weight(&self, criterion: Criterion, group: &Group) -> Option<Matrix6<f64>> {
        let d = Matrix6::from_diagonal(&self.scaling);
        Some(match criterion {
            Criterion::Classical => return None,
            Criterion::Zhang2021 => cond_weight(&group.r),
            Criterion::ScaledCond => d * cond_weight(&group.rs) * d,
            Criterion::DOptimal => group.r_inv * group.r_inv.transpose() / -6.0,
            Criterion::RelativeA => {
                let c = group.rs_inv * group.rs_inv.transpose();
                -(d * c * c * d) / c.trace()
            }
            Criterion::TestPose => {
                let z = self.test_weight(group);
                let trace = z.norm_squared();
                if trace <= 0.0 {
                    return None;
                }
                let x = z * group.r_inv.transpose();
                -(x.transpose() * x) / trace
            }
        })
    }
}

/// `v_max v_max^T / s_max^2 - v_min v_min^T / s_min^2` of the 6x6 `r`: the `Y` of `d ln cond_2`.
fn cond_weight(r: &Matrix6<f64>) -> Matrix6<f64> {
    let (s, v) = singular_values_and_vectors(r);
    let (max, min) = (s.imax(), s.imin());
    let (v_max, v_min) = (v.column(max), v.column(min));
    v_max * v_max.transpose() / (s[max] * s[max]) - v_min * v_min.transpose() / (s[min] * s[min])
}
