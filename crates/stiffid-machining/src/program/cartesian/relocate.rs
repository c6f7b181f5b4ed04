//! A program's frame taught in the nominal cell, read on a calibrated one. The calibration moves
//! the cell frame (the tracker's registration takes the base's errors), so a work object, base or
//! user frame the nominal controller measured (touching the part with the nominal robot) is not
//! where the part is in the calibrated cell, as a G-code program's `[workpiece] base_from_part`
//! from before the calibration is not. On a setup whose robot is not the controller's (a
//! calibrated robot file, a nominal controller), a frame the program's files state (KRL `$BASE`,
//! RAPID `wobjdata`, a backup's `BASE_DATA`, `SYSFRAME.VA` user frames) is taught in the nominal
//! cell; a frame the setup's `[controller] bases` gives is stated as measured in the calibrated
//! cell and read as it is. Where the calibrated robot file locates the part
//! ([`stiffid_core::Robot::part`], from reflectors on the part or its fixture), a taught frame
//! within [`NEAR_M`] and [`NEAR_RAD`] of it is the part's frame: its targets are read in the
//! located part's frame, and a note names the frame, its line and how far it was. A frame farther
//! away (another fixture), or any taught frame where the part is not located, is read as stated
//! with a note that its place in the calibrated cell is not known.

use super::same::same;
use super::{words, Frame};
use nalgebra::Isometry3;

/// The farthest a program's frame may lie from the located part and be the part's frame taught
/// in the nominal cell, m (a nominal robot's error over a large cell: millimetres).
pub(crate) const NEAR_M: f64 = 0.02;

/// The most a program's frame may turn from the located part and be the part's frame, rad
/// (1 deg).
pub(crate) const NEAR_RAD: f64 = 0.017_453_292_519_943_295;

/// What to give for a frame of the calibrated cell, for the notes.
const GIVE: &str = "give the part's reflectors ([workpiece] reflectors_mm) to the calibration to locate it, or the frame as measured in the calibrated cell in the setup's [controller] bases";

/// Where a program's frames are read: whether the setup's robot is calibrated and its
/// controller nominal, the part's frame the calibration located (if it did) and the controller's
/// world, the setup's base frame, m.
pub(super) type Cell = (bool, Option<Isometry3<f64>>, Isometry3<f64>);

/// The frame `frame` (the setup's base frame) of a target whose program states `stated`, on
/// `cell`, re-located as the module docs say; a note for it added to `notes` (once per
/// statement).
pub(super) fn relocated(
    (nominal_cell, located, world): Cell,
    stated: &Frame,
    frame: Isometry3<f64>,
    notes: &mut Vec<String>,
) -> Isometry3<f64> {
    let line = match stated {
        Frame::Stated(l, _) | Frame::Held(l, ..) if nominal_cell => *l,
        _ => return frame,
    };
    let mut note = |n: String| {
        if !notes.contains(&n) {
            notes.push(n);
        }
    };
    let here = words(&(world.inverse() * frame));
    let Some(part) = located else {
        note(format!("line {line}: the program's frame ({here}) was taught in the nominal cell (the setup's robot is calibrated, its controller nominal), and where it lies in the calibrated cell is not known: read as stated, it is off by the nominal robot's error there; {GIVE}"));
        return frame;
    };
    if same(&frame, &part) {
        return frame;
    }
    let (d, a) = (
        (frame.translation.vector - part.translation.vector).norm(),
        frame.rotation.angle_to(&part.rotation),
    );
    let what = format!(
        "line {line}: the program's frame ({here}), taught in the nominal cell, is {:.3} mm and {:.4} deg from the part's frame the calibration located ([part] of the calibrated robot file: {})",
        d * 1e3,
        a.to_degrees(),
        words(&(world.inverse() * part))
    );
    match d <= NEAR_M && a <= NEAR_RAD {
        true => {
            note(format!(
                "{what}: its targets are read in the located part's frame"
            ));
            part
        }
        false => {
            note(format!(
                "{what}: not the part's frame, read as stated; {GIVE}"
            ));
            frame
        }
    }
}
