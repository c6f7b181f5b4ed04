//! `stiffid.identify` and `stiffid.validate`: joint stiffness from measured displacements
//! (Zhang et al. 2021, Eq. 10-14) and its check on other measurements (Eq. 22), over
//! [`stiffid::internal::identify`] and [`stiffid::internal::identify::validate`].

use crate::arrays::{self, rows};
use crate::compare;
use crate::count;
use crate::documents;
use crate::error::{self, raise, value};
use crate::setup::Setup;
use nalgebra::{Vector3, Vector6};
use pyo3::prelude::*;
use pyo3::types::{PyAny, PyDict};
use std::fs::File;
use std::path::PathBuf;
use stiffid::app::identify::{self as job, Options, Report, Request};
use stiffid::app::measurements::Data;
use stiffid::app::validate as validation;
use stiffid::internal::identify::Loss;
use stiffid::internal::io::Capped;
use stiffid::internal::observation::Measurement;

/// The job's measurements: a CSV path (the `stiffid identify --data` format, read by the job
/// and turned into the base frame) or the arrays `q_deg` (n, 6), `wrench` (n, 3 | 6: N, Nm, base
/// frame) and `displacement_mm` (n * m, 3: loaded minus unloaded, base frame; posture-major, then
/// measuring points 1..m).
fn job_data(
    setup: &stiffid::Setup,
    measurements: Option<&Bound<'_, PyAny>>,
    arrays: [Option<&Bound<'_, PyAny>>; 3],
    point: Option<Vec<i64>>,
) -> PyResult<Data<Capped<File>>> {
    if point.is_some() && measurements.is_some() {
        return Err(value(
            "point: only with q_deg, wrench and displacement_mm (a measurements file has its own point column)",
        ));
    }
    match (measurements, arrays) {
        (Some(m), [None, None, None]) => {
            let path = m.extract::<PathBuf>().map_err(|_| {
                value(format!("measurements: expected the path of a measurements CSV file (str or os.PathLike), got {}", m.get_type()))
            })?;
            let reader = error::open(&path)?;
            let name = path.display().to_string();
            Ok(Data::File { name, reader })
        }
        (None, [Some(q), Some(w), Some(d)]) => {
            Ok(Data::Measurements(from_arrays(setup, q, w, d, point)?))
        }
        _ => Err(value(
            "give either a measurements CSV path, or q_deg, wrench and displacement_mm",
        )),
    }
}

fn from_arrays(
    setup: &stiffid::Setup,
    q: &Bound<'_, PyAny>,
    w: &Bound<'_, PyAny>,
    d: &Bound<'_, PyAny>,
    point: Option<Vec<i64>>,
) -> PyResult<Vec<Measurement>> {
    let r = &setup.robot();
    let (q, _) = arrays::postures(q, "q_deg", (r.limits(), "the joint limits"), usize::MAX)?;
    let n = q.len();
    let wrench = wrenches(w, n)?;
    let d = rows::<3>(d, "displacement_mm")?.rows;
    let points = measured_points(setup, point)?;
    let m = points.len();
    if d.len() != n * m {
        return Err(value(format!(
            "displacement_mm: expected {} rows, one per posture and measuring point in that order ({n} postures x {m} points{}), got {}",
            n * m,
            match m == setup.tool().measuring_points.len() {
                true => ", all of the setup's; give point=[...] for fewer",
                false => " of point",
            },
            d.len()
        )));
    }
    let measurements = d
        .iter()
        .enumerate()
        .map(|(i, dm)| Measurement {
            posture: i / m,
            point: points[i % m],
            q: q[i / m],
            e: Default::default(),
            wrench: wrench[i / m],
            displacement: Vector3::from(*dm) * 1e-3,
        })
        .collect();
    Ok(measurements)
}

/// The measuring points (0-based) each posture's rows are, in row order: `point` (1-based, as
/// the setup's `measuring_points_mm` and the measurement files number them, each once), else
/// every point of the setup.
fn measured_points(setup: &stiffid::Setup, point: Option<Vec<i64>>) -> PyResult<Vec<usize>> {
    let count = setup.tool().measuring_points.len();
    let Some(given) = point else {
        return Ok((0..count).collect());
    };
    let mut seen = vec![false; count];
    let mut out = Vec::with_capacity(given.len());
    for (i, &p) in given.iter().enumerate() {
        let k = usize::try_from(p)
            .ok()
            .filter(|k| (1..=count).contains(k))
            .ok_or_else(|| {
                value(format!(
                    "point[{i}]: {p} is not a measuring point of the setup (1 to {count})"
                ))
            })?;
        if std::mem::replace(&mut seen[k - 1], true) {
            return Err(value(format!(
                "point[{i}]: measuring point {p} given twice"
            )));
        }
        out.push(k - 1);
    }
    match out.is_empty() {
        true => Err(value("point: expected at least one measuring point")),
        false => Ok(out),
    }
}

/// Wrenches `(n, 3)` (force only) or `(n, 6)` (force and moment), N and Nm.
fn wrenches(w: &Bound<'_, PyAny>, n: usize) -> PyResult<Vec<Vector6<f64>>> {
    let wrong = |got: usize| {
        value(format!(
            "wrench: expected {n} rows (one per posture), got {got}"
        ))
    };
    let six = rows::<6>(w, "wrench");
    let out: Vec<Vector6<f64>> = match six {
        Ok(r) => r.rows.iter().map(|v| Vector6::from(*v)).collect(),
        Err(_) => {
            let r = rows::<3>(w, "wrench")
                .map_err(|_| value("wrench: expected an array of shape (n, 3) or (n, 6): N, Nm"))?;
            r.rows
                .iter()
                .map(|f| Vector6::new(f[0], f[1], f[2], 0.0, 0.0, 0.0))
                .collect()
        }
    };
    match out.len() == n {
        true => Ok(out),
        false => Err(wrong(out.len())),
    }
}

/// The keys of the identify document (the six drives) that Python returns as NumPy arrays.
const ARRAYS: [&str; 8] = [
    "stiffness_nm_per_rad",
    "compliance_rad_per_nm",
    "std_error_nm_per_rad",
    "ci95_nm_per_rad",
    "ci95_from_compliance_nm_per_rad",
    "compliance_std_error_rad_per_nm",
    "compliance_ci95_rad_per_nm",
    "compliance_covariance_rad2_per_nm2",
];

/// The keys of the identify document of a model with virtual springs that Python returns as
/// NumPy arrays.
const MODEL_ARRAYS: [&str; 1] = ["compliance_covariance_si"];

/// Identifies the joint stiffness of ``setup``'s robot (Zhang et al. 2021, Eq. 10-14: least
/// squares by QR) from ``measurements``, a CSV path in the ``stiffid identify --data`` format
/// (``posture,point,q1_deg..q6_deg,fx_n,fy_n,fz_n[,mx_nm,my_nm,mz_nm],dx_mm,dy_mm,dz_mm``), or
/// from the arrays ``q_deg`` (shape ``(n, 6)``, axis angles, deg), ``wrench`` (``(n, 3)`` or
/// ``(n, 6)``: force N and moment Nm at the loading point, base frame) and ``displacement_mm``
/// (``(n * m, 3)``: loaded minus unloaded, base frame, mm; posture by posture, in each posture
/// the setup's m measuring points in order, or the points ``point`` lists: 1-based numbers as in
/// the setup's ``measuring_points_mm``, e.g. ``point=[1, 2, 4]``; any other row count is a
/// ``ValueError`` naming ``displacement_mm``). ``robust="huber"`` or ``"tukey"`` down-weights outliers (IRLS);
/// ``nonnegative=True`` bounds every compliance at >= 0 (Lawson-Hanson); ``cross_validate=True``
/// leaves one posture out at a time (or ``folds=K`` folds), refits and predicts it (key
/// ``cross_validation``). ``measurements`` may also be raw tracker readings under load steps
/// (``posture,point,q1_deg..q6_deg,load_step,fx_n,fy_n,fz_n,x_tracker_mm,y_tracker_mm,z_tracker_mm``,
/// or ``load_n``, or ``x_mm,y_mm,z_mm``): each loaded reading is taken from its point's unloaded
/// one, and the document's ``load_steps`` gives each posture's linearity, zero-load offset and
/// hysteresis; ``offsets=True`` fits an offset per posture and measuring point beside the
/// compliances (key ``offsets``). The same job as ``stiffid identify``: a stiffness that is not physical
/// or far off the setup's nominal (a likely unit mistake: displacements in m, forces in kN)
/// raises a ``UserWarning`` with the command's message. Returns the identify document as a dict,
/// the keys and values of ``stiffid identify --json`` (docs/schemas/identify.schema.json) with
/// the stiffness, compliance, their standard errors, intervals and covariance as NumPy arrays
/// (NaN for ``null``; ``None`` without degrees of freedom): ``stiffness_nm_per_rad``,
/// ``compliance_rad_per_nm``, ``ci95_nm_per_rad`` (``(6, 2)``), ``residuals`` (per
/// measurement: ``posture``, ``point``, ``residual_mm``, ...), ``region``, ... .
/// ``ValueError`` naming the file, line and column (or the measurement) for bad data, and for
/// data that cannot identify every joint.
///
/// Over a setup whose model has virtual springs (``Setup.with_model``, a ``[model]`` table) every
/// parameter is identified (the document of ``stiffid identify --json`` for such a setup:
/// ``parameters`` with name, kind, unit, stiffness in that unit and interval,
/// ``unidentifiable``, ...), with ``compliance_covariance_si`` as a NumPy array; a combination of
/// parameters the data cannot separate raises a ``UserWarning``.
///
/// ``compare_models=True`` chooses the model by the data instead (``stiffid identify
/// --compare-models``): from the setup's model, forward selection of ``candidates`` (names such
/// as ``"tilt3_z"``, ``"bend2_y"``, ``"tool_y"``, ``"lost3"``, a declared spring's, or families
/// ``"tilt"``, ``"bend"``, ``"base"``, ``"tool"``, ``"lost"``, ``"load"``, ``"declared"``; default
/// all of them) on the leave-one-posture-out error, nested in an outer cross-validation. Returns
/// a dict: the command's ``--json`` document (``models``, ``steps``, ``recommended_fit``,
/// ``nested``, ``conclusion``, ``dropped``, ``nonlinear_separation``, ...; the same keys
/// and values), plus ``table`` (the selection path as arrays and names, one entry per model:
/// ``added``, ``springs``, ``parameters``, ``in_sample_explained``, ``held_out_explained``,
/// ``held_out_rms_delta_b_mm``, ``aic``, ``bic``, ``noise_ratio``, ``physical``, ``identified``,
/// ``recommended``; NaN where the document has ``null``) and ``fragment`` (the recommended
/// model as a ``[model]`` fragment for ``Setup.with_model``). ``bootstrap=N`` (1 to 2000)
/// adds the posture bootstrap (``stiffid identify --compare-models --bootstrap N --seed S``):
/// postures drawn with replacement (``seed``, default 1, only with ``bootstrap``; the same result
/// whatever the thread count), the
/// selection redone on each resample; the document's ``bootstrap`` holds how often each
/// parameter is chosen and the spread of its stiffness over the models chosen. Not with
/// ``robust``, ``nonnegative``, ``cross_validate``, ``folds`` or ``offsets``. With
/// ``bootstrap``, ``stiffness_out`` (a new file, never an input) receives the stiffness file of
/// ``stiffid identify --compare-models --bootstrap N --stiffness-out``, byte for byte: the
/// setup's model fitted to every posture with the models the data support and their resampled
/// parameter sets (``model_form``), whose spread ``compensate`` takes as its error budget's
/// model-form part.
#[pyfunction]
#[pyo3(signature = (setup, measurements=None, *, q_deg=None, wrench=None, displacement_mm=None, point=None, robust=None, nonnegative=false, cross_validate=false, folds=None, offsets=false, compare_models=false, candidates=None, bootstrap=None, seed=None, stiffness_out=None))]
#[allow(clippy::too_many_arguments)]
pub fn identify<'py>(
    py: Python<'py>,
    setup: &Setup,
    measurements: Option<&Bound<'py, PyAny>>,
    q_deg: Option<&Bound<'py, PyAny>>,
    wrench: Option<&Bound<'py, PyAny>>,
    displacement_mm: Option<&Bound<'py, PyAny>>,
    point: Option<Vec<i64>>,
    robust: Option<&str>,
    nonnegative: bool,
    cross_validate: bool,
    #[pyo3(from_py_with = crate::count::optional_whole)] folds: Option<i64>,
    offsets: bool,
    compare_models: bool,
    candidates: Option<Vec<String>>,
    #[pyo3(from_py_with = crate::count::optional_whole)] bootstrap: Option<i64>,
    #[pyo3(from_py_with = crate::count::optional_whole)] seed: Option<i64>,
    stiffness_out: Option<PathBuf>,
) -> PyResult<Bound<'py, PyAny>> {
    let folds = count::optional("folds", folds)?;
    let bootstrap = count::optional("bootstrap", bootstrap)?;
    let seed = seed.map(|s| count::seed("seed", s)).transpose()?;
    let options = Options {
        robust: robust.map(str::parse::<Loss>).transpose().map_err(raise)?,
        nonnegative,
        cross_validate,
        folds,
        offsets,
        compare_models,
        candidates,
        bootstrap,
        seed,
    };
    options.check().map_err(raise)?;
    if stiffness_out.is_some() && bootstrap.is_none() {
        return Err(value(
            "stiffness_out: only with compare_models=True and bootstrap=N (the model-form file)",
        ));
    }
    let s = &setup.inner;
    let stiffness_file = stiffness_out
        .map(|p| {
            let mut inputs = setup.files.clone();
            inputs.extend(measurements.and_then(|m| m.extract::<PathBuf>().ok()));
            crate::output::prepare(&p, "stiffness_out", &inputs, &[])
        })
        .transpose()?;
    let data = job_data(s, measurements, [q_deg, wrench, displacement_mm], point)?;
    let request = Request {
        setup: s,
        setup_name: setup.given.clone(),
        data,
        options,
        progress: &(),
    };
    let outcome = py.detach(|| job::run(request)).map_err(raise)?;
    documents::warn(py, outcome.warnings())?;
    let document = match &outcome.report {
        Report::Comparison(r) => {
            if let Some(file) = &stiffness_file {
                let spell = |o: stiffid::internal::common::error::JobOption| o.name().to_string();
                let text = r.stiffness_file_text(s, &spell);
                match text.map_err(raise)? {
                    Some(text) => file.write(text.as_bytes())?,
                    None => return Err(value("stiffness_out: only with bootstrap=N")),
                }
            }
            compare::compare_models(py, r, &r.document())?
        }
        Report::Drives(r) => documents::to_python(py, &r.document(), &ARRAYS)?,
        Report::Springs(r) => documents::to_python(py, &r.document(), &MODEL_ARRAYS)?,
    };
    Ok(document.into_any())
}

/// Validates the stiffness of every parameter of the setup's model (``stiffness_nm_per_rad``: shape
/// ``(p,)``, the six drives in Nm/rad then the virtual springs in Nm/rad or N/mm, or the path of a
/// stiffness JSON file as ``stiffid identify --out`` writes it) on measurements
/// it was not fitted to (Zhang et al. 2021, Eq. 22, Table 7): the measurements as for
/// ``identify``. The validate job of ``stiffid validate``: returns its document
/// (docs/schemas/validate.schema.json) as a dict, ``setup``, ``data`` (the file's name or
/// ``"arrays"``), ``parameters`` (the stiffness validated), ``checks`` (per measurement:
/// ``posture``, ``point``, ``line`` for a file, ``measured_mm``, ``predicted_mm``, base frame,
/// and ``delta_b_mm``, ``|delta_m - delta_c|``), ``mean_delta_b_mm``, ``max_delta_b_mm``,
/// ``rms_delta_b_mm``, ``mean_measured_mm``, ``max_measured_mm``, ``rms_measured_mm`` and
/// ``explained`` (``1 - RMS(delta_b) / RMS(|delta_m|)``); plus the checks as arrays,
/// ``delta_b_mm`` (shape ``(n,)``), ``measured_mm`` and ``predicted_mm`` (``(n, 3)``). With a
/// stiffness file that holds held-out residuals (``identify(..., cross_validate=True)``), each
/// check's ``interval_mm`` and ``prediction_intervals`` (``method``, ``level``, ``coverage``, the
/// share of the measured coordinates inside their intervals) at ``level`` (0.5 to 0.999). The job's
/// warnings (angles that look like radians) are raised as ``UserWarning``.
#[pyfunction]
#[pyo3(signature = (setup, stiffness_nm_per_rad, measurements=None, *, q_deg=None, wrench=None, displacement_mm=None, point=None, level=None))]
#[allow(clippy::too_many_arguments)]
pub fn validate<'py>(
    py: Python<'py>,
    setup: &Setup,
    stiffness_nm_per_rad: &Bound<'py, PyAny>,
    measurements: Option<&Bound<'py, PyAny>>,
    q_deg: Option<&Bound<'py, PyAny>>,
    wrench: Option<&Bound<'py, PyAny>>,
    displacement_mm: Option<&Bound<'py, PyAny>>,
    point: Option<Vec<i64>>,
    level: Option<&Bound<'_, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let level = crate::count::real("level", level)?;
    let s = &setup.inner;
    let compliance =
        crate::stiffness::compliance(s, stiffness_nm_per_rad, None, "stiffness_nm_per_rad")?;
    let data = job_data(s, measurements, [q_deg, wrench, displacement_mm], point)?;
    let request = validation::Request {
        setup_name: setup.given.clone(),
        setup: s,
        compliance: &compliance,
        data,
        level,
    };
    let outcome = py.detach(|| validation::run(request)).map_err(raise)?;
    documents::warn(py, &outcome.warnings)?;
    let d = documents::to_python(py, outcome.written(), &[])?;
    let checks = outcome.document().checks;
    let delta_b = checks.iter().map(|c| c.delta_b_mm);
    d.set_item("delta_b_mm", arrays::vec1(py, delta_b))?;
    let measured: Vec<[f64; 3]> = checks.iter().map(|c| c.measured_mm).collect();
    let predicted: Vec<[f64; 3]> = checks.iter().map(|c| c.predicted_mm).collect();
    d.set_item("measured_mm", arrays::table(py, &measured))?;
    d.set_item("predicted_mm", arrays::table(py, &predicted))?;
    Ok(d)
}
