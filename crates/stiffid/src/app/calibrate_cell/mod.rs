//! The calibrate job (`stiffid calibrate-cell`): the tracker's transform and the measuring points
//! in the flange frame fitted together from unloaded readings ([`stiffid_metrology::cell_calibration`]:
//! the robot calibration's Levenberg-Marquardt over 6 + 3p unknowns, `calibrate --geometry none
//! --gravity none`), each point's shift from the setup's value with its standard deviation.

pub mod document;

use crate::app::in_data;
pub use crate::app::readings::Request;
use crate::app::readings::{read, refuse_implausible};
use crate::app::Warning;
use nalgebra::Vector3;
use stiffid_core::Result;
use stiffid_metrology::cell_calibration::{self, Calibration};

/// What the calibrate job found.
#[derive(Debug, Clone)]
pub struct Report {
    /// The readings file's name.
    pub data_name: String,
    /// The setup's measuring points, flange frame, m (the fit's start).
    pub setup_points: Vec<Vector3<f64>>,
    /// Unloaded readings used.
    pub readings: usize,
    /// The calibrated cell.
    pub calibration: Calibration,
    /// Inputs to look at before trusting the result (angles that look like radians).
    pub warnings: Vec<Warning>,
}

/// The calibrate-cell job's report and its document.
pub type Outcome = crate::app::Outcome<Report, document::Calibration>;

/// Runs the calibrate job.
///
/// # Errors
/// Those of [`read`]; of [`cell_calibration::observations`] and [`cell_calibration::fit`] (readings in the base
/// frame, too few readings for the unknowns, one flange orientation), as
/// [`stiffid_core::Error::Input`] naming the file; unless [`Request::force`], readings that are a
/// mirror image (of the nominal robot's points) or leave a residual beyond
/// [`stiffid_metrology::register::residual_limit`], naming the reading.
pub fn run(request: &Request<'_>) -> Result<Outcome> {
    let report = find(request)?;
    let document = document::Calibration::new(&report, &request.setup_name);
    Ok(Outcome { report, document })
}

/// What [`run`] finds, before its document.
fn find(request: &Request<'_>) -> Result<Report> {
    let (data, mut warnings) = read(request)?;
    let name = &request.name;
    let setup_points = request.setup.tool().measuring_points.clone();
    let observations =
        cell_calibration::observations(request.setup, &data).map_err(|e| in_data(name, e))?;
    let calibration =
        cell_calibration::fit(request.setup, &observations).map_err(|e| in_data(name, e))?;
    refuse_implausible(request, &data, None, &calibration.residuals)?;
    warnings.extend(stiffid_metrology::calibration::fit::stop_warning(
        calibration.stop,
        calibration.iterations,
    ));
    Ok(Report {
        data_name: name.clone(),
        setup_points,
        readings: observations.len(),
        calibration,
        warnings,
    })
}
