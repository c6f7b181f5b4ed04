//! The cell constraints of a setup as inequalities `c(q) <= 0` on one posture.

use crate::setup::Setup;
use nalgebra::Vector6;

/// The inequalities `c(q) <= 0` (m) of the setup's [`crate::setup::CellConstraints`] for one
/// posture q (axis angles, rad), z the base-frame height of the loading point:
/// `z_min - z` (loading point at or above `loading_point_min_z`) and `anchor_z - z` (rope anchor at
/// or below the loading point). Empty without constraints.
pub fn inequalities(setup: &Setup, q: &Vector6<f64>) -> Vec<f64> {
    let kinds = kinds(setup);
    if kinds.is_empty() {
        return Vec::new();
    }
    let z = setup.robot.frames(q).point(&setup.tool.loading_point).z;
    kinds.iter().map(|k| k.value(setup, z)).collect()
}

/// The largest of [`inequalities`] clamped at 0: 0 when q satisfies every constraint, m.
pub fn violation(setup: &Setup, q: &Vector6<f64>) -> f64 {
    inequalities(setup, q).into_iter().fold(0.0, f64::max)
}

/// One kind of cell constraint.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Kind {
    /// Loading point at or above the floor height.
    MinZ,
    /// Anchor at or below the loading point.
    AnchorBelow,
}

impl Kind {
    /// `c <= 0` given the loading point height `z` (m).
    pub(super) fn value(self, setup: &Setup, z: f64) -> f64 {
        match self {
            Kind::MinZ => {
                setup
                    .constraints
                    .loading_point_min_z
                    .unwrap_or(f64::NEG_INFINITY)
                    - z
            }
            Kind::AnchorBelow => setup.load.anchor.z - z,
        }
    }
}

/// The constraint kinds the setup asks for.
pub(super) fn kinds(setup: &Setup) -> Vec<Kind> {
    let c = &setup.constraints;
    let mut kinds = Vec::new();
    if c.loading_point_min_z.is_some() {
        kinds.push(Kind::MinZ);
    }
    if c.anchor_below_loading_point {
        kinds.push(Kind::AnchorBelow);
    }
    kinds
}
