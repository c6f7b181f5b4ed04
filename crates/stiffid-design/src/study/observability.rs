//! Which calibration criterion predicts held-out accuracy: Spearman's rank correlation, over
//! random groups of postures, between each criterion of [`crate::observability`] and the
//! held-out RMS position error of the calibration the group's readings give (the check of the
//! paper's Fig. 8, for calibration).
//!
//! The simulation: the FANUC R-2000iC/165F preset with three measuring points, every parameter
//! of the full geometric error model ([`stiffid_metrology::calibration::Geometry::Full`]: frame,
//! points, six errors a joint)
//! drawn uniformly within +-1 mm or +-1 mrad, readings in a tracker frame with Gaussian noise
//! (`noise` per coordinate), fitted by [`stiffid_metrology::calibration::fit::fit`] from the
//! registered nominal; the truth of a
//! group is the RMS position error, at test postures, of its calibrated model against the true
//! positions (the square root of the mean over `draws` noise draws of the squared RMS). Postures
//! are drawn uniformly in the middle 60% of the joint ranges (at most +-150 deg), every stream
//! from `seed`.
//!
//! The study itself is a unit test (`observability_tests.rs` beside this file, which runs it and
//! checks the ranking); this module holds the postures it draws.

use nalgebra::Vector6;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use stiffid_core::Robot;

/// `n` postures drawn uniformly in the middle 60% of `robot`'s joint ranges (at most +-150 deg).
pub fn postures(robot: &Robot, n: usize, rng: &mut ChaCha8Rng) -> Vec<Vector6<f64>> {
    let l = robot.limits();
    (0..n)
        .map(|_| {
            Vector6::from_fn(|i, _| {
                let (lo, hi) = (l.lower[i].max(-2.6), l.upper[i].min(2.6));
                0.5 * (lo + hi) + 0.6 * (hi - lo) * (rng.random::<f64>() - 0.5)
            })
        })
        .collect()
}
