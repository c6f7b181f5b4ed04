//! How a calibration chooses its model and judges it: the ladder of gravity models and joint
//! error maps scored by their held-out error ([`ladder`], [`maps`]) over the region where the
//! robot is used ([`region`]), the held-out readings the calibration extrapolates to
//! ([`extrapolation`]), the bound of a held-out reading's error from the fit ([`fit_bound`]), the
//! leave-one-posture-out folds that diverged, left out of the intervals ([`diverged`]), why the
//! ladder fitted its rung ([`why`]) and the warnings about a fit ([`judge`]). The calibrate job (`stiffid::app::calibrate`) runs
//! them; they need only the calibration's error model, its fit and the setup.

pub mod diverged;
pub mod extrapolation;
pub mod fit_bound;
pub mod judge;
pub mod ladder;
pub mod maps;
pub mod named;
pub mod region;
pub mod why;

use stiffid_core::common::warning::{Warning, WarningKind};

/// The noise ratio above which the calibration warns that the model misses something.
pub(crate) const MISFIT_RATIO: f64 = 3.0;

/// The residual degrees of freedom below which the calibration warns that the readings are too
/// few.
pub(crate) const MIN_DEGREES_OF_FREEDOM: usize = 10;

/// The condition number of the scaled identification Jacobian above which the calibration warns
/// that some parameters are weakly determined.
pub(crate) const WEAK_CONDITION: f64 = 1e6;

#[cfg(test)]
mod diverged_tests;
#[cfg(test)]
mod judge_tests;
#[cfg(test)]
mod ladder_tests;
