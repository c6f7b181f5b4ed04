//! The tracker frame in the robot base frame with its standard deviations, as the register and
//! calibrate-cell documents have it.

use super::{mm, mm3};
use nalgebra::Isometry3;
use serde::Serialize;

/// The tracker frame in the robot base frame, as a setup file writes it, with its standard
/// deviation.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Transform {
    /// Translation, mm.
    pub xyz_mm: [f64; 3],
    /// Fixed-axis roll, pitch, yaw, deg (as the setup's `base_from_tracker`).
    pub rpy_deg: [f64; 3],
    /// Standard deviations (linearised, from the residuals).
    #[serde(flatten)]
    pub std: TransformStd,
}

impl Transform {
    /// `base_from_tracker` (SI) with the standard deviations `std` (m, then rad).
    pub(crate) fn new(base_from_tracker: &Isometry3<f64>, std: [f64; 6]) -> Self {
        let [r, p, y] = stiffid_core::robot::file::rpy(&base_from_tracker.rotation);
        Transform {
            xyz_mm: mm3(&base_from_tracker.translation.vector),
            rpy_deg: [r, p, y].map(f64::to_degrees),
            std: TransformStd::new(std),
        }
    }
}

/// Standard deviations of a transform's translation and rotation.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct TransformStd {
    /// Standard deviation of the translation, base frame, mm (linearised: from the residuals
    /// of a fit, from the tracker noise for proposed postures).
    pub translation_std_mm: [f64; 3],
    /// Standard deviation of the rotation about the base x, y, z axes, deg.
    pub rotation_std_deg: [f64; 3],
}

impl TransformStd {
    /// Of the standard deviations `std` (m, then rad).
    pub(crate) fn new(std: [f64; 6]) -> Self {
        TransformStd {
            translation_std_mm: [mm(std[0]), mm(std[1]), mm(std[2])],
            rotation_std_deg: [std[3], std[4], std[5]].map(f64::to_degrees),
        }
    }
}
