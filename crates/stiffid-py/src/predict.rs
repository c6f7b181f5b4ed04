//! `stiffid.predict` and `stiffid.deflection`: the predict job of `stiffid predict`
//! ([`stiffid::app::predict`]), for one posture or for each of many.

use crate::arrays::{self, rows};
use crate::documents;
use crate::error::{raise, raise_in, value};
use crate::setup::Setup;
use nalgebra::{Vector3, Vector6};
use pyo3::prelude::*;
use pyo3::types::{PyAny, PyDict, PyList};
use stiffid::app::predict as job;
use stiffid::internal::common::limits;
use stiffid::internal::model::Compliance;
use stiffid::internal::observation::deflection::Frame;
use stiffid::internal::setup::plausibility::radians_in_option;

/// The forward model (Zhang et al. 2021, Eq. 3-7) of one posture ``q_deg`` (shape ``(6,)``, deg,
/// within the joint limits) under ``wrench`` (``[fx, fy, fz, mx, my, mz]``, N and Nm, in
/// ``frame`` ``"base"`` or ``"tool"``) acting at ``at_mm`` (flange frame, mm; default the setup's
/// loading point), with the stiffness ``stiffness_nm_per_rad`` of every parameter of the setup's
/// model (shape ``(p,)``, or the path of a stiffness JSON file, whose covariance is used; default
/// the setup's nominal) and ``compliance_covariance_rad2_per_nm2`` (``(p, p)``, SI) beside it.
/// The predict job of ``stiffid predict``: returns its document
/// (docs/schemas/predict.schema.json) as a dict, equal to ``stiffid predict --json``: drive
/// torques and deflections, every measuring point's and the TCP's displacement (``*_std_*``
/// standard deviations with a covariance, else ``None``), and the Cartesian compliance and
/// stiffness of the loaded point; where the robot gives its masses (a robot file's ``mass_kg``,
/// ``com_mm``, ``inertia_kg_m2``, a URDF's ``<inertial>``; the tool's from the setup), the
/// natural frequencies and mode shapes of the posture, the effective mass along the wrench's
/// force (held in the other five directions) and the breakthrough surge ``surge_mm_s``
/// (placeholder masses warned about, ``UserWarning``). With a stiffness file that holds held-out residuals
/// (``identify(..., cross_validate=True)``), every displacement's prediction interval at
/// ``level`` (0.5 to 0.999; ``*_interval_mm``).
#[pyfunction]
#[pyo3(signature = (setup, q_deg, wrench, *, at_mm=None, frame="base", stiffness_nm_per_rad=None, compliance_covariance_rad2_per_nm2=None, level=None))]
#[allow(clippy::too_many_arguments)]
pub fn predict<'py>(
    py: Python<'py>,
    setup: &Setup,
    q_deg: &Bound<'py, PyAny>,
    wrench: &Bound<'py, PyAny>,
    at_mm: Option<&Bound<'py, PyAny>>,
    frame: &str,
    stiffness_nm_per_rad: Option<&Bound<'py, PyAny>>,
    compliance_covariance_rad2_per_nm2: Option<&Bound<'py, PyAny>>,
    level: Option<&Bound<'_, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let level = crate::count::real("level", level)?;
    let q = arrays::vector::<6>(q_deg, "q_deg", &limits::ANGLE_DEG)?;
    let wrench = arrays::vector::<6>(wrench, "wrench", &limits::WRENCH)?;
    let options = Options::new(
        setup,
        at_mm,
        frame,
        stiffness_nm_per_rad,
        compliance_covariance_rad2_per_nm2,
        level,
    )?;
    let q = q.map(f64::to_radians);
    documents::warn(py, &Vec::from_iter(radians_in_option("q_deg", &q.into())))?;
    let document = py
        .detach(|| options.run(setup, q.into(), wrench.into()))
        .map_err(raise)?;
    documents::warn(py, &document.warnings)?;
    documents::to_python(py, &document, &[])
}

/// [`predict`] for each posture of ``q_deg`` (shape ``(6,)`` or ``(n, 6)``, deg, at most
/// 1 000 000) under ``wrench`` (shape ``(6,)`` for every posture, or ``(n, 6)``, one per
/// posture), with the same options, rules and warnings: a list of the predict documents, one per
/// posture in order, each equal to ``stiffid predict --json`` for its posture. ``tau = J_a^T W``
/// (Eq. 4), ``dq = h .* tau`` (Eq. 5), ``[dp; dphi] = J_b dq`` (Eq. 6), the Jacobians augmented
/// by the virtual springs' columns. A posture's error names it (``posture i: ...``, 0-based).
#[pyfunction]
#[pyo3(signature = (setup, q_deg, wrench, *, at_mm=None, frame="base", stiffness_nm_per_rad=None, compliance_covariance_rad2_per_nm2=None, level=None))]
#[allow(clippy::too_many_arguments)]
pub fn deflection<'py>(
    py: Python<'py>,
    setup: &Setup,
    q_deg: &Bound<'py, PyAny>,
    wrench: &Bound<'py, PyAny>,
    at_mm: Option<&Bound<'py, PyAny>>,
    frame: &str,
    stiffness_nm_per_rad: Option<&Bound<'py, PyAny>>,
    compliance_covariance_rad2_per_nm2: Option<&Bound<'py, PyAny>>,
    level: Option<&Bound<'_, PyAny>>,
) -> PyResult<Bound<'py, PyList>> {
    let level = crate::count::real("level", level)?;
    let max = crate::robot::MAX_POSTURES;
    let qs = rows::<6>(q_deg, "q_deg")?.rows;
    if qs.is_empty() || qs.len() > max {
        let n = qs.len();
        return Err(value(format!(
            "q_deg: expected 1 to {max} postures, got {n}"
        )));
    }
    let wrenches = per_posture(wrench, qs.len())?;
    let options = Options::new(
        setup,
        at_mm,
        frame,
        stiffness_nm_per_rad,
        compliance_covariance_rad2_per_nm2,
        level,
    )?;
    let mut postures = Vec::with_capacity(qs.len());
    for (i, q) in qs.iter().enumerate() {
        let what = format!("q_deg posture {i}");
        limits::check(&what, q, &limits::ANGLE_DEG).map_err(raise)?;
        let q = Vector6::from(q.map(f64::to_radians));
        documents::warn(py, &Vec::from_iter(radians_in_option(&what, &q)))?;
        postures.push(q);
    }
    let documents = py.detach(|| {
        postures
            .iter()
            .zip(&wrenches)
            .enumerate()
            .map(|(i, (q, w))| options.run(setup, *q, *w).map_err(|e| Box::new((i, e))))
            .collect::<Result<Vec<_>, _>>()
    });
    let documents = documents.map_err(|b| raise_in(&format!("posture {}", b.0), b.1))?;
    // Each distinct warning once: the mass model's and a stiffness file without its region are
    // every posture's; a posture outside the region is its own.
    let mut warnings: Vec<stiffid::internal::common::warning::Warning> = Vec::new();
    for w in documents.iter().flat_map(|d| &d.warnings) {
        if !warnings.contains(w) {
            warnings.push(w.clone());
        }
    }
    documents::warn(py, &warnings)?;
    let list = PyList::empty(py);
    for d in &documents {
        list.append(documents::to_python(py, d, &[])?)?;
    }
    Ok(list)
}

/// The options `predict` and `deflection` share, checked.
struct Options {
    at: Option<Vector3<f64>>,
    frame: Frame,
    compliance: Option<Compliance>,
    level: Option<f64>,
}

impl Options {
    fn new(
        setup: &Setup,
        at_mm: Option<&Bound<'_, PyAny>>,
        frame: &str,
        stiffness: Option<&Bound<'_, PyAny>>,
        covariance: Option<&Bound<'_, PyAny>>,
        level: Option<f64>,
    ) -> PyResult<Self> {
        let at = at_mm
            .map(|p| arrays::vector::<3>(p, "at_mm", &limits::LENGTH_MM))
            .transpose()?
            .map(|p| Vector3::from(p) * 1e-3);
        let compliance = match (stiffness, covariance) {
            (Some(k), cov) => Some(crate::stiffness::compliance(
                &setup.inner,
                k,
                cov,
                "stiffness_nm_per_rad",
            )?),
            (None, Some(_)) => {
                return Err(value(
                    "compliance_covariance_rad2_per_nm2: needs stiffness_nm_per_rad beside it",
                ))
            }
            (None, None) => None,
        };
        Ok(Options {
            at,
            frame: frame.parse::<Frame>().map_err(raise)?,
            compliance,
            level,
        })
    }

    /// The predict job's report (its document) of posture `q` (rad) under `wrench`.
    fn run(
        &self,
        setup: &Setup,
        q: Vector6<f64>,
        wrench: Vector6<f64>,
    ) -> stiffid::Result<job::Report> {
        let s = &setup.inner;
        let outcome = job::run(&job::Request {
            setup_name: setup.given.clone(),
            setup: s,
            q,
            wrench,
            frame: self.frame,
            at: self.at,
            compliance: self.compliance.clone(),
            level: self.level,
        })?;
        Ok(outcome.report)
    }
}

/// One wrench per posture: shape (6,) for all, or (n, 6), each within the wrench limits.
fn per_posture(wrench: &Bound<'_, PyAny>, n: usize) -> PyResult<Vec<Vector6<f64>>> {
    let w = rows::<6>(wrench, "wrench")?;
    for (i, row) in w.rows.iter().enumerate() {
        limits::check(&format!("wrench[{i}]"), row, &limits::WRENCH).map_err(raise)?;
    }
    match (w.single, w.rows.len() == n) {
        (true, _) => Ok(vec![Vector6::from(w.rows[0]); n]),
        (false, true) => Ok(w.rows.iter().map(|v| Vector6::from(*v)).collect()),
        (false, false) => Err(value(format!(
            "wrench: expected shape (6,) or ({n}, 6) for the {n} postures, got {} rows",
            w.rows.len()
        ))),
    }
}
