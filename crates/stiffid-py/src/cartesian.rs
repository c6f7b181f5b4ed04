//! `stiffid.cartesian_compliance` and `stiffid.cartesian_stiffness`: the 6x6 Cartesian compliance
//! and stiffness of a tool point over the setup's model (Salisbury 1980; Zhang et al. 2021, Eq.
//! 4-6), over [`stiffid::internal::observation::cartesian`].

use crate::arrays;
use crate::robot::{point_or, MAX_POSTURES};
use crate::setup::Setup;
use crate::stiffness;
use nalgebra::Matrix6;
use numpy::PyArray3;
use pyo3::prelude::*;
use pyo3::types::PyAny;
use stiffid::internal::observation::cartesian;

/// The Cartesian compliance ``C_x = J diag(h) J^T`` of the tool point ``point_mm`` (flange frame,
/// mm, shape ``(3,)``; default the setup's loading point) in each posture ``q_deg`` (axis angles,
/// deg, shape ``(6,)`` or ``(n, 6)``, within the joint limits): ``[dp; dphi] = C_x [f; m]`` for a
/// wrench ``[f; m]`` (N, Nm) at that point, base frame. ``J`` is the point's Jacobian augmented by
/// the setup's virtual springs, so ``C_x = J_q K^-1 J_q^T + sum_s c_s J_s J_s^T`` over every
/// parameter of the setup's model; ``stiffness_nm_per_rad``: the stiffness of every parameter
/// (shape ``(p,)``: the six drives, Nm/rad, then the virtual springs, Nm/rad or N/mm; or the path
/// of a stiffness JSON file), default the setup's nominal. SI: rows and columns ``[vx, vy, vz,
/// wx, wy, wz]`` and ``[fx, fy, fz, mx, my, mz]``, blocks m/N, m/(N m), rad/N, rad/(N m). Shape
/// ``(6, 6)`` for one posture, ``(n, 6, 6)`` for ``n``; symmetric. Source: Salisbury, "Active
/// stiffness control of a manipulator in Cartesian coordinates", IEEE CDC 1980; docs/model.md.
#[pyfunction]
#[pyo3(signature = (setup, q_deg, *, point_mm=None, stiffness_nm_per_rad=None))]
pub fn cartesian_compliance<'py>(
    py: Python<'py>,
    setup: &Setup,
    q_deg: &Bound<'py, PyAny>,
    point_mm: Option<&Bound<'py, PyAny>>,
    stiffness_nm_per_rad: Option<&Bound<'py, PyAny>>,
) -> PyResult<Py<PyAny>> {
    matrices(
        py,
        setup,
        q_deg,
        point_mm,
        stiffness_nm_per_rad,
        &|s, f, p, h| cartesian::compliance(s.arm(), f, p, h),
    )
}

/// The Cartesian stiffness ``K_x = C_x^-1`` of the tool point ``point_mm`` in each posture
/// ``q_deg``, with the arguments, frames and shapes of ``cartesian_compliance``: ``[f; m] = K_x
/// [dp; dphi]``, blocks N/m, N/rad, (N m)/m, (N m)/rad. For the drives alone computed as ``J^-T K
/// J^-1``, not by inverting ``C_x``. NaN in every entry where ``C_x`` is singular (e.g. a wrist
/// singularity).
#[pyfunction]
#[pyo3(signature = (setup, q_deg, *, point_mm=None, stiffness_nm_per_rad=None))]
pub fn cartesian_stiffness<'py>(
    py: Python<'py>,
    setup: &Setup,
    q_deg: &Bound<'py, PyAny>,
    point_mm: Option<&Bound<'py, PyAny>>,
    stiffness_nm_per_rad: Option<&Bound<'py, PyAny>>,
) -> PyResult<Py<PyAny>> {
    matrices(
        py,
        setup,
        q_deg,
        point_mm,
        stiffness_nm_per_rad,
        &|s, f, p, h| {
            cartesian::stiffness(s.arm(), f, p, h).unwrap_or(Matrix6::from_element(f64::NAN))
        },
    )
}

/// A 6x6 matrix of the setup, a posture's frames, the point (m) and the compliance.
type Of = dyn Fn(
        &stiffid::Setup,
        &stiffid::Frames,
        &nalgebra::Vector3<f64>,
        &nalgebra::DVector<f64>,
    ) -> Matrix6<f64>
    + Sync;

/// `of` in each posture, `(6, 6)` for one, `(n, 6, 6)` for many, the GIL released.
fn matrices<'py>(
    py: Python<'py>,
    setup: &Setup,
    q_deg: &Bound<'py, PyAny>,
    point_mm: Option<&Bound<'py, PyAny>>,
    stiffness_nm_per_rad: Option<&Bound<'py, PyAny>>,
    of: &Of,
) -> PyResult<Py<PyAny>> {
    let s = &setup.inner;
    let within = (s.robot().limits(), "the joint limits");
    let (qs, single) = arrays::postures(q_deg, "q_deg", within, MAX_POSTURES)?;
    let point = point_or(point_mm, s.tool().loading_point)?;
    let what = "stiffness_nm_per_rad";
    let needed_by = "the Cartesian compliance without stiffness_nm_per_rad";
    let h = stiffness::given_or_nominal(s, stiffness_nm_per_rad, what, needed_by)?.h;
    let out: Vec<Matrix6<f64>> = py.detach(|| {
        let robot = s.robot();
        qs.iter()
            .map(|q| of(s, &robot.frames(q), &point, &h))
            .collect()
    });
    let stack: Bound<'py, PyArray3<f64>> =
        arrays::stack::<6>(py, out.len(), |k, r, c| out[k][(r, c)]);
    crate::robot::shaped(stack, single)
}
