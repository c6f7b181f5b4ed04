//! `stiffid.compensate`: deflection compensation of a machining path, over
//! [`stiffid::compensate`] (Zhang et al. 2021, Eq. 4-6, with the loaded pose solved by Newton
//! steps; the free tool axis after Caro et al., ICRA 2013, and Xiong et al., RCIM 2019).

use crate::arrays;
use crate::error::{self, raise, raise_in};
use crate::setup::Setup;
use nalgebra::Vector6;
use pyo3::prelude::*;
use pyo3::types::{PyAny, PyDict};
use std::path::PathBuf;
use stiffid::compensate::{Compensated, FreeToolAxis, Options, PathPoint};
use stiffid::deflection::Frame;
use stiffid::formats::path;

/// Compensates the machining path in the CSV file ``path`` (the format of ``stiffid compensate
/// --path``: axis angles ``q1_deg..q6_deg`` or a TCP pose ``x_mm..rz_deg`` per line, and the
/// wrench ``fx_n..mz_nm`` at the TCP, in ``frame`` ``"base"`` or ``"tool"`` unless the file says)
/// with the stiffness ``stiffness`` of every parameter of the setup's model: one number per
/// parameter (the six drives, Nm/rad, then the virtual springs, Nm/rad or N/mm) or the path of a
/// stiffness JSON file as ``stiffid identify --out`` writes it (its covariance, when present,
/// gives the standard deviations). Inverse kinematics starts at ``q0_deg`` (shape
/// ``(6,)``, deg; default the setup's first test posture); ``free_tool_axis=True`` turns each pose
/// about its tool z within ``+-tool_axis_range_deg`` (at most ``max_step_deg`` between points) to
/// the least deflection. Returns a dict of arrays with one row per path point, in path order:
/// ``line`` (the file's line numbers, ``int64``), ``q_deg`` and ``q_compensated_deg``
/// (``(n, 6)``, deg), ``deflection_mm`` and ``deflection_mrad`` (``(n, 3)``, base frame, the TCP
/// under the wrench), ``residual_um`` and ``residual_urad`` (``(n,)``), ``iterations`` (``(n,)``,
/// ``int64``: the Newton steps of the compensation), ``tool_rotation_deg`` (``(n,)``) and, with a
/// covariance, ``deflection_std_mm`` (``(n, 3)``).
/// The values equal ``stiffid compensate``'s.
#[pyfunction]
#[pyo3(signature = (setup, path, stiffness, *, frame="base", q0_deg=None, free_tool_axis=false, max_step_deg=2.0, tool_axis_range_deg=90.0))]
#[allow(clippy::too_many_arguments)]
pub fn compensate<'py>(
    py: Python<'py>,
    setup: &Setup,
    path: PathBuf,
    stiffness: &Bound<'py, PyAny>,
    frame: &str,
    q0_deg: Option<&Bound<'py, PyAny>>,
    free_tool_axis: bool,
    max_step_deg: f64,
    tool_axis_range_deg: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let s = &setup.inner;
    let compliance = crate::stiffness::compliance(s, stiffness, None, "stiffness")?;
    let frame = frame.parse::<Frame>().map_err(raise)?;
    let name = path.display().to_string();
    let points = path::parse(&error::read(&path)?, frame).map_err(|e| raise_in(&name, e))?;
    let mut options = Options::for_setup(s);
    if let Some(q) = q0_deg {
        let r = s.robot();
        let within = (&r.limits, "the joint limits");
        options.q0 = arrays::postures(q, "q0_deg", within, 1)?.0[0];
    }
    if free_tool_axis {
        let free = FreeToolAxis::try_from_degrees(max_step_deg, tool_axis_range_deg);
        options.free_tool_axis = Some(free.map_err(raise)?);
    }
    let results = py
        .detach(|| stiffid::compensate::path(s, &compliance, &points, &options))
        .map_err(|e| raise_in(&name, e))?;
    table(py, &results, &points)
}

/// The per-point results as arrays (see [`compensate`]).
fn table<'py>(
    py: Python<'py>,
    results: &[Compensated],
    points: &[PathPoint],
) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    let column = |f: &dyn Fn(&Compensated) -> f64| arrays::vec1(py, results.iter().map(f));
    let part = |f: &dyn Fn(&Compensated) -> Vector6<f64>, from: usize, scale: f64| {
        let rows: Vec<[f64; 3]> = results
            .iter()
            .map(|c| std::array::from_fn(|i| f(c)[from + i] * scale))
            .collect();
        arrays::table(py, &rows)
    };
    let lines = points.iter().map(|p| p.line);
    out.set_item("line", arrays::integers(py, lines))?;
    let q: Vec<_> = results.iter().map(|c| c.q).collect();
    let qc: Vec<_> = results.iter().map(|c| c.q_compensated).collect();
    out.set_item("q_deg", arrays::degrees(py, &q))?;
    out.set_item("q_compensated_deg", arrays::degrees(py, &qc))?;
    out.set_item("deflection_mm", part(&|c| c.deflection, 0, 1e3))?;
    out.set_item("deflection_mrad", part(&|c| c.deflection, 3, 1e3))?;
    out.set_item("residual_um", column(&|c| c.residual_position * 1e6))?;
    out.set_item("residual_urad", column(&|c| c.residual_rotation * 1e6))?;
    let iterations = results.iter().map(|c| c.iterations as u64);
    out.set_item("iterations", arrays::integers(py, iterations))?;
    out.set_item(
        "tool_rotation_deg",
        column(&|c| c.tool_rotation.to_degrees()),
    )?;
    if results.iter().all(|c| c.deflection_std.is_some()) {
        let std = |c: &Compensated| c.deflection_std.unwrap_or_default();
        out.set_item("deflection_std_mm", part(&std, 0, 1e3))?;
    }
    Ok(out)
}
