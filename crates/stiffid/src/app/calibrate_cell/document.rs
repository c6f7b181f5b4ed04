//! The document of the calibrate-cell job ([`crate::app::calibrate_cell`]): `stiffid
//! calibrate-cell --json`, Python's `calibrate_cell(...)`.

use crate::app::calibrate_cell::Report;
use crate::app::document::transform::Transform;
use crate::app::document::{mm, mm3};
use serde::Serialize;

/// The calibrate-cell document: the transform, the measuring points and the robot's unloaded
/// absolute error.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "calibrate-cell")]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("calibrate-cell")))]
pub struct Calibration {
    /// The setup as given.
    pub setup: String,
    /// The readings file.
    pub data: String,
    /// The tracker frame in the robot base frame.
    #[serde(flatten)]
    pub transform: Transform,
    /// Every measuring point of the setup.
    pub points: Vec<ToolPoint>,
    /// RMS of the residual lengths, mm: the robot's unloaded absolute positioning error at these
    /// postures (with the tracker noise).
    pub absolute_error_rms_mm: f64,
    /// Noise per coordinate estimated from the residuals, mm.
    pub noise_std_mm: f64,
    /// Unloaded readings used.
    pub readings: usize,
    /// Levenberg-Marquardt iterations.
    pub iterations: usize,
    /// Why the iterations stopped: `converged`, `stalled`, `damping-exhausted` (a minimum within
    /// rounding) or `iteration-limit` (not converged; a warning says so).
    pub stop_reason: stiffid_core::common::stop::Stop,
    /// The corrected fragment of the setup file.
    pub fragment: String,
}

/// One measuring point: the setup's, the fitted, the shift and its standard deviation.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct ToolPoint {
    /// The measuring point (1-based).
    pub point: usize,
    /// The setup's value, flange frame, mm.
    pub setup_mm: [f64; 3],
    /// The fitted value, flange frame, mm.
    pub fitted_mm: [f64; 3],
    /// Fitted minus setup, mm.
    pub shift_mm: [f64; 3],
    /// Standard deviation of the fitted coordinates, mm; `null` for a point never read.
    pub std_mm: Option<[f64; 3]>,
}

impl Calibration {
    /// The document of `report`, for the setup named `setup_name` (as the user gave it).
    pub fn new(report: &Report, setup_name: &str) -> Self {
        let fit = &report.calibration;
        let points: Vec<ToolPoint> = (0..report.setup_points.len())
            .map(|k| ToolPoint {
                point: k + 1,
                setup_mm: mm3(&report.setup_points[k]),
                fitted_mm: mm3(&fit.points[k]),
                shift_mm: mm3(&fit.shifts[k]),
                std_mm: fit.point_std[k].as_ref().map(mm3),
            })
            .collect();
        let transform = Transform::new(&fit.base_from_tracker, fit.transform_std);
        let list = |v: [f64; 3]| format!("[{:.6}, {:.6}, {:.6}]", v[0], v[1], v[2]);
        let measuring: Vec<String> = points.iter().map(|p| list(p.fitted_mm)).collect();
        let fragment = format!(
            "# cell calibration from {} unloaded readings: unloaded absolute error RMS {:.4} mm\n\
             [tracker]\nbase_from_tracker = {{ xyz_mm = {}, rpy_deg = {} }}\n\
             # in [tool]:\n# measuring_points_mm = [{}]\n",
            report.readings,
            mm(fit.rms),
            list(transform.xyz_mm),
            list(transform.rpy_deg),
            measuring.join(", ")
        );
        Calibration {
            setup: setup_name.to_string(),
            data: report.data_name.clone(),
            transform,
            points,
            absolute_error_rms_mm: mm(fit.rms),
            noise_std_mm: mm(fit.sigma),
            readings: report.readings,
            iterations: fit.iterations,
            stop_reason: fit.stop,
            fragment,
        }
    }
}
