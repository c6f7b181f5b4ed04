//! `Robot.inverse_kinematics`: the axis angles that put a tool point at a pose, over
//! [`stiffid::internal::robot::ik`] (damped least squares within the joint limits, continued from a start
//! posture).

use crate::arrays;
use crate::error::{raise, value};
use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3, Vector6};
use numpy::{AllowTypeChange, PyArrayLikeDyn};
use pyo3::prelude::*;
use pyo3::types::{PyAny, PyDict};
use stiffid::internal::common::limits::{self, check_count, Range, IK_TOLERANCE};
use stiffid::internal::robot::ik::{self, Options};
use stiffid::Robot;

/// Most poses of one call.
pub const MAX_POSES: usize = 100_000;

/// How far a given rotation may be from orthonormal (`|R^T R - I|`, entry by entry).
const ORTHONORMAL: f64 = 1e-6;

/// The arguments of `Robot.inverse_kinematics` in the user's units.
pub struct Effort {
    pub position_tolerance_mm: Option<f64>,
    pub rotation_tolerance_deg: Option<f64>,
    pub max_iterations: Option<usize>,
    pub restarts: Option<usize>,
    pub seed: u64,
}

impl Effort {
    /// The library's options, each argument checked against its limit in its own unit.
    fn options(&self) -> PyResult<Options> {
        let d = Options::default();
        let mm = Range::new(IK_TOLERANCE.min * 1e3, IK_TOLERANCE.max * 1e3, "mm");
        let deg = Range::new(
            IK_TOLERANCE.min.to_degrees(),
            IK_TOLERANCE.max.to_degrees(),
            "deg",
        );
        let tolerance = |given: Option<f64>, what: &str, range: &Range, per_si: f64, default| {
            given.map_or(Ok(default), |v| {
                limits::check(what, &[v], range).map_err(raise)?;
                Ok::<_, PyErr>(v / per_si)
            })
        };
        let most = limits::MAX_IK_ITERATIONS as usize;
        let iterations = self.max_iterations.unwrap_or(d.max_iterations);
        check_count("max_iterations", iterations, 1, most).map_err(raise)?;
        let restarts = self.restarts.unwrap_or(d.restarts);
        let most = limits::MAX_IK_RESTARTS as usize;
        check_count("restarts", restarts, 0, most).map_err(raise)?;
        Ok(Options {
            position_tolerance: tolerance(
                self.position_tolerance_mm,
                "position_tolerance_mm",
                &mm,
                1e3,
                d.position_tolerance,
            )?,
            rotation_tolerance: tolerance(
                self.rotation_tolerance_deg,
                "rotation_tolerance_deg",
                &deg,
                1f64.to_degrees(),
                d.rotation_tolerance,
            )?,
            max_iterations: iterations,
            restarts,
            seed: self.seed,
        })
    }
}

/// Solves each pose of `pose_mm` in turn, the first from `q0` (rad), each next from the previous
/// solution; the dict of `Robot.inverse_kinematics`.
pub fn solve<'py>(
    py: Python<'py>,
    robot: &Robot,
    pose_mm: &Bound<'py, PyAny>,
    q0: Vector6<f64>,
    point: Vector3<f64>,
    effort: &Effort,
) -> PyResult<Bound<'py, PyDict>> {
    let options = effort.options()?;
    let (targets, single) = poses(pose_mm)?;
    let (solutions, failure) = py.detach(|| {
        let mut start = q0;
        let mut out = Vec::with_capacity(targets.len());
        for (i, t) in targets.iter().enumerate() {
            match ik::solve(robot, &point, t, &start, &options) {
                Ok(s) => {
                    start = s.q;
                    out.push(s);
                }
                Err(e) => return (out, Some((i, e))),
            }
        }
        (out, None)
    });
    if let Some((i, e)) = failure {
        return Err(match single {
            true => raise(e),
            false => crate::error::raise_in(&format!("pose_mm[{i}]"), e),
        });
    }
    let q: Vec<Vector6<f64>> = solutions.iter().map(|s| s.q).collect();
    let iterations = solutions.iter().map(|s| s.iterations as u64);
    let position = solutions.iter().map(|s| s.position_error * 1e3);
    let rotation = solutions.iter().map(|s| s.rotation_error.to_degrees());
    let items = [
        ("q_deg", arrays::degrees(py, &q).into_any()),
        ("iterations", arrays::integers(py, iterations).into_any()),
        ("position_error_mm", arrays::vec1(py, position).into_any()),
        ("rotation_error_deg", arrays::vec1(py, rotation).into_any()),
    ];
    let d = PyDict::new(py);
    for (key, v) in items {
        match single {
            true => d.set_item(key, v.get_item(0)?)?,
            false => d.set_item(key, v)?,
        }
    }
    Ok(d)
}

/// Homogeneous transforms (translation in mm) of shape `(4, 4)` (one, `true`) or `(n, 4, 4)` as
/// poses in m: finite, a rotation block orthonormal with determinant +1, the last row `[0, 0, 0,
/// 1]`, positions within the length limit.
fn poses(obj: &Bound<'_, PyAny>) -> PyResult<(Vec<Isometry3<f64>>, bool)> {
    let expected = "pose_mm: expected an array of shape (4, 4) or (n, 4, 4) (homogeneous transforms, translation in mm)";
    let array: PyArrayLikeDyn<'_, f64, AllowTypeChange> =
        obj.extract().map_err(|_| value(expected))?;
    let view = array.as_array();
    let (n, single) = match view.shape() {
        [4, 4] => (1, true),
        [n, 4, 4] if (1..=MAX_POSES).contains(n) => (*n, false),
        shape => {
            return Err(value(format!(
                "{expected} with 1 to {MAX_POSES} poses, got shape {shape:?}"
            )))
        }
    };
    let flat: Vec<f64> = view.iter().copied().collect();
    (0..n)
        .map(|k| pose(&flat[16 * k..16 * (k + 1)], k, single))
        .collect::<PyResult<Vec<_>>>()
        .map(|p| (p, single))
}

/// One pose from its 16 numbers (row-major).
fn pose(m: &[f64], k: usize, single: bool) -> PyResult<Isometry3<f64>> {
    let what = match single {
        true => "pose_mm".to_string(),
        false => format!("pose_mm[{k}]"),
    };
    if let Some(i) = m.iter().position(|v| !v.is_finite()) {
        return Err(value(format!(
            "{what}[{}, {}] = {} is not a finite number",
            i / 4,
            i % 4,
            m[i]
        )));
    }
    if m[12..] != [0.0, 0.0, 0.0, 1.0] {
        return Err(value(format!("{what}: the last row must be [0, 0, 0, 1]")));
    }
    let r = Matrix3::from_fn(|i, j| m[4 * i + j]);
    let off = (r.transpose() * r - Matrix3::identity()).amax();
    if off > ORTHONORMAL || r.determinant() <= 0.0 {
        return Err(value(format!(
            "{what}: the upper-left 3x3 block is not a rotation (orthonormal to {ORTHONORMAL:e}, determinant +1)"
        )));
    }
    let t = [m[3], m[7], m[11]];
    limits::check(&format!("{what} translation"), &t, &limits::LENGTH_MM).map_err(raise)?;
    let rotation = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix(&r));
    let translation = Translation3::from(Vector3::from(t) * 1e-3);
    Ok(Isometry3::from_parts(translation, rotation))
}
