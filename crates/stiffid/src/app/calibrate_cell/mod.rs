//! The calibrate job (`stiffid calibrate-cell`): the tracker's transform and the measuring points
//! in the flange frame fitted together from unloaded readings ([`stiffid_metrology::cell_calibration`]:
//! the robot calibration's Levenberg-Marquardt over 6 + 3p unknowns, `calibrate --geometry none
//! --gravity none`), each point's shift from the setup's value with its standard deviation.

use crate::app::document::transform::Transform;
use crate::app::document::{mm3, units};
use crate::app::in_data;
pub use crate::app::readings::Request;
use crate::app::readings::{read, refuse_implausible};
use crate::app::Warning;
use nalgebra::Vector3;
use serde::Serialize;
use stiffid_core::common::stop::Stop;
use stiffid_core::Result;
use stiffid_metrology::cell_calibration::{self, Calibration};

/// The calibrate-cell document: the transform, the measuring points and the robot's unloaded
/// absolute error.
///
/// The report is its own document (`stiffid calibrate-cell --json`, Python's
/// `calibrate_cell(...)`): SI lengths written in mm by the unit adapters
/// ([`crate::app::document::units`]); the transform as a setup file writes it.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "calibrate-cell")]
#[cfg_attr(
    feature = "schema",
    schemars(
        description = "The calibrate-cell document: the transform, the measuring points and the robot's unloaded\nabsolute error."
    )
)]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("calibrate-cell")))]
pub struct Report {
    /// The setup as given.
    pub setup: String,
    /// The readings file.
    #[serde(rename = "data")]
    pub data_name: String,
    /// The tracker frame in the robot base frame.
    #[serde(flatten)]
    pub transform: Transform,
    /// Every measuring point of the setup.
    pub points: Vec<ToolPoint>,
    /// RMS of the residual lengths: m, written in mm; the robot's unloaded absolute positioning
    /// error at these postures (with the tracker noise).
    #[serde(rename = "absolute_error_rms_mm", serialize_with = "units::mm")]
    pub absolute_error_rms: f64,
    /// Noise per coordinate estimated from the residuals: m, written in mm.
    #[serde(rename = "noise_std_mm", serialize_with = "units::mm")]
    pub noise_std: f64,
    /// Unloaded readings used.
    pub readings: usize,
    /// Levenberg-Marquardt iterations.
    pub iterations: usize,
    /// Why the iterations stopped: `converged`, `stalled`, `damping-exhausted` (a minimum within
    /// rounding) or `iteration-limit` (not converged; a warning says so).
    #[serde(rename = "stop_reason")]
    pub stop: Stop,
    /// The corrected fragment of the setup file.
    pub fragment: String,
    /// Inputs to look at before trusting the result (angles that look like radians): printed
    /// and raised, not written.
    #[serde(skip)]
    pub warnings: Vec<Warning>,
}

/// One measuring point: the setup's, the fitted, the shift and its standard deviation.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct ToolPoint {
    /// The measuring point (1-based).
    pub point: usize,
    /// The setup's value, flange frame: m, written in mm.
    #[serde(rename = "setup_mm", serialize_with = "units::mm3")]
    #[cfg_attr(feature = "schema", schemars(with = "[f64; 3]"))]
    pub setup: Vector3<f64>,
    /// The fitted value, flange frame: m, written in mm.
    #[serde(rename = "fitted_mm", serialize_with = "units::mm3")]
    #[cfg_attr(feature = "schema", schemars(with = "[f64; 3]"))]
    pub fitted: Vector3<f64>,
    /// Fitted minus setup: m, written in mm.
    #[serde(rename = "shift_mm", serialize_with = "units::mm3")]
    #[cfg_attr(feature = "schema", schemars(with = "[f64; 3]"))]
    pub shift: Vector3<f64>,
    /// Standard deviation of the fitted coordinates: m, written in mm; `null` for a point never
    /// read.
    #[serde(rename = "std_mm", serialize_with = "units::mm3_option")]
    #[cfg_attr(feature = "schema", schemars(with = "Option<[f64; 3]>"))]
    pub std: Option<Vector3<f64>>,
}

/// The calibrate-cell job's report, which is its document.
pub(crate) type Outcome = crate::app::Outcome<Report>;

/// Runs the calibrate job.
///
/// # Errors
/// Those of [`read`]; of [`cell_calibration::observations`] and [`cell_calibration::fit`] (readings in the base
/// frame, too few readings for the unknowns, one flange orientation), as
/// [`stiffid_core::Error::Input`] naming the file; unless [`Request::force`], readings that are a
/// mirror image (of the nominal robot's points) or leave a residual beyond
/// [`stiffid_metrology::register::residual_limit`], naming the reading.
pub fn run(request: &Request<'_>) -> Result<Outcome> {
    Ok(Outcome {
        report: find(request)?,
        document: crate::app::Itself,
    })
}

/// The report of `fit` from `readings` unloaded readings, the setup's measuring points
/// `setup_points` (flange frame, m).
fn report(
    request: &Request<'_>,
    fit: Calibration,
    setup_points: &[Vector3<f64>],
    readings: usize,
    warnings: Vec<Warning>,
) -> Report {
    let points: Vec<ToolPoint> = (setup_points.iter().enumerate())
        .map(|(k, setup)| ToolPoint {
            point: k + 1,
            setup: *setup,
            fitted: fit.points[k],
            shift: fit.shifts[k],
            std: fit.point_std[k],
        })
        .collect();
    let transform = Transform::new(&fit.base_from_tracker, fit.transform_std);
    let list = |v: [f64; 3]| format!("[{:.6}, {:.6}, {:.6}]", v[0], v[1], v[2]);
    let measuring: Vec<String> = points.iter().map(|p| list(mm3(&p.fitted))).collect();
    let fragment = format!(
        "# cell calibration from {readings} unloaded readings: unloaded absolute error RMS {:.4} mm\n\
         [tracker]\nbase_from_tracker = {{ xyz_mm = {}, rpy_deg = {} }}\n\
         # in [tool]:\n# measuring_points_mm = [{}]\n",
        crate::app::document::mm(fit.rms),
        list(transform.xyz_mm),
        list(transform.rpy_deg),
        measuring.join(", ")
    );
    Report {
        setup: request.setup_name.clone(),
        data_name: request.name.clone(),
        transform,
        points,
        absolute_error_rms: fit.rms,
        noise_std: fit.sigma,
        readings,
        iterations: fit.iterations,
        stop: fit.stop,
        fragment,
        warnings,
    }
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
    Ok(report(
        request,
        calibration,
        &setup_points,
        observations.len(),
        warnings,
    ))
}
