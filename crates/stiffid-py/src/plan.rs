//! `stiffid.plan`: the measurement plan job ([`stiffid::app::plan`]) whose document `stiffid
//! select --report DIR` writes as `plan.json`.

use crate::arrays::postures;
use crate::documents::{to_python, warn};
use crate::error::raise;
use crate::setup::Setup;
use pyo3::prelude::*;
use pyo3::types::{PyAny, PyDict};
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
/// With external axes, ``external`` (shape ``(n, k)``, mm for a linear axis and deg for a rotary
/// one, the cell's order) says where each posture is read, as the postures file's ``e1_mm``..
/// columns do for the command: the plan works each posture out there and gives its values; it is
/// required then (without it every posture would stand at every axis 0).
/// ``InputError`` for a setup without a nominal stiffness, a robot whose meshes were not found
/// with a ``[cell]``, or ``external`` not one row per posture of values within the axes' travel
/// (or given for a robot without external axes, or left out for one with them); ``ValueError`` for a row of another length.
#[pyfunction]
#[pyo3(signature = (setup, postures_deg, *, criterion="relative-a", target_pct=None, external=None))]
pub fn plan<'py>(
    py: Python<'py>,
    setup: &Setup,
    postures_deg: &Bound<'py, PyAny>,
    criterion: &str,
    target_pct: Option<&Bound<'_, PyAny>>,
    external: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let target_pct = crate::count::real("target_pct", target_pct)?;
    let s = &setup.inner;
    let within = (s.robot().limits(), "the joint limits");
    let (group, _) = postures(postures_deg, "postures_deg", within, job::MAX_POSTURES)?;
    let external = in_si(s, crate::count::real_rows("external", external)?)?;
    let request = Request {
        setup: s,
        criterion: criterion.parse().map_err(raise)?,
        postures: &group,
        target_pct,
        external: &external,
        scene: false,
    };
    let outcome = py.detach(|| job::run(&request)).map_err(raise)?;
    warn(py, &outcome.warnings)?;
    to_python(py, &outcome.report, &[])
}

/// Each row of external values (mm, deg) in SI; rows of another length, or for a robot without
/// external axes, as given (the job refuses them naming `external`).
pub(crate) fn in_si(s: &stiffid::Setup, rows: Vec<Vec<f64>>) -> PyResult<Vec<Vec<f64>>> {
    let Some(axes) = s.robot().external() else {
        return Ok(rows);
    };
    rows.into_iter()
        .enumerate()
        .map(|(i, e)| match e.len() == axes.len() {
            true => Ok(axes.to_si(&e)),
            false => Err(crate::error::value(format!(
                "external[{i}]: expected {} values ({}), got {}",
                axes.len(),
                axes.column_names().join(", "),
                e.len()
            ))),
        })
        .collect()
}
