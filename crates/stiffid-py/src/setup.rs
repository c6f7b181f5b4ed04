//! `stiffid.Setup`: an experimental cell (robot, tool, loading, noise, bounds, nominal stiffness),
//! read-only, with the design methods (evaluate, select) of [`crate::design`].

use crate::arrays::{self, postures};
use crate::design;
use crate::error::{self, raise, Failure};
use crate::robot::Robot;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyAny, PyDict, PyList};
use std::path::{Path, PathBuf};
use stiffid::internal::setup;
use stiffid::internal::setup::reference::{self, Meshes};

/// An experimental setup (read-only). Lengths in mm, angles in deg, stiffness in Nm/rad.
#[pyclass(frozen, module = "stiffid", name = "Setup")]
pub struct Setup {
    pub inner: stiffid::Setup,
    /// The files it was read from (the setup file, its robot file), which a call that writes
    /// files never writes over.
    pub files: Vec<PathBuf>,
    /// The setup as the user named it: a built-in's name, the path given to `from_file`, the
    /// `source_name` of `from_toml`. The documents' `setup`, as the command's is its `--setup`.
    pub given: String,
}

#[pymethods]
impl Setup {
    /// A built-in setup (see ``Setup.builtins()``): ``"zhang2021-comau-nj165"`` (the paper's
    /// cell) or ``"fanuc-r2000ic-165f"`` (the real data's). ``ValueError`` for an unknown name.
    #[staticmethod]
    fn builtin(name: &str) -> PyResult<Self> {
        Ok(Self {
            inner: setup::builtin(name).map_err(raise)?,
            files: Vec::new(),
            given: name.to_string(),
        })
    }

    /// The names of the built-in setups.
    #[staticmethod]
    fn builtins() -> Vec<&'static str> {
        setup::builtin_names().collect()
    }

    /// A setup from a setup ``.toml`` file; a robot file it names is looked for relative to the
    /// file (a preset name wins over a path that does not exist). A URDF robot's meshes are read
    /// as ``Robot.from_file`` reads them: ``package://`` in ``package_paths`` first, then in the
    /// setup's own ``package_paths`` (relative to the setup file).
    #[staticmethod]
    #[pyo3(signature = (path, *, package_paths=Vec::new()))]
    pub(crate) fn from_file(
        py: Python<'_>,
        path: PathBuf,
        #[pyo3(from_py_with = crate::robot::package_paths)] package_paths: Vec<PathBuf>,
    ) -> PyResult<Self> {
        let text = error::read(&path)?;
        let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
        let mut setup = Self::parse(py, &text, &path.display().to_string(), &dir, &package_paths)?;
        setup.files.push(path);
        Ok(setup)
    }

    /// A setup from the text of a setup TOML (``source_name`` names it in errors; robot files are
    /// looked for in ``base_dir``, default the current directory; ``package_paths`` as in
    /// ``Setup.from_file``).
    #[staticmethod]
    #[pyo3(signature = (text, source_name="<string>", base_dir=None, *, package_paths=Vec::new()))]
    fn from_toml(
        py: Python<'_>,
        text: &str,
        source_name: &str,
        base_dir: Option<PathBuf>,
        #[pyo3(from_py_with = crate::robot::package_paths)] package_paths: Vec<PathBuf>,
    ) -> PyResult<Self> {
        let dir = base_dir.unwrap_or_default();
        Self::parse(py, text, source_name, &dir, &package_paths)
    }

    /// The parameters of the setup's elastostatic model, drives first (``k1`` .. ``k6``), then
    /// the virtual springs in the setup's order: one dict each, ``name``, ``kind`` (``"drive"``,
    /// ``"rotation"`` or ``"translation"``), ``unit`` (``"Nm/rad"`` or ``"N/mm"``) and
    /// ``stiffness``, the nominal stiffness in ``unit`` (``None`` where the setup has none), as
    /// the stiffness file and the documents list them.
    #[getter]
    fn parameters<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        crate::model::parameters(py, &self.inner)
    }

    /// The ``[model]`` table of the setup's virtual springs as setup TOML (``[[model.spring]]``
    /// tables, each spring with its axis; empty for the six drives alone), what
    /// ``Setup.with_model`` reads back.
    #[getter]
    fn model_toml(&self) -> String {
        stiffid::internal::model::fragment(self.inner.model().springs())
    }

    /// The same setup with the model's virtual springs those of ``toml``: a setup file's
    /// ``[model]`` table alone (``[[model.spring]]`` and ``[[model.family]]`` tables, e.g.
    /// ``Setup.model_toml`` or the fragment ``stiffid identify --compare-models --out`` writes;
    /// an empty text leaves the six drives alone). ``source_name`` names it in errors.
    /// ``stiffid.InputError`` naming the field (e.g. ``model.spring[1].axis``).
    #[pyo3(signature = (toml, source_name="<model>"))]
    fn with_model(&self, py: Python<'_>, toml: &str, source_name: &str) -> PyResult<Self> {
        let inner = crate::model::with_model(&self.inner, toml, source_name)?;
        crate::documents::warn(py, &setup::plausibility::warnings(&inner))?;
        Ok(Self {
            inner,
            files: self.files.clone(),
            given: self.given.clone(),
        })
    }

    /// Each posture's checks in the cell (the setup's bounds, floor, obstacles, self-collision,
    /// rope, line of sight, incidence, ``[constraints]``), as ``Setup.evaluate``'s and ``stiffid
    /// evaluate --json``'s ``feasibility``: ``postures_deg`` (axis angles, deg, shape ``(6,)`` or
    /// ``(n, 6)``, within the joint limits; at most 10000) gives a list of one dict per posture,
    /// ``posture`` (1-based), ``feasible``, ``min_clearance_mm`` (the smallest distance between
    /// bodies and lines that must not touch; ``None`` without ``[cell]`` or ``[tracker]``) and
    /// ``violations`` (the failing checks: ``check``, e.g. ``"floor"``, ``margin_mm`` or
    /// ``margin_deg``, negative, and ``between``, the tightest pair, e.g. ``["link 3",
    /// "floor"]``). Source: ``stiffid_core::cell``, docs/model.md.
    fn feasibility<'py>(
        &self,
        py: Python<'py>,
        postures_deg: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let r = self.inner.robot();
        let within = (r.limits(), "the joint limits");
        let most = stiffid::internal::common::limits::MAX_GROUP_POSTURES;
        let (group, _) = postures(postures_deg, "postures_deg", within, most)?;
        let setup = &self.inner;
        setup.check_bodies().map_err(crate::error::raise)?;
        let document = py.detach(|| stiffid::app::evaluate::feasibility(setup, &group));
        crate::documents::to_object(py, &document)
    }

    /// Short name, e.g. ``"zhang2021-comau-nj165"``.
    #[getter]
    fn name(&self) -> &str {
        self.inner.name()
    }

    /// What this cell is, free text.
    #[getter]
    fn description(&self) -> &str {
        self.inner.description()
    }

    /// The robot reference as written (a preset name or a file).
    #[getter]
    fn robot_ref(&self) -> &str {
        self.inner.robot_ref()
    }

    /// The robot (with the setup's base and flange offsets).
    #[getter]
    fn robot(&self) -> Robot {
        Robot {
            inner: self.inner.robot().clone(),
        }
    }

    /// Where the springs sit: ``"axis"`` (in the drives) or ``"kinematic"``.
    #[getter]
    fn springs(&self) -> &'static str {
        self.inner.springs().name()
    }

    /// Nominal (in simulation: true) joint stiffness, Nm/rad, shape ``(6,)`` (Table 2); ``None``
    /// if the setup has none (the criteria scaled by it, simulation and study need it).
    #[getter]
    fn nominal_stiffness_nm_per_rad<'py>(
        &self,
        py: Python<'py>,
    ) -> Option<Bound<'py, PyArray1<f64>>> {
        let k = self.inner.nominal_stiffness()?;
        Some(arrays::vec1(py, k.iter().copied()))
    }

    /// Characteristic length ``L`` of the dexterity index (Eq. 20), mm; ``None`` if the setup has
    /// none (the classical and zhang2021 criteria need it).
    #[getter]
    fn characteristic_length_mm(&self) -> Option<f64> {
        self.inner.characteristic_length().map(|l| l * 1e3)
    }

    /// Loading point, flange frame, mm, shape ``(3,)``.
    #[getter]
    fn loading_point_mm<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arrays::vec1(py, self.inner.tool().loading_point.iter().map(|v| v * 1e3))
    }

    /// Measuring points, flange frame, mm, shape ``(p, 3)``.
    #[getter]
    fn measuring_points_mm<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        arrays::millimetres(py, &self.inner.tool().measuring_points)
    }

    /// Tool centre point of the dexterity index, flange frame, mm, shape ``(3,)``.
    #[getter]
    fn tcp_mm<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arrays::vec1(py, self.inner.tool().tcp.iter().map(|v| v * 1e3))
    }

    /// Rope load ``G``, N.
    #[getter]
    fn load_n(&self) -> f64 {
        self.inner.load().load
    }

    /// The load steps read in each posture (``[loading] steps_n``), N, rising; empty for one load
    /// per posture.
    #[getter]
    fn load_steps_n(&self) -> Vec<f64> {
        self.inner.load_steps().to_vec()
    }

    /// Rope anchor (pulley) ``P2``, base frame, mm, shape ``(3,)``.
    #[getter]
    fn anchor_mm<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arrays::vec1(py, self.inner.load().anchor.iter().map(|v| v * 1e3))
    }

    /// Variance of one displacement coordinate (a loaded minus an unloaded reading: twice
    /// the reading variance of ``[noise] reading_sd_mm``) at noise multiple 1, mm^2.
    #[getter]
    fn noise_variance_mm2(&self) -> f64 {
        self.inner.noise().displacement_variance() * 1e6
    }

    /// Noise levels as multiples of the variance, shape ``(levels,)`` (Table 3).
    #[getter]
    fn level_multiples<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arrays::vec1(py, self.inner.noise().levels.iter().copied())
    }

    /// Lower experiment bounds, axis angles, deg, shape ``(6,)`` (Table 1).
    #[getter]
    fn lower_deg<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arrays::vec1(py, self.inner.bounds().lower.iter().map(|v| v.to_degrees()))
    }

    /// Upper experiment bounds, axis angles, deg, shape ``(6,)`` (Table 1).
    #[getter]
    fn upper_deg<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arrays::vec1(py, self.inner.bounds().upper.iter().map(|v| v.to_degrees()))
    }

    /// Test (validation) postures, axis angles, deg, shape ``(t, 6)`` (Table 5).
    #[getter]
    fn test_postures_deg<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        arrays::degrees(py, self.inner.test_postures())
    }

    /// Every design criterion of a group of postures (``postures_deg``, shape ``(n, 6)``, axis
    /// angles within the setup's bounds), its predicted deviation rates, each posture's
    /// feasibility in the cell and how well the group identifies each parameter of the setup's
    /// model: the evaluate job of ``stiffid evaluate``, its document
    /// (docs/schemas/evaluate.schema.json) as a dict: ``classical``, ``zhang2021``,
    /// ``scaled_cond``, ``d_optimal``, ``relative_a``, ``test_pose_mm``, ``cond_psi`` (floats),
    /// ``relative_std`` (an array of shape ``(6,)``), ``predicted_deviation_pct`` (shape
    /// ``(levels, 6)``, percent: ``100 sqrt(2/pi) sqrt(m) sqrt([(S^T S)^-1]_jj)``),
    /// ``feasibility``, ``parameters`` and ``unidentifiable``. Sources: Zhang et al. 2021, Eq.
    /// 19-21; docs/model.md section 5. ``None`` for an infinite value and for what the setup
    /// lacks a field for: ``classical`` and ``zhang2021`` without ``characteristic_length_mm``;
    /// ``scaled_cond``, ``d_optimal``, ``relative_a``, ``relative_std`` and
    /// ``predicted_deviation_pct`` without ``nominal_stiffness_nm_per_rad``; ``test_pose_mm``
    /// without test postures. ``candidates``: how the group identifies each candidate of
    /// ``identify --compare-models`` together with the setup's model (``identified``,
    /// ``separation``, the combinations it cannot separate, and ``separable``: those the
    /// comparison can separate on data measured in the group), for the candidates named in
    /// ``candidates`` (families or single candidates, as ``stiffid evaluate --candidates``),
    /// default all. ``ValueError`` for a group that cannot identify every joint, or an unknown
    /// candidate.
    /// ``purpose``: what the group is for, as the command's ``--for``: ``"stiffness"`` (the
    /// identification, the default), ``"calibration"`` (the robot's geometric and elastostatic
    /// calibration, as ``calibrate`` fits it, with ``calibration_criterion``: ``"test-pose"``, the
    /// default, ``"o1"``, ``"o3"``, ``"o4"``, ``"o5"`` or ``"d-optimality"``; ``geometry`` and
    /// ``gravity`` as ``calibrate``'s) or ``"both"`` (the weighted sum of the two log-criteria,
    /// ``weight`` the calibration's, default 0.5); ``ValueError`` naming a calibration option given
    /// for the stiffness alone, or ``weight`` without ``"both"``.
    /// With the calibration, the document's ``calibration`` holds the group's calibration
    /// criteria.
    #[pyo3(signature = (postures_deg, *, candidates=None, purpose="stiffness", calibration_criterion=None, geometry=None, gravity=None, weight=None))]
    #[allow(clippy::too_many_arguments)]
    fn evaluate<'py>(
        &self,
        py: Python<'py>,
        postures_deg: &Bound<'py, PyAny>,
        candidates: Option<Vec<String>>,
        purpose: &str,
        calibration_criterion: Option<&str>,
        geometry: Option<&str>,
        gravity: Option<&str>,
        weight: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let weight = crate::count::real("weight", weight)?;
        let group = self.group(postures_deg, "postures_deg")?;
        let purpose = design::For {
            purpose,
            calibration_criterion,
            geometry,
            gravity,
            weight,
        };
        design::evaluate(py, &self.inner, &group, candidates, &purpose)
    }

    /// The group of ``n`` postures (2 to 100; default 6, or as many as ``start``) that minimises
    /// ``criterion`` (``"classical"``, ``"zhang2021"``, ``"scaled-cond"``, ``"d-optimal"``,
    /// ``"relative-a"``, the default, ``"test-pose"``; with ``purpose`` ``"stiffness"`` or
    /// ``"both"`` only) within the setup's bounds and cell checks: the select job of
    /// ``stiffid select``, run the same way.
    ///
    /// - ``method="global"`` (default): ``starts`` local searches from seeded Latin-hypercube
    ///   groups (default 32; ``screen_steps`` SQP steps each, default 60, then the best
    ///   ``polished``, default 8, continue), the best kept;
    /// - ``method="local"``: SQP from ``start`` (shape ``(n, 6)``, deg), or from the
    ///   seeded random group of ``n`` postures when ``start`` is None (the paper's procedure);
    /// - ``method="pool"`` (or ``pool`` given): the best ``n`` of the postures ``pool``
    ///   (shape ``(m, 6)``, deg, at most 10000; postures failing a cell check are skipped), exact
    ///   by enumeration up to 100000 groups, else the best of ``restarts`` exchange runs.
    ///
    /// ``margin_mm`` (0 to 1000): the margin every posture keeps to every constraint of the
    /// cell (line of sight, incidence, floor, obstacles, bodies, rope, ``[constraints]``), in a
    /// search and a pool alike; default the tracker's ``registration_uncertainty_mm``, else 0.
    /// ``target_pct`` (global or pool): the smallest group whose predicted mean deviation rate at
    /// noise level multiple 1 is at most this many percent on every parameter, instead of ``n``.
    /// ``max_evals`` bounds the evaluations of one local search (default 6000); ``gradient`` is
    /// ``"exact"`` or ``"fd"``; ``solver`` the SQP: ``"auto"`` (per criterion: ``"active-set"``
    /// on ``relative-a``, ``d-optimal`` and ``test-pose``, ``"slsqp"`` on the others),
    /// ``"slsqp"`` or ``"active-set"`` (ours); the document's ``solver`` names the one that ran.
    /// ``for_candidates=True``: design for the setup's model and the candidates of
    /// ``identify --compare-models`` together (``candidates``: families or single candidates,
    /// default all; the linear ones are added to the model of the design, each at the drives'
    /// geometric-mean stiffness unless declared with one), the document's ``candidates`` saying
    /// how the group identifies each, as ``evaluate`` does; ``ValueError`` for too few postures
    /// (naming the count needed), with ``target_pct``, or ``candidates`` without it.
    /// ``distinct=True`` (pool only): forbid postures that are not distinct, the pool keeping the
    /// first of every pair whose axis angles all lie within ``distinct_deg`` (0 to 180, default 2)
    /// or whose flanges reach the same pose (origins within ``distinct_mm``, 0 to 10000, default
    /// 10; orientations within ``distinct_deg``; a wrist flip counts); the document's
    /// ``pool.not_distinct`` lists those left out. ``ValueError`` for a search, or for the
    /// distances without ``distinct``.
    /// ``purpose``: what the group is for, as the command's ``--for``: ``"stiffness"`` (the
    /// identification, the default), ``"calibration"`` (the robot's geometric and elastostatic
    /// calibration, as ``calibrate`` fits it, with ``calibration_criterion``: ``"test-pose"``, the
    /// default, ``"o1"``, ``"o3"``, ``"o4"``, ``"o5"`` or ``"d-optimality"``; ``geometry`` and
    /// ``gravity`` as ``calibrate``'s) or ``"both"`` (the weighted sum of the two log-criteria,
    /// ``weight`` the calibration's, default 0.5); ``ValueError`` naming a calibration option given
    /// for the stiffness alone, or ``weight`` without ``"both"``.
    /// ``stations``: for a robot with external axes (a track), where the arm stands for the
    /// whole group, a list of stations, each one value per axis in the cell's order (mm, deg);
    /// the group is designed at each and the best kept (the document's ``station`` and
    /// ``stations``). ``ValueError`` without them on such a robot, or with them on another.
    /// Deterministic for a ``seed``. Returns the document of ``stiffid select --json`` (docs/schemas/select.schema.json) as a dict: ``search``,
    /// ``criterion``, ``postures_deg`` (an array of shape ``(n, 6)``), ``value``,
    /// ``start_value`` (None for a pool), ``evaluations``, ``termination`` and ``terminations``
    /// (why the searches stopped), ``criteria``, and ``pool``, ``target``, ``unconstrained`` where
    /// they apply. ``stiffid.InfeasibleError`` when no feasible group is found.
    #[pyo3(signature = (criterion=None, method=None, start=None, n=None, seed=1, *, starts=None, screen_steps=None, polished=None, max_evals=None, gradient="exact", solver="auto", pool=None, restarts=None, target_pct=None, margin_mm=None, for_candidates=false, candidates=None, distinct=false, distinct_deg=None, distinct_mm=None, purpose="stiffness", calibration_criterion=None, geometry=None, gravity=None, weight=None, stations=None))]
    #[allow(clippy::too_many_arguments)]
    fn select<'py>(
        &self,
        py: Python<'py>,
        criterion: Option<&str>,
        method: Option<&str>,
        start: Option<&Bound<'py, PyAny>>,
        #[pyo3(from_py_with = crate::count::optional_whole)] n: Option<i64>,
        #[pyo3(from_py_with = crate::count::seed_of)] seed: u64,
        #[pyo3(from_py_with = crate::count::optional_whole)] starts: Option<i64>,
        #[pyo3(from_py_with = crate::count::optional_whole)] screen_steps: Option<i64>,
        #[pyo3(from_py_with = crate::count::optional_whole)] polished: Option<i64>,
        #[pyo3(from_py_with = crate::count::optional_whole)] max_evals: Option<i64>,
        gradient: &str,
        solver: &str,
        pool: Option<&Bound<'py, PyAny>>,
        #[pyo3(from_py_with = crate::count::optional_whole)] restarts: Option<i64>,
        target_pct: Option<&Bound<'_, PyAny>>,
        margin_mm: Option<&Bound<'_, PyAny>>,
        for_candidates: bool,
        candidates: Option<Vec<String>>,
        distinct: bool,
        distinct_deg: Option<&Bound<'_, PyAny>>,
        distinct_mm: Option<&Bound<'_, PyAny>>,
        purpose: &str,
        calibration_criterion: Option<&str>,
        geometry: Option<&str>,
        gravity: Option<&str>,
        weight: Option<&Bound<'_, PyAny>>,
        stations: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let target_pct = crate::count::real("target_pct", target_pct)?;
        let margin_mm = crate::count::real("margin_mm", margin_mm)?;
        let distinct_deg = crate::count::real("distinct_deg", distinct_deg)?;
        let distinct_mm = crate::count::real("distinct_mm", distinct_mm)?;
        let weight = crate::count::real("weight", weight)?;
        use crate::count::optional;
        let start = start.map(|s| self.group(s, "start")).transpose()?;
        let pool = match pool {
            None => None,
            Some(p) => Some(self.pool(p)?),
        };
        let request = design::Request {
            criterion,
            method,
            start,
            n: optional("n", n)?,
            seed,
            starts: optional("starts", starts)?,
            screen_steps: optional("screen_steps", screen_steps)?,
            polished: optional("polished", polished)?,
            max_evals: optional("max_evals", max_evals)?,
            gradient,
            solver,
            pool,
            restarts: optional("restarts", restarts)?,
            target_pct,
            margin_mm,
            for_candidates,
            candidates,
            distinct,
            distinct_deg,
            distinct_mm,
            stations: crate::count::real_rows("stations", stations)?,
            purpose: design::For {
                purpose,
                calibration_criterion,
                geometry,
                gravity,
                weight,
            },
        };
        design::select(py, &self.inner, request)
    }

    /// A seeded Latin-hypercube group of ``n`` postures within the bounds (the start group of a
    /// local search), deg, shape ``(n, 6)``.
    #[pyo3(signature = (n=6, seed=1))]
    fn random_group<'py>(
        &self,
        py: Python<'py>,
        #[pyo3(from_py_with = crate::count::whole)] n: i64,
        #[pyo3(from_py_with = crate::count::seed_of)] seed: u64,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let (n, seed) = (crate::count::count("n", n)?, seed);
        design::check_postures(n)?;
        Ok(arrays::degrees(
            py,
            &stiffid::internal::design::random_group(&self.inner, n, seed),
        ))
    }

    fn __repr__(&self) -> String {
        format!("Setup({:?})", self.inner.name())
    }
}

impl Setup {
    /// The setup of `text`, its plausibility warnings ([`setup::plausibility`]) raised as
    /// `UserWarning`s, as the command prints them.
    fn parse(
        py: Python<'_>,
        text: &str,
        source_name: &str,
        dir: &Path,
        package_paths: &[PathBuf],
    ) -> PyResult<Self> {
        crate::robot::check_package_paths(package_paths)?;
        let meshes = Meshes {
            read: &error::bytes,
            package_paths,
        };
        let read = error::read_if_exists;
        let inner = reference::setup_text_with_meshes(text, source_name, dir, read, &meshes)
            .map_err(|e: Failure| e.0)?;
        crate::documents::warn(py, &setup::plausibility::warnings(&inner))?;
        let robot_file = dir.join(inner.robot_ref());
        let files = Vec::from_iter(robot_file.is_file().then_some(robot_file));
        Ok(Self {
            inner,
            files,
            given: source_name.to_string(),
        })
    }

    /// A group of postures within the setup's bounds (at most 10000).
    pub fn group(
        &self,
        obj: &Bound<'_, PyAny>,
        what: &str,
    ) -> PyResult<Vec<nalgebra::Vector6<f64>>> {
        let within = (self.inner.bounds(), "the setup's bounds");
        Ok(postures(
            obj,
            what,
            within,
            stiffid::internal::common::limits::MAX_GROUP_POSTURES,
        )?
        .0)
    }

    /// Pool postures: within the robot's joint limits (the cell's checks, bounds included, decide
    /// which are usable).
    fn pool(&self, obj: &Bound<'_, PyAny>) -> PyResult<Vec<nalgebra::Vector6<f64>>> {
        let r = &self.inner.robot();
        let within = (r.limits(), "the joint limits");
        Ok(postures(
            obj,
            "pool",
            within,
            stiffid::internal::design::pool::MAX_POOL,
        )?
        .0)
    }
}
