//! `stiffid.simulate` and `stiffid.reproduce`: the Monte Carlo identification of groups of
//! postures and the paper's simulation study, over [`stiffid::internal::design::study::simulate`] and [`stiffid::internal::design::study`].

use crate::documents::{to_json, to_python, warn};
use crate::error::{raise, value};
use crate::setup::Setup;
use pyo3::prelude::*;
use pyo3::types::{PyAny, PyDict, PyList};
use stiffid::app::reproduce as job_reproduce;
use stiffid::app::simulate as job;
use stiffid::internal::common::limits::{self, check_count};
use stiffid::internal::design::study::simulate as monte_carlo;
use stiffid::internal::design::study::Options;

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
    #[pyo3(from_py_with = crate::count::whole)] runs: i64,
    #[pyo3(from_py_with = crate::count::seed_of)] seed: u64,
) -> PyResult<Bound<'py, PyList>> {
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
        progress: &(),
    };
    let outcome = py.detach(|| job::run(&request)).map_err(raise)?;
    warn(py, &outcome.warnings)?;
    let out = PyList::empty(py);
    for g in &outcome.report.groups {
        out.append(to_python(py, g, &RATES)?)?;
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
/// (``"zhang2021-comau-nj165"``). Deterministic for a ``seed``. Returns the document of
/// ``stiffid reproduce``'s ``summary.json`` as a dict (the same keys and values): ``setup``,
/// ``seed``, ``runs``, ``levels`` (the noise levels, multiples of the variance), ``validation_level``,
/// ``elapsed_s``, ``test_deflection_mm``, ``groups`` (one dict per group: ``name``, ``title``,
/// ``criterion``, ``search``, ``search_evaluations``, ``postures_deg``, the criteria of
/// ``Setup.evaluate``, ``mean_deviation_pct``, ``std_deviation_pct``, ``predicted_deviation_pct``,
/// ``mean_stiffness_nm_per_rad`` (``(levels, 6)``), ``average_deviation_pct``,
/// ``validation_error_mm``), ``start_trials`` and ``findings`` (in numbers and in words); the
/// arrays as NumPy arrays. ``figures=True`` adds ``figures``: the figures of ``stiffid
/// reproduce``'s report as SVG documents (str) keyed by name, byte for byte its
/// ``figures/<name>.svg``: ``deviation_vs_noise``, ``table4_level2``, ``criteria_vs_deviation``
/// and ``postures_<group>`` per group.
#[pyfunction]
#[pyo3(signature = (setup=None, runs=200, seed=1, starts=16, trials=20, solver="auto", figures=false))]
#[allow(clippy::too_many_arguments)]
pub fn reproduce<'py>(
    py: Python<'py>,
    setup: Option<&Setup>,
    #[pyo3(from_py_with = crate::count::whole)] runs: i64,
    #[pyo3(from_py_with = crate::count::seed_of)] seed: u64,
    #[pyo3(from_py_with = crate::count::whole)] starts: i64,
    #[pyo3(from_py_with = crate::count::whole)] trials: i64,
    solver: &str,
    figures: bool,
) -> PyResult<Bound<'py, PyDict>> {
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
            paper = stiffid::internal::setup::builtin("zhang2021-comau-nj165").map_err(raise)?;
            &paper
        }
    };
    let request = job_reproduce::Request {
        setup,
        options,
        progress: &(),
    };
    let outcome = py.detach(|| job_reproduce::run(&request)).map_err(raise)?;
    warn(py, &outcome.warnings)?;
    let out = study_document(py, outcome.written())?;
    if figures {
        let drawings = stiffid_figures::reproduce::figures(&outcome.study);
        out.set_item("figures", crate::figures::svgs(py, &drawings)?)?;
    }
    Ok(out)
}

/// The keys of a study's group returned as NumPy arrays, besides [`RATES`].
const GROUP_ARRAYS: [&str; 2] = ["postures_deg", "validation_error_mm"];

/// The keys of a study's document returned as NumPy arrays (its groups' besides).
const STUDY_ARRAYS: [&str; 2] = ["levels", "test_deflection_mm"];

/// The document `report` is written as (``summary.json``) as a dict, with [`STUDY_ARRAYS`] and
/// each group's [`RATES`] and [`GROUP_ARRAYS`] as NumPy arrays.
fn study_document<'py>(
    py: Python<'py>,
    report: &job_reproduce::Report,
) -> PyResult<Bound<'py, PyDict>> {
    let summary = to_json(report)?;
    let out = to_python(py, &summary, &STUDY_ARRAYS)?;
    let groups = PyList::empty(py);
    let arrays: Vec<&str> = RATES.into_iter().chain(GROUP_ARRAYS).collect();
    for g in summary["groups"].as_array().into_iter().flatten() {
        groups.append(to_python(py, g, &arrays)?)?;
    }
    out.set_item("groups", groups)?;
    Ok(out)
}
