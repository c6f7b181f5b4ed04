//! Fast evaluation of one design criterion, for the posture search.
//!
//! [`Evaluator::new`] precomputes what does not depend on the postures; [`Evaluator::value`]
//! computes one criterion of a group, equal (to rounding) to [`super::evaluate`]'s.

use super::criteria::{evaluate, Criterion};
use crate::setup::Setup;
use nalgebra::Vector6;

/// Evaluates design criteria of groups of postures for one setup.
#[derive(Debug, Clone)]
pub struct Evaluator<'a> {
    setup: &'a Setup,
}

impl<'a> Evaluator<'a> {
    /// An evaluator for `setup`.
    pub fn new(setup: &'a Setup) -> Self {
        Self { setup }
    }

    /// The setup evaluated.
    pub fn setup(&self) -> &Setup {
        self.setup
    }

    /// The value of `criterion` for `postures` (axis angles, rad): `+infinity` for a group whose
    /// observation matrix is rank deficient, never NaN.
    pub fn value(&self, criterion: Criterion, postures: &[Vector6<f64>]) -> f64 {
        evaluate(self.setup, postures).value(criterion)
    }
}
