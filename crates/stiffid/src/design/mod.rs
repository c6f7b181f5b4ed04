//! Experiment design: which postures to measure in (step 1 of the experiment).
//!
//! [`criteria`] scores a group of postures, [`Evaluator`] scores it fast for the search, and
//! [`search`] chooses the postures that minimise a criterion within the setup's bounds.

pub mod criteria;
mod evaluator;
pub mod search;

pub use criteria::{evaluate, Criterion, Evaluation};
pub use evaluator::{Evaluator, PostureTerms};
pub use search::{global, local, random_group, Gradient, SearchOptions, SearchOutcome};
