//! The forward model of the Virtual Joint Method (Zhang et al. 2021, Eq. 3-7).

use crate::robot::kinematics::Frames;
use crate::setup::{Arm, Setup};
use nalgebra::{Vector3, Vector6};

/// What a wrench does to a posture: joint torques, joint deflections and the displacement of every
/// measuring point.
#[derive(Debug, Clone, PartialEq)]
pub struct Deflection {
    /// `tau = J_f^T W` (Eq. 4), Nm, in the springs' coordinates.
    pub torques: Vector6<f64>,
    /// `dq = h .* tau` (Eq. 5), rad.
    pub joint_deflections: Vector6<f64>,
    /// `J_m dq` (Eq. 6) of each measuring point: translation (m) then rotation of the flange (rad),
    /// base frame.
    pub displacements: Vec<Vector6<f64>>,
}

/// Joint torques `tau = J_f^T W` (Eq. 4), Nm, of a wrench `[f; m]` (N, Nm, base frame) at the
/// arm's loading point, in the coordinates of the springs.
pub fn joint_torques(arm: &Arm, frames: &Frames, wrench: &Vector6<f64>) -> Vector6<f64> {
    frames
        .jacobian(&arm.tool().loading_point, arm.springs())
        .tr_mul(wrench)
}

/// The deflection of the posture `frames` under a wrench `[f; m]` (N, Nm, base frame, at the loading
/// point) with joint stiffness `stiffness` (Nm/rad) (Eq. 3-7).
pub fn deflection(
    arm: &Arm,
    frames: &Frames,
    wrench: &Vector6<f64>,
    stiffness: &Vector6<f64>,
) -> Deflection {
    let torques = joint_torques(arm, frames, wrench);
    let joint_deflections = torques.component_div(stiffness);
    let displacements = arm
        .tool()
        .measuring_points
        .iter()
        .map(|p| frames.jacobian(p, arm.springs()) * joint_deflections)
        .collect();
    Deflection {
        torques,
        joint_deflections,
        displacements,
    }
}

/// The translation (m) of each measuring point under the setup's rope-mass load and stiffness
/// `stiffness` (Nm/rad).
pub fn rope_displacements(
    setup: &Setup,
    frames: &Frames,
    stiffness: &Vector6<f64>,
) -> Vec<Vector3<f64>> {
    let wrench = setup.rope_wrench(frames);
    deflection(setup.arm(), frames, &wrench, stiffness)
        .displacements
        .iter()
        .map(|d| d.fixed_rows::<3>(0).into_owned())
        .collect()
}
