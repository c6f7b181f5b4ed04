//! Choosing the best group from a pool of candidate postures: postures the user already knows are
//! reachable (taught on the pendant, seen by the tracker).
//!
//! The group of `n` pool postures that minimises a design criterion is found
//! - exactly, by enumerating every group, when there are at most
//!   [`PoolOptions::enumeration_limit`] of them (`C(pool, n)`, default 100 000);
//! - otherwise by the modified Fedorov exchange algorithm (Cook & Nachtsheim 1980, Technometrics
//!   22(3)): from a seeded random group, each posture of the group in turn is exchanged for the
//!   pool posture that lowers the criterion most, until a whole pass exchanges none; from
//!   [`PoolOptions::restarts`] seeded groups, the best kept (`design::exchange`).
//!
//! Updates: the information matrix of a group is `S^T S = sum_i M_i` (6 x 6, `S` the scaled
//! observation matrix of [`super::criteria`]) with `M_i = S_i^T S_i` of each pool posture, its
//! `3p x 6` block (rank <= min(3p, 6)), computed once. An exchange is the rank-`<= 6` update
//! `S^T S - M_i + M_j`, refactored by a 6 x 6 Cholesky (whose factor is the group's triangular
//! factor `R_s` up to row signs, so every criterion is computed by the same code as
//! [`super::Evaluator`]); that is cheaper than a Woodbury update, which needs a `3p x 3p` solve
//! per candidate. The chosen group's value is then recomputed from its observation matrix by QR
//! ([`super::Evaluator::value`]).
//!
//! Limits: at most [`MAX_POOL`] pool postures; groups of 2 to 60 postures.

use super::evaluator::Information;
use super::exchange::{self, PoolMethod, PoolOptions};
use super::search::check_count;
use super::{Criterion, Evaluator};
use nalgebra::Vector6;
use stiffid_core::setup::Setup;
use stiffid_core::{Error, Result};

/// Most postures in a pool (each costs one forward kinematics and a 6 x 6 matrix; an exchange
/// pass costs `n x pool` Cholesky factorisations).
pub const MAX_POOL: usize = 10_000;

/// Most postures in a group chosen from a pool.
pub(crate) const MAX_GROUP: usize = 60;

/// The group chosen from a pool.
#[derive(Debug, Clone, PartialEq)]
pub struct PoolChoice {
    /// The chosen postures, as indices into the pool given to [`Pool::new`], ascending.
    pub indices: Vec<usize>,
    /// The criterion of the group, computed from its observation matrix by QR
    /// ([`Evaluator::value`]).
    pub value: f64,
    /// Enumeration or exchange.
    pub method: PoolMethod,
    /// Groups evaluated (by their information matrix).
    pub evaluations: usize,
}

/// A pool of candidate postures of one setup, with each usable posture's information matrix.
#[derive(Debug, Clone)]
pub struct Pool<'a> {
    evaluator: Evaluator<'a>,
    postures: Vec<Vector6<f64>>,
    /// Pool indices of the usable postures, ascending.
    usable: Vec<usize>,
    /// `M_i = S_i^T S_i` of each usable posture.
    information: Vec<Information>,
    /// TCP dexterity `k(J_N)` of each usable posture (for the classical index).
    dexterity: Vec<f64>,
}

impl<'a> Pool<'a> {
    /// A pool of `postures` (axis angles, rad) of `setup`; `usable[i]` false skips posture i (an
    /// infeasible posture: see the setup's cell checks). `usable` empty means every posture.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (field `pool`) for more than [`MAX_POOL`] postures, or a `usable`
    /// mask of another length than the pool.
    pub fn new(setup: &'a Setup, postures: &[Vector6<f64>], usable: &[bool]) -> Result<Self> {
        if postures.len() > MAX_POOL {
            return Err(pool_error(format!(
                "{} postures: at most {MAX_POOL} are allowed",
                postures.len()
            )));
        }
        if !usable.is_empty() && usable.len() != postures.len() {
            return Err(pool_error(format!(
                "{} usability flags for {} postures",
                usable.len(),
                postures.len()
            )));
        }
        let evaluator = Evaluator::new(setup);
        let usable: Vec<usize> = (0..postures.len())
            .filter(|&i| usable.get(i).copied().unwrap_or(true))
            .collect();
        let (information, dexterity) = usable
            .iter()
            .map(|&i| {
                let terms = evaluator.posture(&postures[i]);
                (evaluator.information(&terms), evaluator.dexterity(&terms))
            })
            .unzip();
        Ok(Self {
            evaluator,
            postures: postures.to_vec(),
            usable,
            information,
            dexterity,
        })
    }

    /// Pool indices of the usable postures, ascending.
    pub fn usable(&self) -> &[usize] {
        &self.usable
    }

    /// The postures of pool indices (axis angles, rad).
    pub fn postures(&self, indices: &[usize]) -> Vec<Vector6<f64>> {
        indices.iter().map(|&i| self.postures[i]).collect()
    }

    /// The group of `n` usable pool postures that minimises `criterion` (see the module docs for
    /// how). The same options give the same group whatever the thread count.
    ///
    /// # Errors
    /// [`Error::InvalidField`]: `options` outside their limits; `n` below 2, above 60 or above the
    /// usable postures; the `test-pose` criterion without test postures; no group of `n` usable
    /// postures that identifies all six compliances (field `pool`). [`Error::MissingField`] for a
    /// criterion the setup lacks a field for ([`Criterion::check`]).
    pub fn best(
        &self,
        criterion: Criterion,
        n: usize,
        options: &PoolOptions,
    ) -> Result<PoolChoice> {
        let goal = super::search::Goal::stiffness(criterion);
        let value = |group: &[usize]| self.value(criterion, group);
        let full = |postures: &[Vector6<f64>]| self.evaluator.value(criterion, postures);
        self.choose(
            &goal,
            n,
            options,
            &value,
            &full,
            "identifies all six compliances",
        )
    }

    /// The best group of `n` usable postures for `goal` ([`super::Goal`]): [`Pool::best`] for a
    /// stiffness criterion alone; with a calibration part, the same enumeration or exchange on
    /// the goal's value of each group ([`super::Goal::value`], from the postures).
    ///
    /// # Errors
    /// Those of [`Pool::best`]; (field `pool`) no group of `n` usable postures with a finite
    /// value.
    pub(crate) fn best_for(
        &self,
        goal: &super::Goal,
        n: usize,
        options: &PoolOptions,
    ) -> Result<PoolChoice> {
        if goal.calibration.is_none() {
            return self.best(goal.stiffness, n, options);
        }
        let of = |group: &[usize]| -> Vec<Vector6<f64>> {
            group
                .iter()
                .map(|&k| self.postures[self.usable[k]])
                .collect()
        };
        let value = |group: &[usize]| goal.value(&self.evaluator, &of(group));
        let full = |postures: &[Vector6<f64>]| goal.value(&self.evaluator, postures);
        self.choose(goal, n, options, &value, &full, "has a finite value")
    }

    /// The group of `n` usable postures that minimises `value` (of positions in
    /// [`Pool::usable`]), by enumeration or exchange, as pool indices in ascending order with
    /// `full`'s value of its postures; `failure` says what no group achieved when that value is
    /// not finite.
    fn choose(
        &self,
        goal: &super::Goal,
        n: usize,
        options: &PoolOptions,
        value: &(dyn Fn(&[usize]) -> f64 + Sync),
        full: &dyn Fn(&[Vector6<f64>]) -> f64,
        failure: &str,
    ) -> Result<PoolChoice> {
        options.validate()?;
        check_count(self.evaluator.setup(), goal, n)?;
        if n > MAX_GROUP.min(self.usable.len()) {
            return Err(Error::InvalidField {
                field: "postures".into(),
                message: format!(
                    "{n} given: expected at most {MAX_GROUP} and at most the {} usable pool postures",
                    self.usable.len()
                ),
            });
        }
        let chosen = exchange::best(self.usable.len(), n, options, value);
        let mut indices: Vec<usize> = chosen.group.iter().map(|&k| self.usable[k]).collect();
        indices.sort_unstable();
        let value = full(&self.postures(&indices));
        if !value.is_finite() {
            return Err(pool_error(format!(
                "no group of {n} of the {} usable postures {failure}",
                self.usable.len()
            )));
        }
        Ok(PoolChoice {
            indices,
            value,
            method: chosen.method,
            evaluations: chosen.evaluations,
        })
    }

    /// The criterion of a group of usable postures (positions in [`Pool::usable`]) from its
    /// information matrix.
    pub(crate) fn value(&self, criterion: Criterion, group: &[usize]) -> f64 {
        let Some(information) = Information::sum(group.iter().map(|&k| &self.information[k]))
        else {
            return f64::INFINITY;
        };
        let classical = group.iter().map(|&k| self.dexterity[k]).fold(0.0, f64::max);
        self.evaluator
            .value_from_information(criterion, &information, classical)
    }
}

fn pool_error(message: String) -> Error {
    Error::InvalidField {
        field: "pool".into(),
        message,
    }
}
