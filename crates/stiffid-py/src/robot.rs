//! `stiffid.Robot`: an immutable 6-axis robot, its forward kinematics, point Jacobians and the
//! dexterity index.

use crate::arrays;
use crate::error::{self, raise, Failure};
use nalgebra::{Matrix4, Matrix6, Vector3, Vector6};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyAny, PyDict, PyList};
use std::path::{Path, PathBuf};
use stiffid::app::kinematics::{self as job, characteristic_length_or_derived};
use stiffid::internal::common::limits;
use stiffid::internal::io::postures;
use stiffid::internal::robot::presets;
use stiffid::internal::setup::reference::{self, Meshes};
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
    /// default the only leaf, else the leaf ending six revolute joints, else ``tool0``). A URDF's
    /// ``<collision>`` shapes become the robot's bodies (the cell's checks use them): its meshes
    /// (STL, OBJ) are read relative to the URDF, and ``package://NAME/PATH`` as
    /// ``DIR/NAME/PATH`` for the first directory ``DIR`` of ``package_paths`` (at most 64) that
    /// holds it. Raises ``FileNotFoundError``/``OSError`` for a file that cannot be read,
    /// ``stiffid.InputError`` (a ``ValueError``) for its content or a mesh that cannot be found
    /// (the library's message names the file, field, package and the paths tried); a mesh not
    /// found only warns (``UserWarning``): the robot serves everything but the cell's body checks.
    #[staticmethod]
    #[pyo3(signature = (path, tip=None, *, package_paths=Vec::new()))]
    fn from_file(
        py: Python<'_>,
        path: PathBuf,
        tip: Option<&str>,
        #[pyo3(from_py_with = crate::robot::package_paths)] package_paths: Vec<PathBuf>,
    ) -> PyResult<Self> {
        let inner = from_path(&path, tip, &package_paths)?;
        let warning = stiffid::internal::setup::plausibility::meshes(&inner);
        crate::documents::warn(py, &Vec::from_iter(warning))?;
        Ok(Self { inner })
    }

    /// Human-readable name, e.g. ``"COMAU SMART5 NJ 165-3.0"``.
    #[getter]
    fn name(&self) -> &str {
        self.inner.name()
    }

    /// Where the numbers come from (datasheet, paper, file and tip link).
    #[getter]
    fn source(&self) -> &str {
        self.inner.source()
    }

    /// Lower joint limits, axis coordinates, deg, shape ``(6,)``.
    #[getter]
    fn lower_limit_deg<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arrays::vec1(py, self.inner.limits().lower.iter().map(|v| v.to_degrees()))
    }

    /// Upper joint limits, axis coordinates, deg, shape ``(6,)``.
    #[getter]
    fn upper_limit_deg<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arrays::vec1(py, self.inner.limits().upper.iter().map(|v| v.to_degrees()))
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
        characteristic_length_mm: Option<&Bound<'_, PyAny>>,
        coordinates: &str,
    ) -> PyResult<Py<PyAny>> {
        let characteristic_length_mm =
            crate::count::real("characteristic_length_mm", characteristic_length_mm)?;
        let (robot, at) = (&self.inner, point(point_mm)?);
        let given = characteristic_length_mm.map(|l| l * 1e-3);
        let length = py
            .detach(|| characteristic_length_or_derived(robot, &at, given))
            .map_err(raise)?;
        let (js, single) = self.jacobians(py, q_deg, point_mm, coordinates)?;
        let k: Vec<f64> = js.iter().map(|j| dexterity(j, length)).collect();
        match single {
            true => Ok(k[0].into_pyobject(py)?.into_any().unbind()),
            false => Ok(arrays::vec1(py, k).into_any().unbind()),
        }
    }

    /// The kinematics job of ``stiffid kinematics`` for one posture ``q_deg`` (shape ``(6,)``,
    /// deg, within the joint limits): returns its document (docs/schemas/kinematics.schema.json)
    /// as a dict, equal to ``stiffid kinematics --json``: the flange pose, the point
    /// ``point_mm``'s position (flange frame, mm; default the flange origin) and Jacobian
    /// (``coordinates``), every joint frame's origin, and the dexterity with the characteristic
    /// length ``characteristic_length_mm`` (``None``: the robot's own, named ``derived``); where
    /// the robot gives its masses, the mass matrix and the point's operational-space inertia,
    /// and with ``stiffness_nm_per_rad`` (shape ``(6,)``, Nm/rad, in ``coordinates``) the
    /// natural frequencies and mode shapes. Placeholder masses are warned about
    /// (``UserWarning``). A robot with external axes (a track, a positioner) needs ``external``
    /// (shape ``(n,)``, mm for a linear axis and deg for a rotary one, the cell's order): positions
    /// in the cell frame, ``external_jacobian`` (6 rows, one column per axis: the tool point
    /// relative to the part) and the part's frame.
    #[pyo3(signature = (q_deg, point_mm=None, characteristic_length_mm=None, coordinates="axis", stiffness_nm_per_rad=None, external=None))]
    #[allow(clippy::too_many_arguments)]
    fn kinematics<'py>(
        &self,
        py: Python<'py>,
        q_deg: &Bound<'py, PyAny>,
        point_mm: Option<&Bound<'py, PyAny>>,
        characteristic_length_mm: Option<&Bound<'_, PyAny>>,
        coordinates: &str,
        stiffness_nm_per_rad: Option<&Bound<'py, PyAny>>,
        external: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let characteristic_length_mm =
            crate::count::real("characteristic_length_mm", characteristic_length_mm)?;
        let external = match (external, self.inner.external()) {
            (None, _) => Vec::new(),
            (Some(_), None) => {
                // Refused with the job's message: the robot has no external axes.
                job::check_external(&self.inner, &[0.0], "external").map_err(raise)?;
                Vec::new()
            }
            (Some(e), Some(axes)) => axes.to_si(&arrays::values(e, "external", axes.len())?),
        };
        let stiffness = stiffness_nm_per_rad
            .map(|k| {
                let range = &limits::STIFFNESS_NM_PER_RAD;
                arrays::vector::<6>(k, "stiffness_nm_per_rad", range).map(Vector6::from)
            })
            .transpose()?;
        let q = Vector6::from(arrays::vector::<6>(q_deg, "q_deg", &limits::ANGLE_DEG)?);
        let q = q.map(f64::to_radians);
        let warning = stiffid::internal::setup::plausibility::radians_in_option("q_deg", &q);
        crate::documents::warn(py, &Vec::from_iter(warning))?;
        let request = job::Request {
            robot: &self.inner,
            q,
            point: point(point_mm)?,
            characteristic_length: characteristic_length_mm.map(|l| l * 1e-3),
            coordinates: coordinates_arg(coordinates)?,
            stiffness,
            external,
            workpiece: None,
        };
        let outcome = py.detach(|| job::run(&request)).map_err(raise)?;
        crate::documents::warn(py, &outcome.warnings)?;
        crate::documents::to_python(py, outcome.written(), &[])
    }

    /// The robot's own characteristic length (mm) for the point ``point_mm`` (flange frame, mm;
    /// default the flange origin): the length that minimises the point's median dexterity over
    /// 512 seeded postures within the joint limits (``stiffid_core::setup::prior``; about 1200 mm for the
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
        let l = py
            .detach(|| stiffid::internal::setup::prior::robot_characteristic_length(robot, &point));
        Ok(l.map_err(raise)? * 1e3)
    }

    /// The axis angles (deg) that put the tool point ``point_mm`` (flange frame, mm, shape
    /// ``(3,)``; default the flange origin) at the pose ``pose_mm``: a homogeneous transform in
    /// the base frame, translation in mm (the point's position) and the rotation of the flange,
    /// as ``flange_pose`` returns it for the flange origin; shape ``(4, 4)``, or ``(n, 4, 4)`` for
    /// a path. Damped least squares on the point's Jacobian within the joint limits
    /// (``stiffid_core::robot::ik``), from ``q0_deg`` (shape ``(6,)``, deg, within the joint limits), each
    /// next pose from the previous solution (one branch along a path); if a start fails,
    /// ``restarts`` seeded random postures (default 8, ``seed``). Converged when the point is
    /// within ``position_tolerance_mm`` (default 1e-7 mm) and the rotation within
    /// ``rotation_tolerance_deg`` (default 5.7e-9 deg, 1e-10 rad), at most ``max_iterations``
    /// steps per start (default 100). Returns a dict: ``q_deg`` (shape ``(6,)`` or ``(n, 6)``),
    /// ``iterations``, ``position_error_mm`` and ``rotation_error_deg`` (what remains; a number
    /// or shape ``(n,)``). ``stiffid.InfeasibleError`` naming the smallest remaining distance
    /// and rotation for a pose out of reach (outside the workspace or beyond a joint limit).
    #[pyo3(signature = (pose_mm, q0_deg, *, point_mm=None, position_tolerance_mm=None, rotation_tolerance_deg=None, max_iterations=None, restarts=None, seed=1))]
    #[allow(clippy::too_many_arguments)]
    fn inverse_kinematics<'py>(
        &self,
        py: Python<'py>,
        pose_mm: &Bound<'py, PyAny>,
        q0_deg: &Bound<'py, PyAny>,
        point_mm: Option<&Bound<'py, PyAny>>,
        position_tolerance_mm: Option<&Bound<'_, PyAny>>,
        rotation_tolerance_deg: Option<&Bound<'_, PyAny>>,
        #[pyo3(from_py_with = crate::count::optional_whole)] max_iterations: Option<i64>,
        #[pyo3(from_py_with = crate::count::optional_whole)] restarts: Option<i64>,
        #[pyo3(from_py_with = crate::count::seed_of)] seed: u64,
    ) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
        let position_tolerance_mm =
            crate::count::real("position_tolerance_mm", position_tolerance_mm)?;
        let rotation_tolerance_deg =
            crate::count::real("rotation_tolerance_deg", rotation_tolerance_deg)?;
        let max_iterations = crate::count::optional("max_iterations", max_iterations)?;
        let restarts = crate::count::optional("restarts", restarts)?;
        let limits = (self.inner.limits(), "the joint limits");
        let (q0, single) = arrays::postures(q0_deg, "q0_deg", limits, 1)?;
        if !single {
            return Err(error::value("q0_deg: expected an array of shape (6,)"));
        }
        let effort = crate::ik::Effort {
            position_tolerance_mm,
            rotation_tolerance_deg,
            max_iterations,
            restarts,
            seed,
        };
        crate::ik::solve(py, &self.inner, pose_mm, q0[0], point(point_mm)?, &effort)
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

    /// The cell's external axes (a track under the arm, a positioner under the part), in the
    /// cell's order, as dicts: ``name``, ``column`` (``e1_mm``, ``e2_deg``, ...), ``role``
    /// (``carrier`` or ``positioner``), ``direction``, ``point_mm``, ``limits`` and ``offset`` (mm
    /// or deg); empty for a robot without.
    #[getter]
    fn external_axes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let list = PyList::empty(py);
        let Some(axes) = self.inner.external() else {
            return Ok(list);
        };
        for (a, column) in axes.axes().iter().zip(axes.column_names()) {
            let d = PyDict::new(py);
            d.set_item("name", &a.name)?;
            d.set_item("column", column)?;
            let role = match a.role {
                stiffid::internal::robot::external::Role::Carrier => "carrier",
                stiffid::internal::robot::external::Role::Positioner => "positioner",
            };
            d.set_item("role", role)?;
            d.set_item(
                "direction",
                a.direction.iter().copied().collect::<Vec<f64>>(),
            )?;
            d.set_item(
                "point_mm",
                (a.point * 1e3).iter().copied().collect::<Vec<f64>>(),
            )?;
            d.set_item("limits", vec![a.to_display(a.lower), a.to_display(a.upper)])?;
            d.set_item("offset", a.to_display(a.offset))?;
            list.append(d)?;
        }
        Ok(list)
    }

    /// The robot in a cell with these external axes: a list of dicts with the keys of a robot
    /// file's ``[[external_axis]]`` tables (``name``, ``role``, ``direction``, ``limits_mm`` or
    /// ``limits_deg``, ``offset_mm`` or ``offset_deg``, ``point_mm``, ``error_motions``), or
    /// ``None`` / ``[]`` for none. Raises ``stiffid.InputError`` naming the table and the field.
    fn with_external_axes(
        &self,
        py: Python<'_>,
        axes: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let axes = match axes {
            None => None,
            Some(a) => {
                let text = tables_json(py, a, "axes")?;
                stiffid::internal::robot::external::file::from_json(&text, "axes").map_err(raise)?
            }
        };
        Ok(Self {
            inner: self.inner.clone().with_external(axes),
        })
    }

    fn __repr__(&self) -> String {
        format!("Robot({:?})", self.inner.name())
    }
}

/// `tables` (the argument `name`: dicts, lists, strings and numbers, NumPy arrays and numbers
/// among them) as JSON text; an `InputError` naming the argument for anything else, NaN or an
/// infinity.
fn tables_json(py: Python<'_>, tables: &Bound<'_, PyAny>, name: &str) -> PyResult<String> {
    let kwargs = PyDict::new(py);
    kwargs.set_item("allow_nan", false)?;
    kwargs.set_item("default", py.eval(c"lambda o: o.tolist()", None, None)?)?;
    let dumped = py
        .import("json")?
        .call_method("dumps", (tables,), Some(&kwargs));
    match dumped {
        Ok(text) => text.extract(),
        Err(e) => Err(error::value(format!(
            "{name}: expected tables of names, numbers and lists of numbers (finite; NumPy arrays taken as lists), got {}",
            limits::short(&e.value(py).to_string())
        ))),
    }
}

impl Robot {
    /// Postures within the joint limits, and whether one posture of shape (6,) was given.
    fn postures(&self, q_deg: &Bound<'_, PyAny>) -> PyResult<(Vec<nalgebra::Vector6<f64>>, bool)> {
        let limits = (self.inner.limits(), "the joint limits");
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
    point_or(point_mm, Vector3::zeros())
}

/// The point `point_mm` (flange frame, mm, the argument `point_mm`), m; `default` (m) if `None`.
pub fn point_or(
    point_mm: Option<&Bound<'_, PyAny>>,
    default: Vector3<f64>,
) -> PyResult<Vector3<f64>> {
    Ok(match point_mm {
        None => default,
        Some(p) => Vector3::from(arrays::vector::<3>(p, "point_mm", &limits::LENGTH_MM)?) * 1e-3,
    })
}

/// `"axis"` or `"kinematic"`.
pub fn coordinates_arg(given: &str) -> PyResult<Coordinates> {
    given.parse().map_err(raise)
}

/// The first of a stack for one posture, else the stack.
pub fn shaped<'py>(out: Bound<'py, numpy::PyArray3<f64>>, single: bool) -> PyResult<Py<PyAny>> {
    match single {
        true => Ok(out.get_item(0)?.unbind()),
        false => Ok(out.into_any().unbind()),
    }
}

/// A robot from a `.toml` or `.urdf` file (never a preset: a missing file is
/// `FileNotFoundError`), a URDF's meshes read, `package://` in `package_paths`.
fn from_path(
    path: &Path,
    tip: Option<&str>,
    package_paths: &[PathBuf],
) -> PyResult<stiffid::Robot> {
    check_package_paths(package_paths)?;
    let read = |p: &Path| Some(error::read(p).map_err(Failure));
    let reference = path.to_string_lossy();
    let meshes = Meshes {
        read: &error::bytes,
        package_paths,
    };
    reference::robot_with_meshes(&reference, tip, read, &meshes).map_err(|e: Failure| e.0)
}

/// The `package_paths` argument read by PyO3 (`#[pyo3(from_py_with = robot::package_paths)]`):
/// a sequence of directories; one path given alone (a str or an `os.PathLike`, which PyO3 would
/// refuse as "Can't extract `str` to `Vec`") is refused saying to give a list.
pub fn package_paths(given: &Bound<'_, PyAny>) -> PyResult<Vec<PathBuf>> {
    let os_path_like = given.py().import("os")?.getattr("PathLike")?;
    if given.is_instance_of::<pyo3::types::PyString>()
        || given.is_instance_of::<pyo3::types::PyBytes>()
        || given.is_instance(&os_path_like)?
    {
        let repr = given.repr()?;
        return Err(crate::error::value(format!(
            "{repr} is one path: expected a list of directories (package_paths=[{repr}])"
        )));
    }
    given.extract()
}

/// At most [`stiffid::internal::setup::MAX_PACKAGE_PATHS`] package paths.
pub fn check_package_paths(paths: &[PathBuf]) -> PyResult<()> {
    let most = stiffid::internal::setup::MAX_PACKAGE_PATHS;
    limits::check_count("package_paths", paths.len(), 0, most).map_err(raise)
}
