//! The readings of a cell: what the register and calibrate jobs read.

use super::{in_data, Warning};
use crate::io::readings::{self, Readings};
use crate::setup::plausibility;
use crate::{Result, Setup};

/// Readings of a cell: what the register and calibrate jobs read.
pub struct Request<'a> {
    /// The setup: robot, tool (its measuring points), tracker.
    pub setup: &'a Setup,
    /// The readings file's name (for errors and the document).
    pub name: String,
    /// Its text: `posture,point,q1_deg..q6_deg,x_tracker_mm,y_tracker_mm,z_tracker_mm`
    /// ([`crate::io::readings`]; with load steps, only the unloaded readings are used), at
    /// most [`readings::MAX_READINGS`] rows.
    pub text: &'a str,
}

/// The readings of `request`, and the warnings about them.
///
/// # Errors
/// Those of [`readings::parse`], as [`crate::Error::Input`] naming the file.
pub fn read(request: &Request<'_>) -> Result<(Readings, Vec<Warning>)> {
    let Request { setup, name, text } = request;
    let points = setup.tool().measuring_points.len();
    let data = readings::parse(text, setup.robot(), points).map_err(|e| in_data(name, e))?;
    let warnings = plausibility::radians_as_degrees(data.readings.iter().map(|r| &r.q))
        .map(|mut w| {
            w.message = format!("{name}: {}", w.message);
            w
        })
        .into_iter()
        .collect();
    Ok((data, warnings))
}
