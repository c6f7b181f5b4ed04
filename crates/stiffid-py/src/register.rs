//! `stiffid.register` and `stiffid.calibrate_cell`: the tracker's transform from raw readings
//! ([`stiffid::jobs::register`]) and the transform with the measuring points fitted together
//! ([`stiffid::jobs::calibrate`]), as the command computes them.

use crate::documents::{to_python, warn};
use crate::error::{self, raise};
use crate::setup::Setup;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;
use stiffid::documents::register::{Calibration, Document};
use stiffid::jobs::calibrate as calibrate_job;
use stiffid::jobs::register as register_job;

/// The readings of `path` as a job's request runs on them.
fn with_request<T>(
    setup: &Setup,
    path: PathBuf,
    job: impl FnOnce(&register_job::Request<'_>) -> stiffid::Result<T>,
) -> PyResult<T> {
    let text = error::read(&path)?;
    let request = register_job::Request {
        setup: &setup.inner,
        name: path.display().to_string(),
        text: &text,
    };
    job(&request).map_err(raise)
}

/// Registers the laser tracker to the robot base from ``readings``, a CSV path in the ``stiffid
/// register --data`` format (``posture,point,q1_deg..q6_deg,x_tracker_mm,y_tracker_mm,z_tracker_mm``,
/// one row per posture and measuring point; with load steps only the unloaded readings count):
/// each measuring point through the setup's robot model against the tracker's reading, the
/// least-squares rigid transform (Umeyama, by SVD). Returns the document of ``stiffid register
/// --json``: ``xyz_mm``, ``rpy_deg`` (``base_from_tracker`` as the setup writes it),
/// ``translation_std_mm``, ``rotation_std_deg``, ``residual_rms_mm``, ``noise_std_mm``,
/// ``points`` (each unloaded reading's residual) and ``fragment`` (the ``[tracker]`` text of the
/// setup file). ``InputError`` naming the file, line and column for bad readings, fewer than 3
/// points or points on one line; angles that look like radians raise a ``UserWarning``.
#[pyfunction]
pub fn register<'py>(
    py: Python<'py>,
    setup: &Setup,
    readings: PathBuf,
) -> PyResult<Bound<'py, PyDict>> {
    let report = with_request(setup, readings, |r| py.detach(|| register_job::run(r)))?;
    warn(py, &report.warnings)?;
    to_python(py, &Document::new(&report, setup.inner.name()), &[])
}

/// Calibrates the cell from unloaded ``readings`` (the ``register`` format) of postures that turn
/// the flange: the tracker's transform and every measuring point in the flange frame fitted
/// together (Gauss-Newton over 6 + 3 per point read). Returns the document of ``stiffid
/// calibrate-cell --json``: the transform as for ``register``, ``points`` (each measuring point's
/// ``setup_mm``, ``fitted_mm``, ``shift_mm`` and ``std_mm``, ``None`` for a point never read),
/// ``absolute_error_rms_mm`` (the robot's unloaded absolute error at these postures),
/// ``noise_std_mm``, ``readings``, ``iterations`` and the corrected ``fragment``.
/// ``InputError`` for bad readings or readings that cannot separate the unknowns.
#[pyfunction]
pub fn calibrate_cell<'py>(
    py: Python<'py>,
    setup: &Setup,
    readings: PathBuf,
) -> PyResult<Bound<'py, PyDict>> {
    let report = with_request(setup, readings, |r| py.detach(|| calibrate_job::run(r)))?;
    warn(py, &report.warnings)?;
    to_python(py, &Calibration::new(&report, setup.inner.name()), &[])
}
