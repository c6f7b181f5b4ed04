//! `stiffid.deflection`: the deflection of a tool point under a wrench, and its uncertainty
//! (Zhang et al. 2021, Eq. 4-6), over [`stiffid::observation::deflection`].

use crate::arrays::{self, rows};
use crate::error::{raise, value};
use crate::setup::Setup;
use crate::stiffness;
use nalgebra::{DVector, Vector3, Vector6};
use pyo3::prelude::*;
use pyo3::types::{PyAny, PyDict};
use stiffid::common::limits;
use stiffid::observation::deflection::{base_wrench, Frame, Points};

/// The deflection of a tool point in each posture ``q_deg`` (shape ``(6,)`` or ``(n, 6)``, deg,
/// within the joint limits) under ``wrench`` (``[fx, fy, fz, mx, my, mz]``, N and Nm, shape
/// ``(6,)`` for every posture or ``(n, 6)``; in ``frame`` ``"base"`` or ``"tool"``) acting at
/// ``loaded_mm`` (flange frame, mm; default the setup's loading point), observed at
/// ``observed_mm`` (default the loaded point), with the stiffness ``stiffness_nm_per_rad`` of
/// every parameter of the setup's model (shape ``(p,)``: the six drives, Nm/rad, then the virtual
/// springs, Nm/rad or N/mm; or the path of a stiffness JSON file; default the setup's nominal).
/// ``tau = J_a^T W`` (Eq. 4), ``dq = h .* tau`` (Eq. 5), ``[dp; dphi] = J_b dq`` (Eq. 6), the
/// Jacobians augmented by the virtual springs' columns. Returns a dict of arrays with one row per
/// posture: ``displacement_mm`` (``(n, 3)``, base frame), ``rotation_rad`` (``(n, 3)``),
/// ``torques_nm`` and ``joint_deflections_rad`` (``(n, p)``: the drives in the springs'
/// coordinates, then each virtual spring's load, Nm or N, and deflection, rad or m) and, given
/// ``compliance_covariance_rad2_per_nm2`` (``(p, p)``, SI, as ``Identification`` has it, or in the
/// stiffness file),
/// ``displacement_std_mm`` and ``rotation_std_rad`` (``(n, 3)``: exact first-order propagation).
#[pyfunction]
#[pyo3(signature = (setup, q_deg, wrench, *, loaded_mm=None, observed_mm=None, stiffness_nm_per_rad=None, frame="base", compliance_covariance_rad2_per_nm2=None))]
#[allow(clippy::too_many_arguments)]
pub fn deflection<'py>(
    py: Python<'py>,
    setup: &Setup,
    q_deg: &Bound<'py, PyAny>,
    wrench: &Bound<'py, PyAny>,
    loaded_mm: Option<&Bound<'py, PyAny>>,
    observed_mm: Option<&Bound<'py, PyAny>>,
    stiffness_nm_per_rad: Option<&Bound<'py, PyAny>>,
    frame: &str,
    compliance_covariance_rad2_per_nm2: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let s = &setup.inner;
    let r = &s.robot();
    let within = (r.limits(), "the joint limits");
    let (qs, _) = arrays::postures(q_deg, "q_deg", within, crate::robot::MAX_POSTURES)?;
    let wrenches = per_posture(wrench, qs.len())?;
    let point = |p: Option<&Bound<'py, PyAny>>, default: Vector3<f64>, what: &str| {
        p.map_or(Ok::<_, PyErr>(default), |p| {
            Ok(Vector3::from(arrays::vector::<3>(p, what, &limits::LENGTH_MM)?) * 1e-3)
        })
    };
    let loaded = point(loaded_mm, s.tool().loading_point, "loaded_mm")?;
    let observed = point(observed_mm, loaded, "observed_mm")?;
    let compliance = match stiffness_nm_per_rad {
        None => {
            let mut c = s
                .model_compliance("deflection without stiffness_nm_per_rad")
                .map_err(raise)?;
            if let Some(cov) = compliance_covariance_rad2_per_nm2 {
                c.covariance = Some(stiffness::covariance_of(cov, c.len())?);
            }
            c
        }
        Some(k) => stiffness::compliance(
            s,
            k,
            compliance_covariance_rad2_per_nm2,
            "stiffness_nm_per_rad",
        )?,
    };
    let h = &compliance.h;
    let frame = frame.parse::<Frame>().map_err(raise)?;
    let covariance = &compliance.covariance;
    let results: Vec<_> = py.detach(|| {
        qs.iter()
            .zip(&wrenches)
            .map(|(q, w)| {
                let frames = r.frames(q);
                let points = Points {
                    setup: s,
                    frames: &frames,
                    loaded: &loaded,
                    observed: &observed,
                };
                let d = points.deflection(&base_wrench(&frames, w, frame), h);
                let std = covariance.as_ref().map(|c| d.std(c));
                (d, std)
            })
            .collect()
    });
    let out = PyDict::new(py);
    let part = |v: &Vector6<f64>, from: usize, scale: f64| -> [f64; 3] {
        std::array::from_fn(|i| v[from + i] * scale)
    };
    let table3 = |f: &dyn Fn(usize) -> [f64; 3]| {
        let t: Vec<[f64; 3]> = (0..results.len()).map(f).collect();
        arrays::table(py, &t)
    };
    let table = |f: &dyn Fn(usize) -> DVector<f64>| {
        let t: Vec<Vec<f64>> = (0..results.len())
            .map(|i| f(i).as_slice().to_vec())
            .collect();
        arrays::table_n(py, &t, compliance.len())
    };
    out.set_item(
        "displacement_mm",
        table3(&|i| part(&results[i].0.displacement, 0, 1e3)),
    )?;
    out.set_item(
        "rotation_rad",
        table3(&|i| part(&results[i].0.displacement, 3, 1.0)),
    )?;
    out.set_item("torques_nm", table(&|i| results[i].0.torques.clone()))?;
    out.set_item(
        "joint_deflections_rad",
        table(&|i| results[i].0.joint_deflections.clone()),
    )?;
    if covariance.is_some() {
        let std = |i: usize| results[i].1.unwrap_or_default();
        out.set_item("displacement_std_mm", table3(&|i| part(&std(i), 0, 1e3)))?;
        out.set_item("rotation_std_rad", table3(&|i| part(&std(i), 3, 1.0)))?;
    }
    Ok(out)
}

/// One wrench per posture: shape (6,) for all, or (n, 6).
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
