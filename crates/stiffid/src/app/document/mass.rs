//! The document parts of the robot's mass that the jobs share (predict, kinematics, compensate):
//! natural frequencies and mode shapes
//! ([`stiffid_core::robot::dynamics`], [`stiffid_core::observation::dynamics`]).

use nalgebra::Vector3;
use serde::Serialize;
use stiffid_core::robot::dynamics::modes::Modes;

/// One mode of the undamped elastic robot.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct ModeShape {
    /// Its natural frequency, Hz.
    pub frequency_hz: f64,
    /// The joint motion of the mode, q1..q6 (the joint coordinates of the document), scaled to a
    /// largest component of +1.
    pub joints: [f64; 6],
    /// The direction in which it moves the tool point (unit, base frame); zeros where it does not
    /// move it (or where the document has no tool point).
    pub point_direction: [f64; 3],
}

/// The natural frequencies (Hz, ascending) and the mode shapes of `modes`, with the tool point's
/// direction of each (`directions`, zeros where none).
pub(crate) fn modes(
    modes: Option<&Modes>,
    directions: &[Vector3<f64>; 6],
) -> (Option<[f64; 6]>, Option<Vec<ModeShape>>) {
    let Some(m) = modes else {
        return (None, None);
    };
    let shapes = (0..6)
        .map(|i| ModeShape {
            frequency_hz: m.frequencies[i],
            joints: m.shapes[i].into(),
            point_direction: directions[i].into(),
        })
        .collect();
    (Some(m.frequencies), Some(shapes))
}
