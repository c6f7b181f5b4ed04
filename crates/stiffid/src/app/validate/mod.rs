//! The validate job: an identified stiffness of every parameter of the setup's model against
//! measurements it was not fitted to (Zhang et al. 2021, Eq. 22, Table 7; [`crate::identify::validate`]).

pub mod document;

use super::measurements::{angle_warnings, on_measurements, Data, Origin};
use super::Warning;
use crate::identify::validate::{compare_at, Validation};
use crate::model::Compliance;
use crate::{Result, Setup};
use std::io::Read;

/// What to validate on what.
pub struct Request<'a, R> {
    /// The setup: robot, tool, model.
    pub setup: &'a Setup,
    /// The compliance of every parameter of the setup's model (e.g. a stiffness file's,
    /// [`crate::io::stiffness::StiffnessFile::compliance`]).
    pub compliance: &'a Compliance,
    /// The measurements (as for [`super::identify`]), ideally postures not used to identify.
    pub data: Data<R>,
    /// The level of the prediction intervals (with the compliance's prediction calibration),
    /// within [`crate::model::prediction::LEVEL`], only with a compliance that carries one;
    /// `None` for [`crate::model::prediction::DEFAULT_LEVEL`].
    pub level: Option<f64>,
}

/// What the validate job found.
#[derive(Debug, Clone)]
pub struct Report {
    /// The data's name (a file's, or `arrays`).
    pub data_name: String,
    /// The compliance validated.
    pub compliance: Compliance,
    /// Every measurement against its prediction, and the summary.
    pub validation: Validation,
    /// Where each measurement came from.
    pub origin: Origin,
    /// Inputs to look at before trusting the result (angles that look like radians).
    pub warnings: Vec<Warning>,
}

/// Runs the validate job.
///
/// # Errors
/// Errors about the data are [`crate::Error::Input`] naming the data (a file's line and column,
/// or the measurement's number): those of [`crate::io::measurements::parse`] and of
/// [`compare`] (the compliance against the model, the measurements against the setup).
pub fn run<R: Read>(request: Request<'_, R>) -> Result<Report> {
    let Request {
        setup,
        compliance,
        data,
        level,
    } = request;
    let level = crate::model::prediction::requested_level(level, compliance.prediction.is_some())?;
    let (data_name, origin, validation) = on_measurements(setup, data, |m| {
        compare_at(setup.arm(), compliance, m, level)
    })?;
    let warnings = angle_warnings(&data_name, &origin);
    Ok(Report {
        data_name,
        compliance: compliance.clone(),
        validation,
        origin,
        warnings,
    })
}
