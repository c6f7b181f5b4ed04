//! `stiffid.identify` and `stiffid.validate`: joint stiffness from measured displacements
//! (Zhang et al. 2021, Eq. 10-14) and its check on other measurements (Eq. 22), over
//! [`stiffid::identify`] and [`stiffid::validate`].

use crate::arrays::{self, rows};
use crate::error::{self, raise, value};
use crate::setup::Setup;
use nalgebra::{Matrix6, Vector3, Vector6};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyAny, PyDict};
use std::io::BufReader;
use std::path::{Path, PathBuf};
use stiffid::formats::measurements::{self, MeasurementFile};
use stiffid::formats::stiffness;
use stiffid::identify::{Identification as Fit, Loss};
use stiffid::limits;
use stiffid::observation::{Measurement, Observations};

/// Measurements and, when read from a file, the file (to name its lines and columns in errors).
struct Data {
    measurements: Vec<Measurement>,
    /// The file's name and what else it holds (its measurements moved out).
    file: Option<(String, MeasurementFile)>,
}

impl Data {
    /// A library error about these measurements, in the file's terms (line, column) for a file.
    fn error(&self, e: stiffid::Error) -> PyErr {
        match &self.file {
            None => raise(e),
            Some((name, file)) => error::raise_in(name, file.explain(e)),
        }
    }

    fn labels(&self) -> Option<Vec<String>> {
        self.file.as_ref().map(|(_, f)| f.labels.clone())
    }
}

/// Reads the measurements: a CSV path (the `stiffid identify --data` format, turned into the base
/// frame) or the arrays `q_deg` (n, 6), `wrench` (n, 3 | 6: N, Nm, base frame) and
/// `displacement_mm` (n * m, 3: loaded minus unloaded, base frame; posture-major, then measuring
/// points 1..m).
fn data(
    setup: &stiffid::Setup,
    measurements: Option<&Bound<'_, PyAny>>,
    arrays: [Option<&Bound<'_, PyAny>>; 3],
    point: Option<Vec<i64>>,
) -> PyResult<Data> {
    if point.is_some() && measurements.is_some() {
        return Err(value(
            "point: only with q_deg, wrench and displacement_mm (a measurements file has its own point column)",
        ));
    }
    match (measurements, arrays) {
        (Some(m), [None, None, None]) => from_file(setup, m.extract::<PathBuf>()?),
        (None, [Some(q), Some(w), Some(d)]) => from_arrays(setup, q, w, d, point),
        _ => Err(value(
            "give either a measurements CSV path, or q_deg, wrench and displacement_mm",
        )),
    }
}

fn from_file(setup: &stiffid::Setup, path: PathBuf) -> PyResult<Data> {
    let name = path.display().to_string();
    let text = error::read(&path)?;
    let mut file = measurements::parse(&text).map_err(|e| error::raise_in(&name, e))?;
    file.to_base_frame(setup)
        .map_err(|e| error::raise_in(&name, e))?;
    Ok(Data {
        measurements: std::mem::take(&mut file.measurements),
        file: Some((name, file)),
    })
}

fn from_arrays(
    setup: &stiffid::Setup,
    q: &Bound<'_, PyAny>,
    w: &Bound<'_, PyAny>,
    d: &Bound<'_, PyAny>,
    point: Option<Vec<i64>>,
) -> PyResult<Data> {
    let r = &setup.robot();
    let (q, _) = arrays::postures(q, "q_deg", (&r.limits, "the joint limits"), usize::MAX)?;
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
            wrench: wrench[i / m],
            displacement: Vector3::from(*dm) * 1e-3,
        })
        .collect();
    Ok(Data {
        measurements,
        file: None,
    })
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

/// The result of `stiffid.identify`: the joint stiffness and compliance with standard errors and
/// 95% confidence intervals (Student's t with ``degrees_of_freedom``; ``None`` with exactly six
/// rows), the covariance of the compliance, the residuals and the chi-square check of the
/// residuals against the setup's tracker noise. Keys as ``stiffid identify --json``.
#[pyclass(frozen, module = "stiffid", name = "Identification")]
pub struct Identification {
    /// ``"least-squares"``, ``"nonnegative-least-squares"``, ``"huber"`` or ``"tukey"``.
    #[pyo3(get)]
    method: &'static str,
    /// Identified joint stiffness ``k = 1/h``, Nm/rad, shape ``(6,)``.
    #[pyo3(get)]
    stiffness_nm_per_rad: Py<PyArray1<f64>>,
    /// Identified compliance ``h`` (Eq. 8, 14), rad/Nm, shape ``(6,)``.
    #[pyo3(get)]
    compliance_rad_per_nm: Py<PyArray1<f64>>,
    /// Whether each joint's result is physical (finite, positive), shape ``(6,)``.
    #[pyo3(get)]
    physical: Vec<bool>,
    /// Standard error of the stiffness (delta method), Nm/rad, shape ``(6,)``.
    #[pyo3(get)]
    std_error_nm_per_rad: Option<Py<PyArray1<f64>>>,
    /// 95% intervals ``k +- t se(k)``, Nm/rad, shape ``(6, 2)``.
    #[pyo3(get)]
    ci95_nm_per_rad: Option<Py<PyArray2<f64>>>,
    /// 95% intervals mapped from the compliance's, ``[1/h_upper, 1/h_lower]``, Nm/rad, ``(6, 2)``.
    #[pyo3(get)]
    ci95_from_compliance_nm_per_rad: Option<Py<PyArray2<f64>>>,
    /// Standard error of the compliance, rad/Nm, shape ``(6,)``.
    #[pyo3(get)]
    compliance_std_error_rad_per_nm: Option<Py<PyArray1<f64>>>,
    /// 95% intervals of the compliance, rad/Nm, shape ``(6, 2)``.
    #[pyo3(get)]
    compliance_ci95_rad_per_nm: Option<Py<PyArray2<f64>>>,
    /// ``Cov(h) = s^2 (Psi^T Psi)^-1``, (rad/Nm)^2, shape ``(6, 6)``.
    #[pyo3(get)]
    compliance_covariance_rad2_per_nm2: Option<Py<PyArray2<f64>>>,
    /// ``m - 6`` for ``m`` rows.
    #[pyo3(get)]
    degrees_of_freedom: Option<usize>,
    /// The quantile of the 95% intervals.
    #[pyo3(get)]
    t_quantile: Option<f64>,
    /// ``delta - Psi h`` per measurement, mm, shape ``(n, 3)`` (x, y, z, base frame).
    #[pyo3(get)]
    residuals_mm: Py<PyArray2<f64>>,
    /// ``sqrt(|r|^2 / m)``, mm.
    #[pyo3(get)]
    residual_rms_mm: f64,
    /// ``cond_2(Psi)``, SI units.
    #[pyo3(get)]
    cond_psi: f64,
    /// Rows of ``Psi`` (three per measurement).
    #[pyo3(get)]
    rows: usize,
    /// Distinct postures.
    #[pyo3(get)]
    postures: usize,
    /// A file's posture labels, in order of first appearance (None for arrays).
    #[pyo3(get)]
    labels: Option<Vec<String>>,
    /// The residual standard deviation in units of the setup's tracker noise ``s / sigma`` (about 1
    /// for an adequate model).
    #[pyo3(get)]
    noise_ratio: Option<f64>,
    /// ``dof s^2 / sigma^2``, chi-square with ``dof`` degrees of freedom for an adequate model.
    #[pyo3(get)]
    chi2_statistic: Option<f64>,
    /// ``P(X >= chi2_statistic)``: small when the residuals exceed the tracker noise.
    #[pyo3(get)]
    chi2_p_value: Option<f64>,
    /// Whether ``chi2_p_value < 0.01``: the model error dominates the tracker noise.
    #[pyo3(get)]
    model_error_dominates: Option<bool>,
}

#[pymethods]
impl Identification {
    fn __repr__(&self, py: Python<'_>) -> String {
        format!(
            "Identification(method={:?}, stiffness_nm_per_rad={})",
            self.method,
            self.stiffness_nm_per_rad.bind(py)
        )
    }
}

impl Identification {
    fn new(py: Python<'_>, id: &Fit, labels: Option<Vec<String>>, noise_variance: f64) -> Self {
        let u = id.uncertainty.as_ref();
        let a = id.adequacy(noise_variance);
        let v = |x: &Vector6<f64>| arrays::vec1(py, x.iter().copied()).unbind();
        let t = |x: &[[f64; 2]; 6]| arrays::table(py, x).unbind();
        let residuals: Vec<[f64; 3]> = id
            .residuals
            .as_slice()
            .chunks_exact(3)
            .map(|r| [r[0] * 1e3, r[1] * 1e3, r[2] * 1e3])
            .collect();
        Self {
            method: match (&id.robust, id.active_bounds) {
                (Some(fit), _) => fit.loss.name(),
                (None, Some(_)) => "nonnegative-least-squares",
                (None, None) => "least-squares",
            },
            stiffness_nm_per_rad: v(&id.stiffness),
            compliance_rad_per_nm: v(&id.compliance),
            physical: id.physical().to_vec(),
            std_error_nm_per_rad: u.map(|u| v(&u.stiffness_std_error)),
            ci95_nm_per_rad: u.map(|u| t(&u.stiffness_ci95)),
            ci95_from_compliance_nm_per_rad: u.map(|u| t(&u.stiffness_ci95_from_compliance)),
            compliance_std_error_rad_per_nm: u.map(|u| v(&u.compliance_std_error)),
            compliance_ci95_rad_per_nm: u.map(|u| t(&u.compliance_ci95)),
            compliance_covariance_rad2_per_nm2: u
                .map(|u| arrays::matrix6(py, &u.compliance_covariance).unbind()),
            degrees_of_freedom: u.map(|u| u.dof),
            t_quantile: u.map(|u| u.t_quantile),
            residuals_mm: arrays::table(py, &residuals).unbind(),
            residual_rms_mm: id.residual_rms * 1e3,
            cond_psi: id.cond_psi,
            rows: id.rows,
            postures: id.postures,
            labels,
            noise_ratio: a.as_ref().map(|a| a.noise_ratio),
            chi2_statistic: a.as_ref().map(|a| a.chi2),
            chi2_p_value: a.as_ref().map(|a| a.p_value),
            model_error_dominates: a.as_ref().map(|a| a.model_error_dominates()),
        }
    }
}

/// Identifies the joint stiffness of ``setup``'s robot (Zhang et al. 2021, Eq. 10-14: least
/// squares by QR) from ``measurements``, a CSV path in the ``stiffid identify --data`` format
/// (``posture,point,q1_deg..q6_deg,fx_n,fy_n,fz_n[,mx_nm,my_nm,mz_nm],dx_mm,dy_mm,dz_mm``), or
/// from the arrays ``q_deg`` (shape ``(n, 6)``, axis angles, deg), ``wrench`` (``(n, 3)`` or
/// ``(n, 6)``: force N and moment Nm at the loading point, base frame) and ``displacement_mm``
/// (``(n * m, 3)``: loaded minus unloaded, base frame, mm; posture by posture, in each posture
/// the setup's m measuring points in order, or the points ``point`` lists: 1-based numbers as in
/// the setup's ``measuring_points_mm``, e.g. ``point=[1, 2, 4]``; any other row count is a
/// ``ValueError`` naming ``displacement_mm``). ``robust="huber"`` or ``"tukey"`` down-weights outliers (IRLS);
/// ``nonnegative=True`` bounds every compliance at >= 0 (Lawson-Hanson). Returns an
/// ``Identification``. ``ValueError`` naming the file, line and column (or the measurement) for
/// bad data, and for data that cannot identify every joint.
#[pyfunction]
#[pyo3(signature = (setup, measurements=None, *, q_deg=None, wrench=None, displacement_mm=None, point=None, robust=None, nonnegative=false))]
#[allow(clippy::too_many_arguments)]
pub fn identify(
    py: Python<'_>,
    setup: &Setup,
    measurements: Option<&Bound<'_, PyAny>>,
    q_deg: Option<&Bound<'_, PyAny>>,
    wrench: Option<&Bound<'_, PyAny>>,
    displacement_mm: Option<&Bound<'_, PyAny>>,
    point: Option<Vec<i64>>,
    robust: Option<&str>,
    nonnegative: bool,
) -> PyResult<Identification> {
    let s = &setup.inner;
    let loss = robust
        .map(|r| {
            arrays::choice(
                "robust",
                r,
                &[("huber", Loss::Huber), ("tukey", Loss::Tukey)],
            )
        })
        .transpose()?;
    if loss.is_some() && nonnegative {
        return Err(value("robust and nonnegative: choose one"));
    }
    let arrays = [q_deg, wrench, displacement_mm];
    if let (Some(path), None, false, [None, None, None], None) =
        (measurements, loss, nonnegative, arrays, &point)
    {
        return identify_file(py, s, &path.extract::<PathBuf>()?);
    }
    let data = data(s, measurements, arrays, point)?;
    let fit = py.detach(|| {
        let obs = || Observations::from_measurements(s, &data.measurements);
        match (loss, nonnegative) {
            (Some(l), _) => obs()?.robust(l),
            (None, true) => obs()?.nonnegative(),
            // As the command: in blocks, without the whole Psi.
            (None, false) => stiffid::identify::least_squares(s, &data.measurements),
        }
    });
    let fit = fit.map_err(|e| data.error(e))?;
    Ok(Identification::new(
        py,
        &fit,
        data.labels(),
        s.noise().variance,
    ))
}

/// Plain least squares from the measurement file at `path`, of any size: read once in chunks,
/// `Psi` reduced in blocks (as `stiffid identify`, [`stiffid::identify::streamed`]).
fn identify_file(py: Python<'_>, s: &stiffid::Setup, path: &Path) -> PyResult<Identification> {
    let name = path.display().to_string();
    let source = BufReader::new(error::open(path)?);
    let (fit, rows) = py
        .detach(|| stiffid::identify::streamed::least_squares(s, source))
        .map_err(|e| error::raise_in(&name, e))?;
    let labels = rows.labels.iter().map(str::to_string).collect();
    Ok(Identification::new(
        py,
        &fit,
        Some(labels),
        s.noise().variance,
    ))
}

/// Six stiffness values (Nm/rad), or the stiffness of a stiffness JSON file (`stiffid identify
/// --out`) at a path.
fn stiffness(obj: &Bound<'_, PyAny>) -> PyResult<Vector6<f64>> {
    Ok(stiffness_and_covariance(obj)?.0)
}

/// [`stiffness`] and, from a stiffness JSON file that has it, the covariance of the compliance
/// (`compliance_covariance_rad2_per_nm2`, (rad/Nm)^2).
pub fn stiffness_and_covariance(
    obj: &Bound<'_, PyAny>,
) -> PyResult<(Vector6<f64>, Option<Matrix6<f64>>)> {
    if let Ok(path) = obj.extract::<PathBuf>() {
        let name = path.display().to_string();
        let file = stiffness::parse(&error::read(&path)?).map_err(|e| error::raise_in(&name, e))?;
        return Ok((file.stiffness(), file.covariance()));
    }
    let range = &limits::STIFFNESS_NM_PER_RAD;
    let k = arrays::vector::<6>(obj, "stiffness_nm_per_rad", range)?;
    Ok((k.into(), None))
}

/// Validates a joint stiffness (``stiffness_nm_per_rad``: shape ``(6,)``, Nm/rad, or the path of a
/// stiffness JSON file as ``stiffid identify --out`` writes it) on measurements
/// it was not fitted to (Zhang et al. 2021, Eq. 22, Table 7): the measurements as for
/// ``identify``. Returns a dict: ``delta_b_mm`` (shape ``(n,)``: ``|delta_m - delta_c|`` per
/// measurement), ``measured_mm`` and ``predicted_mm`` (``(n, 3)``), ``mean_delta_b_mm``,
/// ``max_delta_b_mm``, ``rms_delta_b_mm``, ``mean_measured_mm``, ``max_measured_mm``,
/// ``rms_measured_mm`` and ``explained`` (``1 - RMS(delta_b) / RMS(|delta_m|)``).
#[pyfunction]
#[pyo3(signature = (setup, stiffness_nm_per_rad, measurements=None, *, q_deg=None, wrench=None, displacement_mm=None, point=None))]
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
) -> PyResult<Bound<'py, PyDict>> {
    let s = &setup.inner;
    let k = stiffness(stiffness_nm_per_rad)?;
    let data = data(s, measurements, [q_deg, wrench, displacement_mm], point)?;
    let v = py
        .detach(|| stiffid::validate::compare(s, &k, &data.measurements))
        .map_err(|e| data.error(e))?;
    let mm = |x: &Vector3<f64>| [x.x * 1e3, x.y * 1e3, x.z * 1e3];
    let d = PyDict::new(py);
    let delta_b = v.checks.iter().map(|c| c.delta_b * 1e3);
    d.set_item("delta_b_mm", arrays::vec1(py, delta_b))?;
    let measured: Vec<[f64; 3]> = v.checks.iter().map(|c| mm(&c.measured)).collect();
    let predicted: Vec<[f64; 3]> = v.checks.iter().map(|c| mm(&c.predicted)).collect();
    d.set_item("measured_mm", arrays::table(py, &measured))?;
    d.set_item("predicted_mm", arrays::table(py, &predicted))?;
    d.set_item("mean_delta_b_mm", v.mean * 1e3)?;
    d.set_item("max_delta_b_mm", v.max * 1e3)?;
    d.set_item("rms_delta_b_mm", v.rms * 1e3)?;
    d.set_item("mean_measured_mm", v.measured[0] * 1e3)?;
    d.set_item("max_measured_mm", v.measured[1] * 1e3)?;
    d.set_item("rms_measured_mm", v.measured[2] * 1e3)?;
    d.set_item("explained", v.explained)?;
    Ok(d)
}
