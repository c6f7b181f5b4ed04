//! The readings of a cell: what the register and calibrate jobs read.

use crate::app::{in_data, Warning};
use nalgebra::Vector3;
use stiffid_core::io::readings::{self, Readings};
use stiffid_core::setup::plausibility;
use stiffid_core::{Result, Setup};
use stiffid_metrology::register::{self, Registration};

/// Readings of a cell: what the register and calibrate jobs read.
pub struct Request<'a> {
    /// The setup: robot, tool (its measuring points), tracker.
    pub setup: &'a Setup,
    /// The setup as the user named it (a built-in setup's name or a file's path): what the
    /// job's document states.
    pub setup_name: String,
    /// The readings file's name (for errors and the document).
    pub name: String,
    /// Its text: `posture,point,q1_deg..q6_deg,x_tracker_mm,y_tracker_mm,z_tracker_mm`
    /// ([`stiffid_core::io::readings`]; with load steps, only the unloaded readings are used), at
    /// most [`readings::MAX_READINGS`] rows.
    pub text: &'a str,
    /// Fit readings that no rigid transform explains (`stiffid_metrology::register`'s check: a
    /// mirror image, a residual beyond [`stiffid_metrology::register::residual_limit`]) instead of
    /// refusing them.
    pub force: bool,
}

/// The readings of `request`, and the warnings about them.
///
/// # Errors
/// Those of [`readings::parse`] and [`register::refuse_other_scale`], as [`stiffid_core::Error::Input`] naming
/// the file.
pub fn read(request: &Request<'_>) -> Result<(Readings, Vec<Warning>)> {
    let Request {
        setup, name, text, ..
    } = request;
    let points = setup.tool().measuring_points.len();
    let data = readings::parse(text, setup.robot(), points).map_err(|e| in_data(name, e))?;
    register::refuse_other_scale(setup, &data).map_err(|e| in_data(name, e))?;
    let warnings = plausibility::radians_as_degrees(data.readings.iter().map(|r| &r.q))
        .map(|mut w| {
            w.message = format!("{name}: {}", w.message);
            w
        })
        .into_iter()
        .collect();
    Ok((data, warnings))
}

/// Refuses, unless `request.force`, readings that no rigid transform explains
/// (`stiffid_metrology::register`'s check at the setup's tracker noise): tracker readings that
/// are a mirror image of the nominal robot's points (by `registration`, or the registration of
/// `data` when `None`), or a fitted residual (`residuals`, m, one per unloaded reading of `data`
/// in file order, or per unloaded reading of the arm's points: the table's reflectors left out) beyond [`stiffid_metrology::register::residual_limit`].
///
/// # Errors
/// [`Error::InvalidField`] in an [`Error::Input`] naming the file: `readings` for a mirror image
/// (both RMS), or the reading's line, posture and point with `residual_norm_mm` (its length and
/// the limit).
pub(crate) fn refuse_implausible(
    request: &Request<'_>,
    data: &Readings,
    registration: Option<&Registration>,
    residuals: &[Vector3<f64>],
) -> Result<()> {
    if request.force {
        return Ok(());
    }
    register::refuse_implausible(request.setup, data, registration, residuals)
        .map_err(|e| in_data(&request.name, e))
}
