//! `stiffid.plan`: the measurement plan job ([`stiffid::app::plan`]) whose document `stiffid
//! select --report DIR` writes as `plan.json`.

use crate::arrays::postures;
use crate::documents::{to_python, warn};
use crate::error::raise;
use crate::setup::Setup;
use pyo3::prelude::*;
use pyo3::types::{PyAny, PyBytes, PyDict};
use stiffid::app::document::scene::{glb, page, MAX_POSTURES as MAX_SCENE_POSTURES};
use stiffid::app::plan::document::Document;
use stiffid::app::plan::{self as job, Request};

/// The measurement plan of the group ``postures_deg`` (axis angles, deg, shape ``(n, 6)``, within
/// the joint limits; at most 10000), as chosen by ``criterion`` (named in the plan; default
/// ``"relative-a"``) to reach ``target_pct`` (the predicted deviation rate the group was chosen
/// for, or ``None`` for a group of a given size): what the operator needs to carry the group out
/// in the cell. The plan job of ``stiffid select --report DIR``: returns its document
/// (docs/schemas/plan.schema.json) as a dict, equal to the ``plan.json`` that command writes for
/// the same group: the setup's load, anchor, load steps and bodies, the group's predicted
/// deviation rates at the setup's noise levels (Zhang et al. 2021, Eq. 19), how well it identifies
/// every parameter of the model, and per posture the rope's direction and length from the loading
/// point to the anchor, the loading point's height, the expected displacement of every measuring
/// point under the load with the nominal stiffness (Eq. 3-7), the cell's checks, and each joint's
/// predicted deviation rate if that posture could not be measured (leave-one-out).
/// ``InputError`` for a setup without a nominal stiffness, or a robot whose meshes were not found
/// with a ``[cell]``.
#[pyfunction]
#[pyo3(signature = (setup, postures_deg, *, criterion="relative-a", target_pct=None))]
pub fn plan<'py>(
    py: Python<'py>,
    setup: &Setup,
    postures_deg: &Bound<'py, PyAny>,
    criterion: &str,
    target_pct: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let s = &setup.inner;
    let within = (s.robot().limits(), "the joint limits");
    let (group, _) = postures(postures_deg, "postures_deg", within, job::MAX_POSTURES)?;
    let request = Request {
        setup: s,
        criterion: criterion.parse().map_err(raise)?,
        postures: &group,
        target_pct,
    };
    let report = py.detach(|| job::run(&request)).map_err(raise)?;
    warn(py, &report.warnings)?;
    to_python(py, &Document::new(&report, s), &[])
}

/// The 3D scene of a plan (``stiffid.scene``): the robot at each posture in the cell, the
/// tracker's lines of sight, the rope, the compliance ellipsoids and the expected displacements,
/// as ``select --report`` shows it in ``plan.html`` and writes it as ``plan.glb``.
#[pyclass(frozen, module = "stiffid", name = "Scene")]
pub struct Scene {
    inner: stiffid::app::document::scene::Scene,
}

#[pymethods]
impl Scene {
    /// The scene's data as a dict (SI: metres and newtons, the unit in every key).
    fn document<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        to_python(py, &self.inner, &[])
    }

    /// A self-contained HTML page of the scene titled ``title`` (opens offline).
    #[pyo3(signature = (title="stiffid scene"))]
    fn html(&self, title: &str) -> String {
        page::page(&self.inner, title)
    }

    /// The scene as glTF binary (``.glb``) bytes.
    fn glb<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        PyBytes::new(py, &glb::glb(&self.inner))
    }

    /// The page in an ``<iframe srcdoc>``, as Jupyter shows it inline.
    fn _repr_html_(&self) -> String {
        let page = page::page(&self.inner, &self.inner.setup);
        format!(
            "<iframe srcdoc=\"{}\" style=\"width: 100%; height: 800px; border: none\"></iframe>",
            page::escape(&page)
        )
    }
}

/// The 3D scene of the group ``postures_deg`` (axis angles, deg, shape ``(n, 6)``, within the
/// joint limits; 1 to 500): the plan's (:func:`plan`) robot in each posture with its links named
/// as the URDF names them, the cell, the tracker's lines of sight with their margins, the rope,
/// the nominal compliance ellipsoid at the tool centre point under the load and each measuring
/// point's expected displacement. ``InputError`` for a setup without a nominal stiffness or a
/// posture count out of range.
#[pyfunction]
#[pyo3(signature = (setup, postures_deg))]
pub fn scene(py: Python<'_>, setup: &Setup, postures_deg: &Bound<'_, PyAny>) -> PyResult<Scene> {
    let s = &setup.inner;
    let within = (s.robot().limits(), "the joint limits");
    let (group, _) = postures(postures_deg, "postures_deg", within, MAX_SCENE_POSTURES)?;
    let request = Request {
        setup: s,
        criterion: stiffid::design::Criterion::RelativeA,
        postures: &group,
        target_pct: None,
    };
    let inner = py
        .detach(|| job::run(&request).and_then(|r| job::document::scene(&r, s)))
        .map_err(raise)?;
    Ok(Scene { inner })
}
