//! `stiffid.scene`: the 3D scene of a group of postures, a plan, an identification, a
//! calibration or a compensation ([`stiffid::internal::view`]), built by the library as
//! the commands' reports build it, shown inline in Jupyter and written as HTML or glTF binary.

use crate::arrays::postures;
use crate::documents::{json, to_python};
use crate::error::{raise, value};
use crate::setup::Setup;
use nalgebra::Vector6;
use pyo3::prelude::*;
use pyo3::types::{PyAny, PyBytes, PyDict};
use serde_json::Value;
use stiffid::app::plan::{self as job, Request};
use stiffid::internal::view::{glb, page, MAX_POSTURES};

/// The 3D scene of a plan, an identification, a calibration or a compensation
/// (``stiffid.scene``): the robot at each posture in the cell, the tracker's lines of sight, the
/// rope, the compliance ellipsoids, the displacements or errors and the path, as ``select
/// --report``, ``identify --report``, ``calibrate --report`` and ``compensate --report`` show it
/// in their pages and write it as ``.glb``.
#[pyclass(frozen, module = "stiffid", name = "Scene")]
pub struct Scene {
    inner: stiffid::internal::view::Scene,
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

/// The 3D scene of ``setup``'s robot in its cell at the postures ``postures_deg`` (axis angles,
/// deg, shape ``(n, 6)``, within the joint limits; 1 to 500), with its links named as the URDF
/// names them, the cell, the tracker's lines of sight with their margins and the rope, and what
/// ``document`` adds:
///
/// - ``None``: the plan's (:func:`plan`) nominal compliance ellipsoid at the tool centre point
///   under the load and each measuring point's expected displacement (``plan.html``);
/// - a plan (the dict :func:`plan` returns): the same for its postures (``postures_deg`` left
///   out);
/// - an identification (the dict :func:`identify` returns, the drives or a model, not the model
///   comparison): each measuring point's measured and predicted displacement (the document's
///   ``residuals``), the identified compliance's ellipsoid under the load, as ``identify
///   --report`` draws it; ``postures_deg`` the ``q_deg`` given to :func:`identify` (one row per
///   measurement), or one row per posture in the order the residuals first name them (for a
///   measurement file);
/// - a calibration (the dict :func:`calibrate` returns; ``postures_deg`` left out): the robot at
///   each fitted posture of the document's ``postures`` (with external axes, the track and the
///   positioner at its values), each measuring point's error before and after the calibration,
///   as ``calibrate --report`` draws it;
/// - a compensation (the ``document`` of the dict :func:`compensate` returns; ``postures_deg``
///   left out): the robot
///   at the path's first point and at its largest deflection (at their external values), the
///   sampled path coloured by its predicted error (the document's ``summary.scene``), as
///   ``compensate --report`` draws it; ``InputError`` for an empty path.
///
/// The document's ``kind`` says which it is. ``InputError`` for a setup without a nominal
/// stiffness (plans), a posture count out of range or not the document's, postures given with a
/// document that holds its own, or another document.
#[pyfunction]
#[pyo3(signature = (setup, postures_deg=None, *, document=None))]
pub fn scene(
    py: Python<'_>,
    setup: &Setup,
    postures_deg: Option<&Bound<'_, PyAny>>,
    document: Option<&Bound<'_, PyAny>>,
) -> PyResult<Scene> {
    let s = &setup.inner;
    let doc = document.map(json).transpose()?;
    let given = |what: Option<&Bound<'_, PyAny>>| {
        let within = (s.robot().limits(), "the joint limits");
        let Some(p) = what else {
            return Err(value("postures_deg: expected the postures (n, 6), deg"));
        };
        postures(p, "postures_deg", within, MAX_POSTURES).map(|(g, _)| g)
    };
    let kind = (doc.as_ref()).and_then(|d| d.get("kind")?.as_str().map(str::to_string));
    let kind = kind.unwrap_or_default();
    let inner = match doc {
        None => plan_scene(py, s, &given(postures_deg)?, &[])?,
        Some(d) if kind == "identify-drives" || kind == "identify-springs" => {
            let group = given(postures_deg)?;
            let text = d.to_string();
            py.detach(|| stiffid::app::identify::document::scene::scene(s, &group, &[], &text))
                .map_err(raise)?
        }
        Some(_) if postures_deg.is_some() && own(&kind) => {
            return Err(value("postures_deg: the document's postures are its own"));
        }
        Some(d) if kind == "plan" => {
            plan_scene(py, s, &plan_postures(&d, s)?, &plan_external(s, &d)?)?
        }
        Some(d) if kind == "calibrate" => {
            let text = d.to_string();
            py.detach(|| stiffid::app::calibrate::scene::scene(s, &text))
                .map_err(raise)?
        }
        Some(d) if kind == "compensate" => {
            let text = d.to_string();
            py.detach(|| stiffid::app::compensate::scene::of_document(s, &text))
                .map_err(raise)?
                .ok_or_else(|| value("document: the compensation's path is empty: no scene"))?
        }
        Some(_) => {
            return Err(value(format!(
                "document: its `kind` is {kind:?}; expected a plan, an identification, a calibration or a compensation (the dict stiffid.plan, stiffid.identify, stiffid.calibrate or stiffid.compensate returns as its document)",
            )))
        }
    };
    Ok(Scene { inner })
}

/// Whether a document of `kind` holds its own postures: a plan, a calibration or a compensation.
fn own(kind: &str) -> bool {
    matches!(kind, "plan" | "calibrate" | "compensate")
}

/// The plan's scene of `group` ([`job::Outcome::scene`]) at the external values `external`
/// (SI, one row per posture; empty: every axis at 0).
fn plan_scene(
    py: Python<'_>,
    s: &stiffid::Setup,
    group: &[Vector6<f64>],
    external: &[Vec<f64>],
) -> PyResult<stiffid::internal::view::Scene> {
    let request = Request {
        setup: s,
        criterion: stiffid::internal::design::Criterion::RelativeA,
        postures: group,
        target_pct: None,
        external,
        scene: true,
    };
    let outcome = py.detach(|| job::run(&request)).map_err(raise)?;
    outcome
        .scene
        .ok_or_else(|| value("the plan job returned no scene"))
}

/// A plan document's external values (`postures[].e1_mm`, .., the cell's columns), SI; empty
/// for a robot without external axes or a plan without them.
fn plan_external(s: &stiffid::Setup, d: &Value) -> PyResult<Vec<Vec<f64>>> {
    let Some(axes) = s.robot().external() else {
        return Ok(Vec::new());
    };
    let columns = axes.column_names();
    let list = d["postures"].as_array().into_iter().flatten();
    let rows: Vec<Option<Vec<f64>>> = list
        .map(|p| columns.iter().map(|c| p[c.as_str()].as_f64()).collect())
        .collect();
    match rows.iter().all(Option::is_none) {
        true => Ok(Vec::new()),
        false => {
            let rows = rows.into_iter().enumerate().map(|(i, r)| {
                r.ok_or_else(|| {
                    value(format!(
                        "document: postures[{i}]: expected the values {}",
                        columns.join(", ")
                    ))
                })
            });
            crate::plan::in_si(s, rows.collect::<PyResult<_>>()?)
        }
    }
}

/// A plan document's postures (`postures[].q_deg`), rad, drawn on `setup`: an `InputError`
/// naming `setup` for a plan of another robot, `document` for a plan without postures.
pub(crate) fn plan_postures(d: &Value, setup: &stiffid::Setup) -> PyResult<Vec<Vector6<f64>>> {
    let robot = setup.robot().name();
    if let Some(theirs) = d["robot"].as_str().filter(|r| *r != robot) {
        return Err(value(format!(
            "setup: the plan is of the robot '{}', this setup's is '{robot}': give the plan's setup",
            stiffid::internal::common::limits::short(theirs)
        )));
    }
    let list = d["postures"].as_array().filter(|l| !l.is_empty());
    let list = list.ok_or_else(|| value("document: a plan without postures (its `postures`)"))?;
    list.iter()
        .enumerate()
        .map(|(i, p)| {
            let q: Option<Vec<f64>> =
                (p["q_deg"].as_array()).map(|a| a.iter().filter_map(Value::as_f64).collect());
            match q {
                Some(q) if q.len() == 6 => {
                    Ok(Vector6::from_iterator(q.iter().map(|v| v.to_radians())))
                }
                _ => Err(value(format!(
                    "document: postures[{i}].q_deg: expected 6 numbers"
                ))),
            }
        })
        .collect()
}
