//! `stiffid.simulate` and `stiffid.reproduce`: the Monte Carlo identification of groups of
//! postures and the paper's simulation study, over [`stiffid::study::simulate`] and [`stiffid::study`].

use crate::arrays;
use crate::documents::{to_python, warn};
use crate::error::{raise, value};
use crate::setup::Setup;
use numpy::ndarray::Array3;
use numpy::{IntoPyArray, PyArray1, PyArray3};
use pyo3::prelude::*;
use pyo3::types::{PyAny, PyDict, PyList};
use stiffid::app::reproduce as job_reproduce;
use stiffid::app::reproduce::document::Summary;
use stiffid::app::simulate as job;
use stiffid::app::simulate::document::Document;
use stiffid::common::limits::{self, check_count};
use stiffid::study::simulate::{self as monte_carlo, GroupSimulation};
use stiffid::study::{self, Options};

/// A count within `[min, max]` (`field` names it in errors, a negative one too).
fn count(field: &str, v: i64, min: u64, max: u64) -> PyResult<usize> {
    let v = crate::count::count(field, v)?;
    check_count(field, v, min as usize, max as usize).map_err(raise)?;
    Ok(v)
}

/// Simulates the identification with each group of postures (``groups``: a list of arrays of
/// shape ``(n_i, 6)``, axis angles in deg within the setup's bounds; at most 100 groups) at every
/// noise level of the setup, ``runs`` times (1 to 100000; the paper: 200), the noise seeded by
/// ``seed`` (Zhang et al. 2021, Section IV-A, Fig. 8): the simulate job of ``stiffid simulate``.
/// Returns one dict per group, the groups of its document: ``name`` (``groups[i]``),
/// ``mean_deviation_pct``, ``std_deviation_pct``, ``predicted_deviation_pct`` (first order) and
/// ``mean_stiffness_nm_per_rad``, each an array of shape ``(levels, 6)``. The same seed gives the
/// same numbers whatever the thread count.
#[pyfunction]
#[pyo3(signature = (setup, groups, runs=200, seed=1))]
pub fn simulate<'py>(
    py: Python<'py>,
    setup: &Setup,
    groups: &Bound<'py, PyAny>,
    runs: i64,
    seed: i64,
) -> PyResult<Bound<'py, PyList>> {
    let seed = crate::count::seed("seed", seed)?;
    let items: Vec<Bound<'py, PyAny>> = groups
        .try_iter()
        .map_err(|_| value("groups: expected a list of (n, 6) arrays"))?
        .collect::<PyResult<_>>()?;
    count("groups", items.len() as i64, 1, limits::MAX_GROUPS as u64)?;
    let groups = items
        .iter()
        .enumerate()
        .map(|(i, g)| {
            let name = format!("groups[{i}]");
            let postures = setup.group(g, &name)?;
            Ok(job::Group { name, postures })
        })
        .collect::<PyResult<Vec<_>>>()?;
    let request = job::Request {
        setup: &setup.inner,
        groups,
        options: monte_carlo::Options {
            runs: count("runs", runs, 1, limits::MAX_RUNS)?,
            seed,
        },
    };
    let report = py.detach(|| job::run(&request)).map_err(raise)?;
    warn(py, &report.warnings)?;
    let out = PyList::empty(py);
    for g in Document::new(&report, &setup.inner).groups {
        out.append(to_python(py, &g, &RATES)?)?;
    }
    Ok(out)
}

/// The keys of a group's simulation returned as NumPy arrays.
const RATES: [&str; 4] = [
    "mean_deviation_pct",
    "std_deviation_pct",
    "predicted_deviation_pct",
    "mean_stiffness_nm_per_rad",
];

/// The paper's simulation study (``stiffid reproduce``): Group 1 a seeded random start group,
/// Groups 2 and 3 the paper's local searches on ``classical`` and ``zhang2021`` from it, Groups 4
/// and 5 global searches on ``relative-a`` and ``d-optimal`` (``starts`` starts each), the
/// start-group check over ``trials`` start groups, and the Monte Carlo identification of every
/// group at every noise level (``runs`` runs); ``solver`` is the SQP of every search,
/// ``"auto"`` (per criterion: ``"active-set"`` on the global searches, ``"slsqp"`` on the
/// paper's ``classical`` and ``zhang2021`` searches), ``"slsqp"`` or ``"active-set"`` (ours). ``setup`` defaults to the paper's
/// (``"zhang2021-comau-nj165"``). Deterministic for a ``seed``; returns a ``Study``.
#[pyfunction]
#[pyo3(signature = (setup=None, runs=200, seed=1, starts=16, trials=20, solver="auto"))]
pub fn reproduce(
    py: Python<'_>,
    setup: Option<&Setup>,
    runs: i64,
    seed: i64,
    starts: i64,
    trials: i64,
    solver: &str,
) -> PyResult<Study> {
    let seed = crate::count::seed("seed", seed)?;
    let options = Options {
        runs: count("runs", runs, 1, limits::MAX_RUNS)?,
        seed,
        starts: count("starts", starts, 1, limits::MAX_STARTS)?,
        trials: count("trials", trials, 0, limits::MAX_TRIALS)?,
        solver: solver.parse().map_err(raise)?,
    };
    let paper;
    let setup = match setup {
        Some(s) => &s.inner,
        None => {
            paper = stiffid::setup::builtin("zhang2021-comau-nj165").map_err(raise)?;
            &paper
        }
    };
    let request = job_reproduce::Request {
        setup,
        options,
        progress: &(),
    };
    let report = py.detach(|| job_reproduce::run(&request)).map_err(raise)?;
    warn(py, &report.warnings)?;
    Ok(Study { report })
}

/// The result of ``stiffid.reproduce``: every group's postures, criteria and deviation rates,
/// and the findings. Deviation rates in percent; arrays over groups in the groups' order.
#[pyclass(frozen, module = "stiffid", name = "Study")]
pub struct Study {
    report: job_reproduce::Report,
}

#[pymethods]
impl Study {
    /// Seed of everything random.
    #[getter]
    fn seed(&self) -> u64 {
        self.study().seed
    }

    /// Monte Carlo runs per group and noise level.
    #[getter]
    fn runs(&self) -> usize {
        self.study().runs
    }

    /// Wall time of the study, s.
    #[getter]
    fn elapsed_s(&self) -> f64 {
        self.study().elapsed_s
    }

    /// The noise levels, multiples of the variance, shape ``(levels,)``.
    #[getter]
    fn level_multiples<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arrays::vec1(py, self.study().setup.noise().levels.iter().copied())
    }

    /// The noise level (0-based) whose mean stiffness is validated: the one nearest multiple 1.
    #[getter]
    fn validation_level(&self) -> usize {
        self.study().validation_level
    }

    /// The groups' names, e.g. ``"group3-zhang2021"``.
    #[getter]
    fn names(&self) -> Vec<String> {
        self.study().groups.iter().map(|g| g.name.clone()).collect()
    }

    /// The groups' titles, e.g. ``"Group 3 (zhang2021, local)"`` (the legend of Fig. 8).
    #[getter]
    fn titles(&self) -> Vec<String> {
        self.study()
            .groups
            .iter()
            .map(|g| g.title.clone())
            .collect()
    }

    /// Mean deviation rate ``|k_id - k_true| / k_true`` over the runs, %, shape
    /// ``(groups, levels, 6)`` (Fig. 8, Table 4).
    #[getter]
    fn mean_deviation_pct<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f64>> {
        self.rates(py, |s| &s.mean_deviation_pct)
    }

    /// Sample standard deviation of the deviation rate, %, shape ``(groups, levels, 6)``.
    #[getter]
    fn std_deviation_pct<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f64>> {
        self.rates(py, |s| &s.std_deviation_pct)
    }

    /// First-order predicted mean deviation rate, %, shape ``(groups, levels, 6)``.
    #[getter]
    fn predicted_deviation_pct<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f64>> {
        self.rates(py, |s| &s.predicted_deviation_pct)
    }

    /// Each group's mean over levels and joints of the mean deviation rate, %, shape
    /// ``(groups,)``.
    #[getter]
    fn average_deviation_pct<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let g = &self.study().groups;
        arrays::vec1(py, g.iter().map(|g| g.average_deviation_pct()))
    }

    /// One dict per group, the groups of ``summary.json`` (``to_dict()["groups"]``): ``name``,
    /// ``title``, ``criterion`` (None for the start group), ``search`` (how it was found, in
    /// words), ``search_evaluations``, ``postures_deg``, the criteria of ``Setup.evaluate``
    /// (``classical`` ... ``cond_psi``), ``mean_deviation_pct``, ``std_deviation_pct``,
    /// ``predicted_deviation_pct``, ``mean_stiffness_nm_per_rad`` (``(levels, 6)``),
    /// ``average_deviation_pct`` and ``validation_error_mm`` (``(test postures, measuring
    /// points)``); the arrays as NumPy arrays.
    #[getter]
    fn groups<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let out = PyList::empty(py);
        let arrays: Vec<&str> = RATES.into_iter().chain(GROUP_ARRAYS).collect();
        for g in Summary::new(&self.report).groups {
            out.append(to_python(py, &g, &arrays)?)?;
        }
        Ok(out)
    }

    /// The document of ``stiffid reproduce``'s ``summary.json``, as dicts and lists: the
    /// resolved setup, the options, every group and the findings (in numbers and in words).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        to_python(py, &Summary::new(&self.report), &[])
    }

    /// What the study found: the ``findings`` of ``summary.json`` (``to_dict()["findings"]``),
    /// ``group3_beats_groups_1_and_2``, ``group3_factor_vs_group1``,
    /// ``group3_factor_vs_group2``, ``relative_a_factor_vs_group3`` (factors of average deviation
    /// rates, > 1: Group 3 better; ``None`` where a group is missing),
    /// ``start_groups_where_zhang2021_beats_both``, ``start_groups``,
    /// ``prediction_mean_abs_relative_error`` and ``sentences`` (the findings in words).
    #[getter]
    fn findings<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        to_python(py, &Summary::new(&self.report).findings, &[])
    }

    fn __repr__(&self) -> String {
        format!(
            "Study(groups={}, runs={}, seed={})",
            self.study().groups.len(),
            self.study().runs,
            self.study().seed
        )
    }
}

/// The keys of a study's group returned as NumPy arrays, besides [`RATES`].
const GROUP_ARRAYS: [&str; 2] = ["postures_deg", "validation_error_mm"];

impl Study {
    fn study(&self) -> &study::Study {
        &self.report.study
    }

    /// A rate of every group's simulation as a `(groups, levels, 6)` array.
    fn rates<'py>(
        &self,
        py: Python<'py>,
        rate: impl Fn(&GroupSimulation) -> &Vec<[f64; 6]>,
    ) -> Bound<'py, PyArray3<f64>> {
        let g = &self.study().groups;
        let levels = self.study().setup.noise().levels.len();
        Array3::from_shape_fn((g.len(), levels, 6), |(i, l, j)| {
            rate(&g[i].simulation)[l][j]
        })
        .into_pyarray(py)
    }
}
