//! An update's external axes (`calibrate --update` on a cell): the axes as a calibrated robot
//! file gives them, their zero offsets fitted, everything else of theirs held.
//!
//! Between sessions a track's encoder or a positioner's is re-mastered (its zero moves); the
//! track's direction and error motions and the positioner's axis lines, which the full
//! calibration found, do not change. A track's zero offset moves the arm along the rail: on
//! the arm's readings alone it is a shift of the tracker's registration (merged); reflectors
//! on a positioner's table, its lines held, tell them apart. A one-axis positioner's angular
//! offset turns its table's zero, which the reflectors' positions (fitted in every session)
//! take; the first axis's of a two-axis positioner turns the second's line, and is identified.

use super::{AxisPart, ErrorModel, Kind, Parameter, Target};
use stiffid_core::robot::external::{AxisKind, ExternalAxes};
use stiffid_core::Result;

impl ErrorModel {
    /// The model with the robot's external axes as it gives them (a calibrated cell's: the
    /// directions, error motions and lines held at the robot file's) and each axis's zero
    /// offset a parameter: a linear axis's `<axis>.offset` (its carriage moved along its
    /// direction, m, [`AxisPart::Shift`]), a rotary axis's `<axis>.offset` (rad), priority 2;
    /// the offsets held too unless `offsets`; and `tables` reflectors on the positioner's table
    /// (fitted). What an update fits on a cell (`calibrate --update`).
    ///
    /// # Errors
    /// As [`ErrorModel::with_external`]; those of [`ErrorModel::with_held`].
    pub fn with_external_offsets(self, tables: usize, offsets: bool) -> Result<Self> {
        let axes = self.robot.external().map_or(0, ExternalAxes::len);
        let mut model = self.with_external(&vec![0; axes], tables)?;
        let x = model.external.as_mut().expect("set by with_external");
        for (i, axis) in x.axes.axes().iter().enumerate() {
            if axis.kind == AxisKind::Linear {
                x.shifts[i] = Some(model.parameters.len());
                model.parameters.push(Parameter {
                    name: format!("{}.offset", axis.name),
                    kind: Kind::Carrier,
                    target: Target::External {
                        axis: i,
                        part: AxisPart::Shift,
                    },
                    nominal: 0.0,
                    priority: 2,
                });
            }
        }
        let held: Vec<(usize, f64)> = (model.parameters.iter().enumerate())
            .filter(|(_, p)| match p.target {
                Target::External { part, .. } => {
                    !offsets || !matches!(part, AxisPart::Offset | AxisPart::Shift)
                }
                _ => false,
            })
            .map(|(c, _)| (c, 0.0))
            .collect();
        model.with_held(&held)
    }
}
