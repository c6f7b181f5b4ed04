//! The frames measurements are taken in, and their rotation into the robot base frame.
//!
//! Identification (Eq. 10-11) needs the wrench and the displacements in the base frame. An F/T
//! sensor on the flange measures the wrench in the tool (flange) frame; a laser tracker measures
//! positions in its own frame.
//! - Wrench in the tool frame: `f_base = R_flange(q) f_tool`, `m_base = R_flange(q) m_tool`, with
//!   `R_flange(q)` the flange orientation of the measurement's posture (forward kinematics). The
//!   wrench stays at the loading point: only its components change frame.
//! - Displacement in the tracker frame: `d_base = R_bt d_tracker`, `R_bt` the rotation of the
//!   setup's `base_from_tracker` transform. A displacement is a difference of two positions, so the
//!   translation of the transform cancels.
//!
//! Sign convention: the wrench is the one that acts on the robot at the loading point (a mass
//! hanging from it pulls down: `f_z < 0`); the displacement is loaded minus unloaded position.

use crate::observation::deflection::{base_wrench, Frame};
use crate::observation::Measurement;
use crate::robot::kinematics::Frames;
use crate::{Error, Result, Setup};

/// The frame of a file's displacement columns.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum DisplacementFrame {
    /// The robot base frame.
    #[default]
    Base,
    /// The laser tracker's frame (the setup's `[tracker] base_from_tracker`).
    Tracker,
}

/// [`to_base`] for measurements whose frames a file named: `wrench` and `displacement` are the
/// frames they are in, and are set to the base frame once the measurements are turned.
///
/// # Errors
/// Those of [`to_base`]; the measurements and frames are then unchanged or partly turned.
pub fn file_to_base(
    setup: &Setup,
    measurements: &mut [Measurement],
    wrench: &mut Frame,
    displacement: &mut DisplacementFrame,
) -> Result<()> {
    to_base(setup, measurements, *wrench, *displacement)?;
    *wrench = Frame::Base;
    *displacement = DisplacementFrame::Base;
    Ok(())
}

/// Rotates the wrenches and displacements of `measurements` from the given frames into the base
/// frame (module docs). Flange orientations are computed once per run of measurements with the same
/// axis angles.
///
/// # Errors
/// [`Error::InvalidField`] (`tracker.base_from_tracker`) when the displacements are in the tracker
/// frame and the setup has no tracker transform.
pub fn to_base(
    setup: &Setup,
    measurements: &mut [Measurement],
    wrench: Frame,
    displacement: DisplacementFrame,
) -> Result<()> {
    if displacement == DisplacementFrame::Tracker {
        let transform = setup
            .tracker()
            .as_ref()
            .and_then(|t| t.base_from_tracker)
            .ok_or_else(|| Error::InvalidField {
            field: "tracker.base_from_tracker".into(),
            message: "the displacements are in the tracker frame (dx_tracker_mm, ...): the setup needs [tracker] base_from_tracker = { xyz_mm = [..], rpy_deg = [..] }".into(),
        })?;
        for m in measurements.iter_mut() {
            m.displacement = transform.rotation * m.displacement;
        }
    }
    if wrench == Frame::Tool {
        // The posture's frames, computed once per run of measurements with the same angles.
        let mut last: Option<(nalgebra::Vector6<f64>, _, Frames)> = None;
        for m in measurements.iter_mut() {
            if last.as_ref().is_none_or(|(q, e, _)| *q != m.q || *e != m.e) {
                last = Some((m.q, m.e, setup.robot().frames_at(&m.q, m.e.as_slice())));
            }
            if let Some((_, _, frames)) = &last {
                m.wrench = base_wrench(frames, &m.wrench, Frame::Tool);
            }
        }
    }
    Ok(())
}
