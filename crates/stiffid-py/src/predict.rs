//! `stiffid.predict`: the predict job of `stiffid predict` ([`stiffid::app::predict`]).

use crate::arrays;
use crate::documents;
use crate::error::raise;
use crate::setup::Setup;
use nalgebra::{Vector3, Vector6};
use pyo3::prelude::*;
use pyo3::types::{PyAny, PyDict};
use stiffid::app::predict as job;
use stiffid::app::predict::document::Document;
use stiffid::common::limits;
use stiffid::observation::deflection::Frame;
use stiffid::setup::plausibility::radians_in_option;

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
/// stiffness of the loaded point. With a stiffness file that holds held-out residuals
/// (``identify(..., cross_validate=True)``), every displacement's prediction interval at
/// ``level`` (0.5 to 0.999; ``*_interval_mm``).
#[pyfunction]
#[pyo3(signature = (setup, q_deg, wrench, *, at_mm=None, frame="base", stiffness_nm_per_rad=None, compliance_covariance_rad2_per_nm2=None, level=0.95))]
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
    level: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let s = &setup.inner;
    let q = Vector6::from(arrays::vector::<6>(q_deg, "q_deg", &limits::ANGLE_DEG)?);
    let wrench = Vector6::from(arrays::vector::<6>(wrench, "wrench", &limits::WRENCH)?);
    let at = at_mm
        .map(|p| arrays::vector::<3>(p, "at_mm", &limits::LENGTH_MM))
        .transpose()?
        .map(|p| Vector3::from(p) * 1e-3);
    let compliance = match (stiffness_nm_per_rad, compliance_covariance_rad2_per_nm2) {
        (Some(k), cov) => Some(crate::stiffness::compliance(
            s,
            k,
            cov,
            "stiffness_nm_per_rad",
        )?),
        (None, Some(_)) => {
            return Err(crate::error::value(
                "compliance_covariance_rad2_per_nm2: needs stiffness_nm_per_rad beside it",
            ))
        }
        (None, None) => None,
    };
    let q = q.map(f64::to_radians);
    documents::warn(py, &Vec::from_iter(radians_in_option("q_deg", &q)))?;
    let request = job::Request {
        setup: s,
        q,
        wrench,
        frame: frame.parse::<Frame>().map_err(raise)?,
        at,
        compliance,
        level,
    };
    let report = py.detach(|| job::run(request)).map_err(raise)?;
    documents::to_python(py, &Document::new(&report, s.name()), &[])
}
