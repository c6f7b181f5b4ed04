//! `stiffid.register` and `stiffid.calibrate_cell`: the tracker's transform from raw readings
//! ([`stiffid::app::register`]) and the transform with the measuring points fitted together
//! ([`stiffid::app::calibrate_cell`]), as the command computes them; the postures to register in
//! ([`stiffid::app::register::propose`]).

use crate::count;
use crate::documents::{to_python, warn};
use crate::error::{self, raise};
use crate::setup::Setup;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;
use stiffid::app::calibrate_cell as calibrate_job;
use stiffid::app::register as register_job;
use stiffid::internal::design::registration as design;

/// The readings of `path` as a job's request runs on them.
fn with_request<T>(
    setup: &Setup,
    (path, force): (PathBuf, bool),
    job: impl FnOnce(&register_job::Request<'_>) -> stiffid::Result<T>,
) -> PyResult<T> {
    let text = error::read(&path)?;
    let request = register_job::Request {
        setup: &setup.inner,
        setup_name: setup.given.clone(),
        name: path.display().to_string(),
        text: &text,
        force,
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
/// points or points on one line, and, unless ``force=True``, readings no rigid transform
/// explains (a mirror image, a residual beyond the larger of 10 mm and 1000 times the tracker
/// noise); angles that look like radians raise a ``UserWarning``.
///
/// With ``count=N`` instead of ``readings``: proposes the N registration postures (1 to 60)
/// inside the setup's bounds that pass the cell's checks without the load and minimise the
/// predicted standard deviation of the transform's rotation, from ``candidates`` postures drawn
/// with ``seed`` (default 20000) and ``restarts`` exchange runs (default 8). Returns the document
/// of ``stiffid register --count N --json``: ``postures`` (``posture``, ``q_deg``), the
/// predicted ``translation_std_mm``, ``rotation_std_deg`` and ``rotation_std_total_deg``, the
/// ``random_median_rotation_std_total_deg`` of random feasible groups, ``readings_template``
/// (the readings CSV to fill in), ``candidates``, ``feasible``, ``checks``, ``method``,
/// ``evaluations``. ``InputError`` when both or neither of ``readings`` and ``count`` are
/// given, or too few candidates pass the cell's checks, and for ``postures=`` (renamed
/// ``count``; ``postures`` is a postures file everywhere else).
#[pyfunction]
#[pyo3(signature = (setup, readings=None, *, count=None, seed=1, candidates=None, restarts=None, force=false, postures=None))]
#[allow(clippy::too_many_arguments)]
pub fn register<'py>(
    py: Python<'py>,
    setup: &Setup,
    readings: Option<PathBuf>,
    #[pyo3(from_py_with = crate::count::optional_whole)] count: Option<i64>,
    #[pyo3(from_py_with = crate::count::seed_of)] seed: u64,
    #[pyo3(from_py_with = crate::count::optional_whole)] candidates: Option<i64>,
    #[pyo3(from_py_with = crate::count::optional_whole)] restarts: Option<i64>,
    force: bool,
    postures: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    if postures.is_some() {
        return Err(raise(stiffid::Error::InvalidField {
            field: "postures".into(),
            message: "renamed count (the number of registration postures to propose)".into(),
        }));
    }
    let postures = count::optional("count", count)?;
    let candidates = count::optional("candidates", candidates)?;
    let restarts = count::optional("restarts", restarts)?;
    let readings = match (readings, postures) {
        (Some(readings), None) => {
            // The proposal's options (the seed's default is the signature's): readings are
            // registered, nothing is drawn or exchanged.
            let given = [
                ("seed", seed != 1),
                ("candidates", candidates.is_some()),
                ("restarts", restarts.is_some()),
            ];
            if let Some((key, _)) = given.iter().find(|(_, given)| *given) {
                return Err(error::value(format!(
                    "{key}: only with count= (the proposal of registration postures)"
                )));
            }
            readings
        }
        (None, Some(n)) => {
            let defaults = design::Options::default();
            let request = register_job::DesignRequest {
                setup: &setup.inner,
                setup_name: setup.given.clone(),
                postures: n,
                options: design::Options {
                    seed,
                    candidates: candidates.unwrap_or(defaults.candidates),
                    restarts: restarts.unwrap_or(defaults.restarts),
                },
                force,
            };
            let proposed = py
                .detach(|| register_job::propose(&request))
                .map_err(raise)?;
            warn(py, &proposed.warnings)?;
            return to_python(py, proposed.written(), &[]);
        }
        _ => {
            return Err(raise(stiffid::Error::InvalidField {
                field: "readings".into(),
                message: "give the readings to register from, or count=N to propose, not both"
                    .into(),
            }))
        }
    };
    let outcome = with_request(setup, (readings, force), |r| {
        py.detach(|| register_job::run(r))
    })?;
    warn(py, &outcome.warnings)?;
    to_python(py, outcome.written(), &[])
}

/// Calibrates the cell from unloaded ``readings`` (the ``register`` format) of postures that turn
/// the flange: the tracker's transform and every measuring point in the flange frame fitted
/// together (the Levenberg-Marquardt fit of ``calibrate`` over 6 + 3 per point read). Returns the document of ``stiffid
/// calibrate-cell --json``: the transform as for ``register``, ``points`` (each measuring point's
/// ``setup_mm``, ``fitted_mm``, ``shift_mm`` and ``std_mm``, ``None`` for a point never read),
/// ``absolute_error_rms_mm`` (the robot's unloaded absolute error at these postures),
/// ``noise_std_mm``, ``readings``, ``iterations`` and the corrected ``fragment``.
/// ``InputError`` for bad readings or readings that cannot separate the unknowns, and, unless
/// ``force=True``, readings no rigid transform explains (as ``register``).
#[pyfunction]
#[pyo3(signature = (setup, readings, *, force=false))]
pub fn calibrate_cell<'py>(
    py: Python<'py>,
    setup: &Setup,
    readings: PathBuf,
    force: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let outcome = with_request(setup, (readings, force), |r| {
        py.detach(|| calibrate_job::run(r))
    })?;
    warn(py, &outcome.warnings)?;
    to_python(py, outcome.written(), &[])
}
