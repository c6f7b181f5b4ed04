//! The update of a calibrated robot from a short check campaign (`calibrate --update`): what
//! drifts between sessions refitted, the rest of the calibration kept.
//!
//! Between sessions a calibrated robot's joint zeros slip (a motor or encoder changed, a
//! collision, a re-mastering), its base moves on its foundation and its tool is re-mounted; its
//! link geometry, its joint error maps and its weight do not change. The update starts from the
//! calibrated robot file (the setup's robot) and fits the joint angle offsets, the frame (the
//! tracker's registration, or the base frame's error for readings in the base frame: the base)
//! and the measuring points (the tool), `calibrate --geometry offsets --gravity none --maps none`
//! on the calibrated file: the DH table, the error maps and the axis map stay as the file has
//! them.

use super::Request;
use crate::common::error::JobOption;
use crate::metrology::calibration::error_model::Observation;
use crate::metrology::calibration::gravity::Gravity;
use crate::metrology::calibration::maps::Spec;
use crate::metrology::calibration::Geometry;
use crate::{Error, Result, Setup};

/// The fewest distinct postures an update reads (the readings must separate the six offsets
/// from the frame and the points).
pub const MIN_POSTURES: usize = 5;

/// The model the job fits: the request's geometry, gravity and maps, or with `update` the
/// offsets alone (module docs).
///
/// # Errors
/// With `update`, [`Error::InvalidOption`] ([`JobOption::Update`]) when the setup's robot is not
/// a calibrated robot file (its name ends with [`crate::robot::CALIBRATED`]), the cell has
/// external axes, the readings are loaded or hold fewer than [`MIN_POSTURES`] postures.
pub(super) fn settings(
    request: &Request<'_>,
    setup: &Setup,
    obs: &[Observation],
) -> Result<(Geometry, Gravity, Spec)> {
    if !request.update {
        return Ok((request.geometry, request.gravity, request.maps));
    }
    let refuse = |message: String| {
        Err(Error::InvalidOption {
            option: JobOption::Update,
            message,
        })
    };
    let robot = setup.robot();
    if !robot.name().ends_with(crate::robot::CALIBRATED) {
        return refuse(format!(
            "the setup's robot {:?} is not a calibrated robot file: point the setup's robot at the file `calibrate --out` wrote",
            robot.name()
        ));
    }
    if robot.external().is_some() {
        return refuse("a cell with external axes is not updated: calibrate it again".into());
    }
    if obs.iter().any(Observation::loaded) {
        return refuse(
            "the check readings are loaded (load steps): read the check postures unloaded".into(),
        );
    }
    let mut postures: Vec<usize> = obs.iter().map(|o| o.posture).collect();
    postures.sort_unstable();
    postures.dedup();
    if postures.len() < MIN_POSTURES {
        return refuse(format!(
            "expected at least {MIN_POSTURES} check postures, got {}: design them with `select --for check`",
            postures.len()
        ));
    }
    Ok((Geometry::Offsets, Gravity::None, Spec::None))
}

/// The `[held_out]` table of the robot file: the held-out errors of this job's validation (else
/// its cross-validation); with `update` and neither, the calibrated robot file's own (its
/// calibration's errors, carried to the updated robot).
pub(super) fn held_out(
    request: &Request<'_>,
    setup: &Setup,
    validation: Option<&super::Held>,
    cross_validation: Option<&super::Held>,
) -> String {
    match (validation.or(cross_validation), setup.robot().held_out()) {
        (None, Some(h)) if request.update => {
            super::document::held_out_lines(&h.source, h.errors.iter().copied())
        }
        _ => super::document::held_out_table(validation, cross_validation),
    }
}
