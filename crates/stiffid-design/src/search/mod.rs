//! Posture search: the group of postures that minimises a design criterion within the setup's
//! bounds and the cell's feasibility checks ([`stiffid_core::cell`]).
//!
//! - [`local`]: SQP from a start group, as in Zhang et al. 2021, Section III-B step 5: SLSQP
//!   (Kraft 1988, through the `slsqp` crate: the counterpart of the MATLAB `fmincon` the paper
//!   uses; [`Solver::Slsqp`]) or our own ([`Solver::ActiveSet`]: a dense Goldfarb-Idnani QP per
//!   step, damped BFGS, an L1 merit line search; the maximum-type criteria in epigraph form), by
//!   default chosen per criterion ([`Solver::resolve`]);
//! - [`global`]: many local searches in parallel from seeded space-filling starts, the best kept
//!   (the paper's stated future work);
//! - [`random_group`]: a seeded Latin-hypercube start group;
//! - [`compass`]: a global search of a box for the least value of any function of a few
//!   variables that may be undefined (a grid, seeded samples, compass searches): the workpiece
//!   placement's search.
//!
//! The variables are the `6n` axis angles (rad) of the `n` postures, posture-major. Every point
//! evaluated is clamped into the bounds, so no search ever returns a posture outside them.

pub mod compass;
#[cfg(test)]
mod compass_tests;
mod constraints;
mod global;
mod local;
mod sample;
pub(crate) mod sqp;
mod termination;

pub use constraints::{cell_constraints, CellConstraints};
pub(crate) use constraints::{design_checker, design_margin};
pub use global::{global, global_for};
pub(super) use local::check_count;
pub use local::local;
pub(crate) use local::local_for;
pub use sample::random_group;
pub use termination::Termination;

use crate::observability::{CalibrationCriterion, CalibrationDesign};
use crate::{Criterion, Evaluator};
use nalgebra::Vector6;
use stiffid_core::{common::limits, Result};

/// What a search minimises: a stiffness criterion, a calibration criterion, or both.
///
/// With a calibration part of weight `w`, the objective is `c_s^(1-w) c_c^w` (`c_s` the stiffness
/// criterion, `c_c` the calibration criterion's loss, `CalibrationCriterion::loss`), so its
/// logarithm, what the SQP minimises, is the weighted sum `(1-w) ln c_s + w ln c_c` of the
/// log-criteria: each criterion's relative improvement counts with its weight, whatever their
/// units and scales (no normalisation constant changes the minimiser), and `w = 1` is the
/// calibration alone (the stiffness criterion is then not evaluated).
#[derive(Debug, Clone, Copy)]
pub struct Goal<'a> {
    /// The stiffness criterion.
    pub stiffness: Criterion,
    /// The calibration part, if any.
    pub calibration: Option<CalibrationGoal<'a>>,
}

/// The calibration part of a [`Goal`].
#[derive(Debug, Clone, Copy)]
pub struct CalibrationGoal<'a> {
    /// The design problem (error model, kept parameters, test postures, noise).
    pub design: &'a CalibrationDesign,
    /// The criterion.
    pub criterion: CalibrationCriterion,
    /// The weight `w` of its logarithm, in `(0, 1]` (1: the calibration alone).
    pub weight: f64,
}

impl<'a> Goal<'a> {
    /// The stiffness criterion alone.
    pub fn stiffness(criterion: Criterion) -> Self {
        Goal {
            stiffness: criterion,
            calibration: None,
        }
    }

    /// The weight of the stiffness criterion's logarithm: `1 - w`.
    pub(crate) fn stiffness_weight(&self) -> f64 {
        self.calibration.map_or(1.0, |c| 1.0 - c.weight)
    }

    /// Whether the stiffness criterion enters the objective.
    pub(crate) fn has_stiffness(&self) -> bool {
        self.stiffness_weight() > 0.0
    }

    /// The SQP a local search on the goal runs for the option `solver`: [`Solver::resolve`] of
    /// the stiffness criterion alone; with a calibration part, under [`Solver::Auto`], ours
    /// ([`Solver::ActiveSet`]) when every part is smooth (`o1`, `d-optimality`, `test-pose`, and a
    /// stiffness criterion ours serves) and SLSQP when one has kinks (`o3`, `o4`, `o5`: extreme
    /// singular values, a condition number or a maximum).
    pub fn solver(&self, solver: Solver) -> Solver {
        let Some(c) = self.calibration else {
            return solver.resolve(self.stiffness);
        };
        let smooth_calibration = matches!(
            c.criterion,
            CalibrationCriterion::O1
                | CalibrationCriterion::DOptimality
                | CalibrationCriterion::TestPose
        );
        let smooth_stiffness =
            !self.has_stiffness() || Solver::Auto.resolve(self.stiffness) == Solver::ActiveSet;
        match (solver, smooth_calibration && smooth_stiffness) {
            (Solver::Auto, true) => Solver::ActiveSet,
            (Solver::Auto, false) => Solver::Slsqp,
            (concrete, _) => concrete,
        }
    }

    /// The goal's value at `postures` (axis angles, rad), `evaluator` scoring the stiffness
    /// criterion: `+infinity` when a part is not positive and finite.
    pub(crate) fn value(&self, evaluator: &Evaluator, postures: &[Vector6<f64>]) -> f64 {
        let Some(c) = self.calibration else {
            return evaluator.value(self.stiffness, postures);
        };
        let calibration = c.design.value(c.criterion, postures);
        match self.has_stiffness() {
            false => calibration,
            true => combine(
                evaluator.value(self.stiffness, postures),
                calibration,
                c.weight,
            ),
        }
    }
}

/// `a^(1-w) b^w`, computed in logarithms; `+infinity` when either is not positive and finite.
pub(crate) fn combine(a: f64, b: f64, w: f64) -> f64 {
    match a.is_finite() && a > 0.0 && b.is_finite() && b > 0.0 {
        true => ((1.0 - w) * a.ln() + w * b.ln()).exp(),
        false => f64::INFINITY,
    }
}

/// How a local search gets the gradient of its objective `ln(criterion)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum Gradient {
    /// Closed form ([`crate::Evaluator::value_and_gradient`]): one evaluation per SQP call;
    /// the cell constraints' gradients from the witness points of their distances.
    #[default]
    Exact,
    /// Forward differences of step [`SearchOptions::fd_step`]: `6n + 1` evaluations per SQP call,
    /// and six more feasibility checks per posture for the cell constraints (for comparison; the
    /// search before exact gradients).
    FiniteDifference,
}

impl Gradient {
    /// Both, exact first.
    pub(crate) const ALL: [Gradient; 2] = [Gradient::Exact, Gradient::FiniteDifference];

    /// The name used on the command line and in files: `exact` or `fd`.
    pub(crate) fn name(self) -> &'static str {
        match self {
            Gradient::Exact => "exact",
            Gradient::FiniteDifference => "fd",
        }
    }
}

impl stiffid_core::common::choice::Choice for Gradient {
    const FIELD: &'static str = "gradient";
    const ALL: &'static [Self] = &Gradient::ALL;
    fn name(self) -> &'static str {
        Gradient::name(self)
    }
    fn help(self) -> &'static str {
        match self {
            Gradient::Exact => "Closed form",
            Gradient::FiniteDifference => "Forward finite differences (for comparison)",
        }
    }
}

stiffid_core::common::choice::by_name!(Gradient);

/// The SQP of a local search.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum Solver {
    /// The default: per criterion, the solver that serves it best ([`Solver::resolve`]): ours
    /// ([`Solver::ActiveSet`]) on the smooth criteria, SLSQP ([`Solver::Slsqp`]) on the
    /// maximum-type ones and `scaled-cond`.
    #[default]
    Auto,
    /// SLSQP (Kraft 1988, the `slsqp` crate, NLopt's translation): a least-squares QP
    /// subproblem (`lsq`, Householder `h12`) with the bounds as general constraints.
    Slsqp,
    /// Our own SQP: a dense Goldfarb-Idnani dual active-set QP per step in range-space form
    /// (bounds handled as unit normals, `O(n q + q^2)` per active-set change with `q` active
    /// constraints), Powell-damped BFGS kept with its inverse (no factorisation per step), an L1
    /// merit line search, a stop confirmed from a fresh Hessian; the maximum-type `classical` and
    /// `zhang2021` in epigraph form (one constraint per posture's dexterity). About 10 times
    /// fewer evaluations than SLSQP in a cell (it converges where SLSQP spends its budget), the
    /// same values on smooth criteria, 7 to 50 times less CPU time on 6 to 24 postures; on
    /// `zhang2021` it ends lower than SLSQP from most start groups, not from all.
    ActiveSet,
}

impl Solver {
    /// Every solver, the default first.
    pub(crate) const ALL: [Solver; 3] = [Solver::Auto, Solver::Slsqp, Solver::ActiveSet];

    /// The solvers a search runs: what [`Solver::resolve`] returns.
    pub const CONCRETE: [Solver; 2] = [Solver::Slsqp, Solver::ActiveSet];

    /// The name used in files and reports: `auto`, `slsqp` or `active-set`.
    pub fn name(self) -> &'static str {
        match self {
            Solver::Auto => "auto",
            Solver::Slsqp => "slsqp",
            Solver::ActiveSet => "active-set",
        }
    }

    /// The solver a local search on `criterion` runs: `self`, or for [`Solver::Auto`]
    /// - [`Solver::ActiveSet`] on the smooth criteria (`relative-a`, `d-optimal`, `test-pose`):
    ///   from each of the paper setup's seeded start groups 1-10 it ends lower than SLSQP or
    ///   within 0.07% of it (lower from 5 to 8 of the 10), at 5 to 10 times less CPU time, and
    ///   with 8 times fewer evaluations in the global search of a cell;
    /// - [`Solver::Slsqp`] on the maximum-type `classical` and `zhang2021`: ours, in epigraph
    ///   form, ends lower on `zhang2021` from most start groups, but from the paper study's
    ///   start group it reaches a group that predicts a worse accuracy than SLSQP's (and than the
    ///   start group), which would reverse the study's findings (`stiffid reproduce`); and on
    ///   `scaled-cond` (a condition number, with kinks where the extreme singular values repeat),
    ///   where ours ends higher than SLSQP from 7 of those 10 start groups (by up to 3.6%).
    ///
    /// Measured on the paper setup with default options (docs/performance.md, "The SQP").
    pub fn resolve(self, criterion: Criterion) -> Solver {
        match self {
            Solver::Auto => match criterion {
                Criterion::RelativeA | Criterion::DOptimal | Criterion::TestPose => {
                    Solver::ActiveSet
                }
                Criterion::Classical | Criterion::Zhang2021 | Criterion::ScaledCond => {
                    Solver::Slsqp
                }
            },
            concrete => concrete,
        }
    }
}

impl stiffid_core::common::choice::Choice for Solver {
    const FIELD: &'static str = "solver";
    const ALL: &'static [Self] = &Solver::ALL;
    fn name(self) -> &'static str {
        Solver::name(self)
    }
    fn help(self) -> &'static str {
        match self {
            Solver::Auto => "Per criterion: active-set on the smooth ones, slsqp on the others",
            Solver::Slsqp => "SLSQP (the slsqp crate)",
            Solver::ActiveSet => "Our SQP: Goldfarb-Idnani QP, damped BFGS",
        }
    }
}

stiffid_core::common::choice::by_name!(Solver);

/// Budget and tolerances of a search.
#[derive(Debug, Clone, PartialEq)]
pub struct SearchOptions {
    /// Most criterion evaluations of one local search (default 6000): a value with its exact
    /// gradient counts as one, a finite-difference probe as one more (an SQP call then costs
    /// `6n + 1`).
    pub max_evals: usize,
    /// Local searches of a global search (default 32).
    pub starts: usize,
    /// SQP steps of every start of a global search before the best [`SearchOptions::polished`]
    /// continue (default 60; 0: every start gets the whole budget).
    pub screen_steps: usize,
    /// Starts of a global search that continue after the screening, with the budget
    /// [`SearchOptions::max_evals`] (default 8).
    pub polished: usize,
    /// Seed of the global search's start groups (default 1).
    pub seed: u64,
    /// Stop when an SQP step changes `ln(criterion)` by less than this, i.e. the criterion by less
    /// than this fraction (default 1e-6).
    pub ftol: f64,
    /// Stop when an SQP step moves every angle by less than this, rad (default 1e-6).
    pub xtol: f64,
    /// Forward finite-difference step of the gradient, rad (default 1e-7, about `sqrt(eps)`
    /// relative to angles of order 1; taken backwards at an upper bound so the probe stays inside).
    /// Used with [`Gradient::FiniteDifference`], for the objective and the cell constraints.
    pub fd_step: f64,
    /// How the objective's gradient is computed (default [`Gradient::Exact`]).
    pub gradient: Gradient,
    /// The SQP of every local search (default [`Solver::Auto`]: per criterion,
    /// [`Solver::resolve`]).
    pub solver: Solver,
    /// The margin every posture keeps to every constraint of the cell, m (0 to
    /// [`limits::MARGIN_MM`]; [`stiffid_core::cell::Checker::keeping`]): lines of sight, incidence, floor,
    /// obstacles, bodies, rope, `[constraints]`. Default `None`: the tracker's
    /// `registration_uncertainty_mm` when the setup gives one, else 0.
    pub margin: Option<f64>,
}

impl Default for SearchOptions {
    fn default() -> Self {
        Self {
            max_evals: 6000,
            starts: 32,
            screen_steps: 60,
            polished: 8,
            seed: 1,
            ftol: 1e-6,
            xtol: 1e-6,
            fd_step: 1e-7,
            gradient: Gradient::Exact,
            solver: Solver::Auto,
            margin: None,
        }
    }
}

impl SearchOptions {
    /// Checks every field against its documented limit, as argmin's `with_*` setters do:
    /// `max_evals` 1 to [`limits::MAX_EVALS`], `starts` and `polished` 1 to
    /// [`limits::MAX_STARTS`], `screen_steps` 0 to [`limits::MAX_EVALS`], `ftol` within
    /// [`limits::FTOL`], `xtol` within [`limits::XTOL_RAD`], `fd_step` within
    /// [`limits::FD_STEP_RAD`], `margin` (in mm) within [`limits::MARGIN_MM`] (NaN and
    /// infinities never). [`local`] and [`global`] call it.
    ///
    /// # Errors
    /// [`stiffid_core::Error::InvalidField`] naming the field (`SearchOptions.fd_step`), the value and the
    /// range; for the margin, a user's option, [`stiffid_core::Error::InvalidOption`]
    /// ([`stiffid_core::JobOption::MarginMm`]).
    pub fn validate(&self) -> Result<()> {
        let counts = [
            ("max_evals", self.max_evals, 1, limits::MAX_EVALS),
            ("starts", self.starts, 1, limits::MAX_STARTS),
            ("screen_steps", self.screen_steps, 0, limits::MAX_EVALS),
            ("polished", self.polished, 1, limits::MAX_STARTS),
        ];
        for (field, value, min, max) in counts {
            limits::check_integer(&format!("SearchOptions.{field}"), value as u64, min, max)?;
        }
        let tolerances = [
            ("ftol", self.ftol, &limits::FTOL),
            ("xtol", self.xtol, &limits::XTOL_RAD),
            ("fd_step", self.fd_step, &limits::FD_STEP_RAD),
        ];
        for (field, value, range) in tolerances {
            limits::check(&format!("SearchOptions.{field}"), &[value], range)?;
        }
        if let Some(m) = self.margin {
            limits::check("margin_mm", &[m * 1e3], &limits::MARGIN_MM)
                .map_err(|e| e.for_option(stiffid_core::JobOption::MarginMm))?;
        }
        Ok(())
    }

    /// A cheaper budget (8 starts screened, the best 2 polished with at most 3000 evaluations,
    /// seed 1): a global search about 4 times cheaper than the default, within 1% of its value on
    /// the paper setup.
    pub fn quick() -> Self {
        Self {
            max_evals: 3000,
            starts: 8,
            polished: 2,
            ..Self::default()
        }
    }
}

/// The result of a search.
#[derive(Debug, Clone, PartialEq)]
pub struct SearchOutcome {
    /// The best group found (axis angles, rad), within the bounds.
    pub postures: Vec<Vector6<f64>>,
    /// The criterion of the start group (for [`global`], of the start of the best local search).
    pub start_value: f64,
    /// The criterion of [`SearchOutcome::postures`]: never above `start_value` (unless the start
    /// violated the cell constraints and the result satisfies them better).
    pub value: f64,
    /// Criterion evaluations spent, finite differences included (for [`global`], over all starts).
    pub evaluations: usize,
    /// Why the local search that found [`SearchOutcome::postures`] stopped (for [`global`], the
    /// best start's last search: its polishing, if it was polished).
    pub termination: Termination,
    /// Why every local search stopped, in start order: one for [`local`]; for [`global`], each
    /// start's last search (the polishing for the polished starts, the screening for the others,
    /// which then mostly end at [`Termination::EvaluationLimit`]). Count them with
    /// [`Termination::count`].
    pub terminations: Vec<Termination>,
}

#[cfg(test)]
mod termination_tests;
