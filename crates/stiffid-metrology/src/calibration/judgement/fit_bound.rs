//! A bound from the fit where the jackknife+ has none: with `n` held-out values (three per
//! fitted reading) the jackknife+ gives a finite end at level `p` only when `n >= p / (1 - p)`
//! ([`stiffid_core::model::prediction::held_out_needed`]: 333 at 99.7 %), so a campaign of 100
//! postures read at one point has no finite 99.7 % interval. Rather than an infinite interval
//! (which covers every reading and says nothing), such an end is taken from the fit under a
//! Gaussian assumption: the error of each coordinate `c` of a held-out reading is taken as normal
//! with mean zero and variance
//!
//! ```text
//! s^2 + (J_x C J_x^T)_cc
//! ```
//!
//! `s^2` the mean square of the fitted postures' leave-one-posture-out errors (what the model
//! misses and the tracker's noise on a posture the fit has not seen, pooled over the
//! coordinates), `J_x` the Jacobian of the reading's predicted position at the fit (its fitted
//! parameters' columns) and `C` the fit's covariance (how far the parameters are determined
//! there, larger away from the fitted postures). The interval is `+- z s_c` with `z` the
//! standard normal's quantile at `(1 + p) / 2`. The assumption is stated in the document; a
//! robot's errors with heavier tails than a normal's are covered less than `p`.

use crate::calibration::error_model::{Estimate, Observation};
use crate::calibration::fit::Fit;
use crate::calibration::validation::Fold;
use crate::calibration::ErrorModel;
use statrs::distribution::{ContinuousCDF, Normal};
use stiffid_core::model::prediction::Interval;
use stiffid_core::Result;

/// The readings whose Jacobian is computed together.
const CHUNK: usize = 1024;

/// What the document says of the bound from the fit.
pub const ASSUMPTION: &str = "each coordinate's error normal, with the variance of the fitted postures' leave-one-posture-out errors plus the fit's covariance carried to the reading";

/// The mean square (m^2) of the coordinates of every fold's held-out errors: `s^2` (module docs).
pub fn held_out_variance(folds: &[Fold]) -> f64 {
    let (sum, n) = (folds.iter().flat_map(|f| &f.held.errors)).fold((0.0, 0usize), |(s, n), e| {
        (s + e.error.norm_squared(), n + 3)
    });
    sum / n.max(1) as f64
}

/// The half-width at `level` of the bound from the fit of each coordinate of a reading whose
/// predicted-position variance from the fit's covariance is `parameters` (m^2), with the held-out
/// variance `held` (m^2), m.
pub fn half_width(level: f64, held: f64, parameters: f64) -> f64 {
    let z = Normal::standard().inverse_cdf(0.5 + 0.5 * level);
    z * (held + parameters.max(0.0)).sqrt()
}

/// Replaces every infinite end of `intervals` (of the errors of `observations` at `estimate`, in
/// their order) by the bound from `fit` at `level` (module docs) with the held-out variance
/// `held` (m^2); returns how many coordinates took it.
///
/// # Errors
/// Those of [`ErrorModel::jacobian_of`].
pub fn fill(
    intervals: &mut [Interval],
    (model, fit, estimate): (&ErrorModel, &Fit, &Estimate),
    observations: &[Observation],
    (level, held): (f64, f64),
) -> Result<usize> {
    let open = |i: &Interval| i.iter().flatten().any(|v| !v.is_finite());
    let mut filled = 0;
    for (chunk, bounds) in observations.chunks(CHUNK).zip(intervals.chunks_mut(CHUNK)) {
        if !bounds.iter().any(open) {
            continue;
        }
        let j = (model.jacobian_of(&estimate.values, chunk)?).select_columns(fit.fitted.iter());
        let propagated = &j * &fit.covariance;
        for (i, interval) in bounds.iter_mut().enumerate() {
            if !open(interval) {
                continue;
            }
            for (c, ends) in interval.iter_mut().enumerate() {
                let row = 3 * i + c;
                let h = half_width(level, held, propagated.row(row).dot(&j.row(row)));
                if !ends[0].is_finite() {
                    ends[0] = -h;
                }
                if !ends[1].is_finite() {
                    ends[1] = h;
                }
                filled += 1;
            }
        }
    }
    Ok(filled)
}
