//! Experiment design: which postures to measure in (step 1 of the experiment).
//!
//! [`criteria`] scores a group of postures; the search modules choose postures that minimise a
//! criterion within the setup's bounds.

pub mod criteria;

pub use criteria::{evaluate, Criterion, Evaluation};
