//! `stiffid.Robot`: an immutable 6-axis robot, its forward kinematics, point Jacobians and the
//! dexterity index.

use crate::arrays;
use crate::error::{self, raise, Failure};
use nalgebra::{Matrix4, Matrix6, Vector3};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyAny;
use std::path::{Path, PathBuf};
use stiffid::formats::postures;
use stiffid::formats::reference;
use stiffid::limits;
use stiffid::robot::presets;
use stiffid::{dexterity, Coordinates};

/// Most postures of one vectorised call (an `(n, 6)` array): 1 000 000.
pub const MAX_POSTURES: usize = 1_000_000;

/// A 6-axis serial robot (immutable). Postures are controller axis angles in degrees, shape
/// ``(6,)`` for one posture or ``(n, 6)`` for many, within the robot's joint limits.
#[pyclass(frozen, module = "stiffid", name = "Robot")]
#[derive(Clone)]
pub struct Robot {
    pub inner: stiffid::Robot,
}

#[pymethods]
impl Robot {
    /// A built-in robot by preset name (see ``Robot.presets()``), e.g.
    /// ``"comau-smart5-nj165-3.0"``. Raises ``ValueError`` for an unknown name.
    #[staticmethod]
    fn preset(name: &str) -> PyResult<Self> {
        Ok(Self {
            inner: presets::get(name).map_err(raise)?,
        })
    }

    /// The names of the built-in robots.
    #[staticmethod]
    fn presets() -> Vec<&'static str> {
        presets::names().collect()
    }

    /// A robot from a robot ``.toml`` file or a ``.urdf`` file (``tip``: the URDF tip link; by
    /// default the only leaf, else the leaf ending six revolute joints, else ``tool0``).
    /// Raises ``FileNotFoundError``/``OSError`` for a file that cannot be read, ``ValueError`` for
    /// its content (the library's message names the file and field).
    #[staticmethod]
    #[pyo3(signature = (path, tip=None))]
    fn from_file(path: PathBuf, tip: Option<&str>) -> PyResult<Self> {
        Ok(Self {
            inner: from_path(&path, tip)?,
        })
    }

    /// Human-readable name, e.g. ``"COMAU SMART5 NJ 165-3.0"``.
    #[getter]
    fn name(&self) -> &str {
        &self.inner.name
    }

    /// Where the numbers come from (datasheet, paper, file and tip link).
    #[getter]
    fn source(&self) -> &str {
        &self.inner.source
    }

    /// Lower joint limits, axis coordinates, deg, shape ``(6,)``.
    #[getter]
    fn lower_limit_deg<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arrays::vec1(py, self.inner.limits.lower.iter().map(|v| v.to_degrees()))
    }

    /// Upper joint limits, axis coordinates, deg, shape ``(6,)``.
    #[getter]
    fn upper_limit_deg<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arrays::vec1(py, self.inner.limits.upper.iter().map(|v| v.to_degrees()))
    }

    /// The flange pose in the base frame as a homogeneous transform, translation in mm:
    /// shape ``(4, 4)`` for ``q_deg`` of shape ``(6,)``, ``(n, 4, 4)`` for ``(n, 6)``.
    fn flange_pose<'py>(&self, py: Python<'py>, q_deg: &Bound<'py, PyAny>) -> PyResult<Py<PyAny>> {
        let (qs, single) = self.postures(q_deg)?;
        let robot = &self.inner;
        let poses: Vec<Matrix4<f64>> = py.detach(|| {
            qs.iter()
                .map(|q| {
                    let mut t = robot.frames(q).flange.to_homogeneous();
                    t.fixed_view_mut::<3, 1>(0, 3).scale_mut(1e3);
                    t
                })
                .collect()
        });
        let out = arrays::stack::<4>(py, poses.len(), |k, r, c| poses[k][(r, c)]);
        shaped(out, single)
    }

    /// The geometric Jacobian of a body point (``point_mm`` in the flange frame, mm; default the
    /// flange origin), base frame, rows ``[vx, vy, vz, wx, wy, wz]`` in m/rad and rad/rad, column
    /// j joint j in ``coordinates`` ``"axis"`` (controller angles q: ``J_q = J_theta M``) or
    /// ``"kinematic"`` (the DH/URDF angles theta). Shape ``(6, 6)`` or ``(n, 6, 6)``.
    /// Source: Zhang et al. 2021, Eq. 4-7; docs/model.md section 2.
    #[pyo3(signature = (q_deg, point_mm=None, coordinates="axis"))]
    fn jacobian<'py>(
        &self,
        py: Python<'py>,
        q_deg: &Bound<'py, PyAny>,
        point_mm: Option<&Bound<'py, PyAny>>,
        coordinates: &str,
    ) -> PyResult<Py<PyAny>> {
        let jacobians = self.jacobians(py, q_deg, point_mm, coordinates)?;
        let (js, single) = jacobians;
        let out = arrays::stack::<6>(py, js.len(), |k, r, c| js[k][(r, c)]);
        shaped(out, single)
    }

    /// The dexterity index ``k(J_N) = (1/6) sqrt(tr(J_N J_N^T) tr((J_N J_N^T)^-1))``,
    /// ``J_N = diag(I/L, I) J`` (Zhang et al. 2021, Eq. 20-21) of the point ``point_mm``
    /// (flange frame, mm; default the flange origin), ``L`` = ``characteristic_length_mm``
    /// (1 to 100000 mm; a setup's ``characteristic_length_mm`` is the one to give; ``None``: the
    /// robot's own, ``Robot.characteristic_length_mm(point_mm)``). 1 is isotropic, larger is
    /// worse, ``inf`` at a singularity. A float for ``q_deg`` of shape ``(6,)``, shape ``(n,)``
    /// for ``(n, 6)``.
    #[pyo3(signature = (q_deg, point_mm=None, characteristic_length_mm=None, coordinates="axis"))]
    fn dexterity<'py>(
        &self,
        py: Python<'py>,
        q_deg: &Bound<'py, PyAny>,
        point_mm: Option<&Bound<'py, PyAny>>,
        characteristic_length_mm: Option<f64>,
        coordinates: &str,
    ) -> PyResult<Py<PyAny>> {
        let length = match characteristic_length_mm {
            Some(l) => {
                let range = &limits::CHARACTERISTIC_LENGTH_MM;
                limits::check("characteristic_length_mm", &[l], range).map_err(raise)?;
                l * 1e-3
            }
            None => self.characteristic_length_mm(py, point_mm)? * 1e-3,
        };
        let (js, single) = self.jacobians(py, q_deg, point_mm, coordinates)?;
        let k: Vec<f64> = js.iter().map(|j| dexterity(j, length)).collect();
        match single {
            true => Ok(k[0].into_pyobject(py)?.into_any().unbind()),
            false => Ok(arrays::vec1(py, k).into_any().unbind()),
        }
    }

    /// The robot's own characteristic length (mm) for the point ``point_mm`` (flange frame, mm;
    /// default the flange origin): the length that minimises the point's median dexterity over
    /// 512 seeded postures within the joint limits (``stiffid::prior``; about 1200 mm for the
    /// paper's COMAU and tool). What ``dexterity`` uses when no length is given; a setup's
    /// ``characteristic_length_mm`` is the one to give where there is a setup. ``ValueError`` for
    /// a robot singular at most postures.
    #[pyo3(signature = (point_mm=None))]
    fn characteristic_length_mm(
        &self,
        py: Python<'_>,
        point_mm: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<f64> {
        let point = point(point_mm)?;
        let robot = &self.inner;
        let l = py.detach(|| stiffid::prior::robot_characteristic_length(robot, &point));
        Ok(l.map_err(raise)? * 1e3)
    }

    /// The postures of a postures CSV file (``posture,q1_deg,...,q6_deg``, as ``stiffid select``
    /// writes them), axis angles in deg, shape ``(n, 6)``, each within the joint limits.
    /// ``ValueError`` naming the file, line and column.
    fn read_postures<'py>(
        &self,
        py: Python<'py>,
        path: PathBuf,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let name = path.display().to_string();
        let text = error::read(&path)?;
        let group =
            postures::parse(&text, &self.inner, None).map_err(|e| error::raise_in(&name, e))?;
        Ok(arrays::degrees(py, &group))
    }

    fn __repr__(&self) -> String {
        format!("Robot({:?})", self.inner.name)
    }
}

impl Robot {
    /// Postures within the joint limits, and whether one posture of shape (6,) was given.
    fn postures(&self, q_deg: &Bound<'_, PyAny>) -> PyResult<(Vec<nalgebra::Vector6<f64>>, bool)> {
        let limits = (&self.inner.limits, "the joint limits");
        arrays::postures(q_deg, "q_deg", limits, MAX_POSTURES)
    }

    /// The Jacobians of [`Robot::jacobian`], and whether one posture was given.
    fn jacobians(
        &self,
        py: Python<'_>,
        q_deg: &Bound<'_, PyAny>,
        point_mm: Option<&Bound<'_, PyAny>>,
        coordinates: &str,
    ) -> PyResult<(Vec<Matrix6<f64>>, bool)> {
        let (qs, single) = self.postures(q_deg)?;
        let point = point(point_mm)?;
        let coordinates = coordinates_arg(coordinates)?;
        let robot = &self.inner;
        let js = py.detach(|| {
            qs.iter()
                .map(|q| robot.frames(q).jacobian(&point, coordinates))
                .collect()
        });
        Ok((js, single))
    }
}

/// A point in the flange frame given in mm (default the flange origin), m.
fn point(point_mm: Option<&Bound<'_, PyAny>>) -> PyResult<Vector3<f64>> {
    Ok(match point_mm {
        None => Vector3::zeros(),
        Some(p) => Vector3::from(arrays::vector::<3>(p, "point_mm", &limits::LENGTH_MM)?) * 1e-3,
    })
}

/// `"axis"` or `"kinematic"`.
pub fn coordinates_arg(given: &str) -> PyResult<Coordinates> {
    given.parse().map_err(raise)
}

/// The first of a stack for one posture, else the stack.
fn shaped<'py>(out: Bound<'py, numpy::PyArray3<f64>>, single: bool) -> PyResult<Py<PyAny>> {
    match single {
        true => Ok(out.get_item(0)?.unbind()),
        false => Ok(out.into_any().unbind()),
    }
}

/// A robot from a `.toml` or `.urdf` file (never a preset: a missing file is
/// `FileNotFoundError`).
fn from_path(path: &Path, tip: Option<&str>) -> PyResult<stiffid::Robot> {
    let read = |p: &Path| Some(error::read(p).map_err(Failure));
    let reference = path.to_string_lossy();
    reference::robot(&reference, tip, read).map_err(|e: Failure| e.0)
}
