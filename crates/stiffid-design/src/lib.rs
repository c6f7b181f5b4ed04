//! Experiment design: which postures to measure in (step 1 of the experiment).
//!
//! [`criteria`] scores a group of postures (for the stiffness identification; [`observability`] for
//! the geometric and elastostatic calibration), [`Evaluator`] scores it fast for the search,
//! [`search`] chooses the postures that minimise a criterion within the setup's bounds, [`pool`]
//! chooses them from a list of candidate postures, [`target`] finds how many postures reach a
//! predicted accuracy, [`distinct`] flags postures of a group that are not distinct, and
//! [`registration`] chooses the postures that register the tracker best; [`candidates`] says
//! which candidates of the model comparison a group identifies and designs for them.
#![deny(missing_docs)]
#![deny(rustdoc::broken_intra_doc_links, rustdoc::private_intra_doc_links)]

pub mod candidates;
pub mod criteria;
pub mod distinct;
pub(crate) mod evaluator;
pub(crate) mod exchange;
mod identifiable;
pub mod observability;
pub mod pool;
pub mod registration;
pub mod search;
pub mod selection;
pub mod study;
pub mod target;

pub use criteria::{Criterion, Evaluation, ParameterQuality};
pub use evaluator::{evaluate, Evaluator};
pub use exchange::{PoolMethod, PoolOptions};
pub use identifiable::{identifiable, unidentifiable};
pub use pool::{Pool, PoolChoice};
pub(crate) use search::local_for;
pub use search::{
    global, global_for, local, random_group, CalibrationGoal, Goal, Gradient, SearchOptions,
    SearchOutcome, Solver, Termination,
};

#[cfg(test)]
mod exchange_tests;

#[cfg(test)]
mod pool_tests;

#[cfg(test)]
mod registration_tests;
