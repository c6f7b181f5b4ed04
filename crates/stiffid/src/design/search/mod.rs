//! Posture search: the group of postures that minimises a design criterion within the setup's
//! bounds and the cell's feasibility checks ([`crate::cell`]).
//!
//! - [`local`]: SQP (SLSQP, Kraft 1988, through the `slsqp` crate: the counterpart of the MATLAB
//!   `fmincon` the paper uses) from a start group, as in Zhang et al. 2021, Section III-B step 5;
//! - [`global`]: many local searches in parallel from seeded space-filling starts, the best kept
//!   (the paper's stated future work);
//! - [`random_group`]: a seeded Latin-hypercube start group.
//!
//! The variables are the `6n` axis angles (rad) of the `n` postures, posture-major. Every point
//! evaluated is clamped into the bounds, so no search ever returns a posture outside them.

mod constraints;
mod global;
mod local;
mod sample;

pub use global::global;
pub(super) use local::check_count;
pub use local::local;
pub use sample::{random_group, CONSTRAINT_TRIES};

use nalgebra::Vector6;

/// Budget and tolerances of a search.
#[derive(Debug, Clone, PartialEq)]
pub struct SearchOptions {
    /// Most criterion evaluations of one local search, finite differences included (default
    /// 6000). Each SQP step costs at most `6n + 1` evaluations.
    pub max_evals: usize,
    /// Local searches of a global search (default 32).
    pub starts: usize,
    /// Seed of the global search's start groups (default 1).
    pub seed: u64,
    /// Stop when an SQP step changes `ln(criterion)` by less than this, i.e. the criterion by less
    /// than this fraction (default 1e-6).
    pub ftol: f64,
    /// Stop when an SQP step moves every angle by less than this, rad (default 1e-6).
    pub xtol: f64,
    /// Forward finite-difference step of the gradient, rad (default 1e-7, about `sqrt(eps)`
    /// relative to angles of order 1; taken backwards at an upper bound so the probe stays inside).
    pub fd_step: f64,
}

impl Default for SearchOptions {
    fn default() -> Self {
        Self {
            max_evals: 6000,
            starts: 32,
            seed: 1,
            ftol: 1e-6,
            xtol: 1e-6,
            fd_step: 1e-7,
        }
    }
}

impl SearchOptions {
    /// A cheaper budget (8 starts of at most 3000 evaluations, seed 1): a global search about 6
    /// times cheaper than the default, within 1% of its value on the paper setup.
    pub fn quick() -> Self {
        Self {
            max_evals: 3000,
            starts: 8,
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
}
