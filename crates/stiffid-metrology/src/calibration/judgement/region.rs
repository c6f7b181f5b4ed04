//! Where the robot is used: the region of axis angles over which the ladder judges how far a
//! gravity model extrapolates ([`super::ladder`]).
//!
//! A heavy robot is often measured, and works, in a small part of its joint limits (36 postures
//! of a FANUC R-2000iC/165F in front of a fixture). Its gravity terms are then determined there
//! and left to their bound elsewhere: a model that predicts the readings better where the robot
//! works spreads its predictions by millimetres over the whole joint limits, where the robot never
//! goes. The ladder judges the spread where the robot is used, not where it can go.
//!
//! The region is a box of axis angles: per axis, the range of every posture the campaign and
//! the setup name (the fitted postures, the held-out postures of `--validate`, the setup's test
//! postures `[test] postures_deg`), widened on each side by [`MARGIN_SHARE`] of that range and
//! at least [`MARGIN_RAD`], then cut to the robot's joint limits and to the setup's `[bounds]`
//! (the experiment's bounds: no posture of the campaign's lies beyond them). A setup that names
//! postures over the whole joint limits (its test postures) judges the models there.

use crate::calibration::error_model::Observation;
use nalgebra::Vector6;
use stiffid_core::common::limits::JointBox;
use stiffid_core::Setup;

/// The share of each axis's range by which the region is widened on either side: 10 %.
pub const MARGIN_SHARE: f64 = 0.1;

/// The least widening of the region on either side of each axis's range: 5 deg.
pub const MARGIN_RAD: f64 = 5.0 * std::f64::consts::PI / 180.0;

/// The region of `postures` (axis angles, rad; module docs) within `limits` and `bounds`; `limits`
/// when there is no posture.
pub fn region(postures: &[Vector6<f64>], limits: &JointBox, bounds: &JointBox) -> JointBox {
    if postures.is_empty() {
        return *limits;
    }
    let mut lower = Vector6::repeat(f64::INFINITY);
    let mut upper = Vector6::repeat(f64::NEG_INFINITY);
    for q in postures {
        lower = lower.inf(q);
        upper = upper.sup(q);
    }
    let margin = (upper - lower).map(|span| (MARGIN_SHARE * span).max(MARGIN_RAD));
    let lower = (lower - margin).sup(&limits.lower).sup(&bounds.lower);
    let upper = (upper + margin).inf(&limits.upper).inf(&bounds.upper);
    // A posture beyond the bounds keeps its axis's range non-empty.
    JointBox::new(lower.inf(&upper), upper.sup(&lower))
}

/// The region of a calibration's `fitted` readings (table readings left out), the postures of
/// the held-out readings `held` (`None` without `--validate`, or when they cannot be read: their
/// error comes with the validation) and the `setup`'s test postures, cut to the robot's limits and
/// the setup's bounds (module docs).
pub fn of(setup: &Setup, fitted: &[Observation], held: Option<&[Vector6<f64>]>) -> JointBox {
    let mut postures: Vec<Vector6<f64>> =
        (fitted.iter()).filter(|o| !o.table).map(|o| o.q).collect();
    postures.extend(held.unwrap_or_default());
    postures.extend_from_slice(setup.test_postures());
    region(&postures, setup.robot().limits(), setup.bounds())
}
