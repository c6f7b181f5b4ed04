//! `Setup.evaluate` and `Setup.select`: the library's evaluate and select jobs
//! ([`stiffid::app::evaluate`], [`stiffid::app::select`]), their documents as dicts.

use crate::documents::{to_python, warn};
use crate::error::{raise, value};
use nalgebra::Vector6;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use stiffid::app::purpose::{CalibrationOptions, Purpose};
use stiffid::app::{evaluate, select};
use stiffid::internal::common::choice::Choice;
use stiffid::internal::common::limits::{self, check_count};
use stiffid::internal::design::distinct::Distinctness;
use stiffid::internal::design::SearchOptions;
use stiffid::Setup;

/// The keys of the evaluate document returned as NumPy arrays.
const CRITERIA_ARRAYS: [&str; 2] = ["relative_std", "predicted_deviation_pct"];

/// What a group is designed for, as Python gives it: `purpose` (`stiffness`, `calibration`,
/// `both` or `check`, the command's `--for`) and the calibration's options (`calibration_criterion`,
/// `geometry`, `gravity`, `weight`), which the library checks against the purpose.
pub struct For<'a> {
    pub purpose: &'a str,
    pub calibration_criterion: Option<&'a str>,
    pub geometry: Option<&'a str>,
    pub gravity: Option<&'a str>,
    pub weight: Option<f64>,
}

impl For<'_> {
    /// The purpose and the calibration options, each name parsed.
    fn parse(&self) -> PyResult<(Purpose, CalibrationOptions)> {
        let purpose = self.purpose.parse::<Purpose>().map_err(|_| {
            let known: Vec<&str> = Purpose::ALL.iter().map(|p| p.name()).collect();
            value(format!(
                "purpose: '{}' is not a purpose (known: {})",
                self.purpose,
                known.join(", ")
            ))
        })?;
        let options = CalibrationOptions {
            criterion: (self.calibration_criterion.map(str::parse))
                .transpose()
                .map_err(raise)?,
            geometry: self.geometry.map(str::parse).transpose().map_err(raise)?,
            gravity: self.gravity.map(str::parse).transpose().map_err(raise)?,
            weight: self.weight,
        };
        Ok((purpose, options))
    }
}

/// The evaluate document of a group (see `Setup.evaluate`), its warnings raised.
pub fn evaluate<'py>(
    py: Python<'py>,
    setup: &Setup,
    group: &[Vector6<f64>],
    candidates: Option<Vec<String>>,
    purpose: &For,
) -> PyResult<Bound<'py, PyDict>> {
    let (purpose, calibration) = purpose.parse()?;
    let request = evaluate::Request {
        purpose,
        calibration,
        setup,
        postures: group,
        candidates,
    };
    let outcome = py.detach(|| evaluate::run(&request)).map_err(raise)?;
    warn(py, &outcome.warnings)?;
    to_python(py, outcome.written(), &CRITERIA_ARRAYS)
}

/// The arguments of `Setup.select`, the shapes of the arrays checked.
pub struct Request<'a> {
    /// The stiffness criterion; relative-a when `None`.
    pub criterion: Option<&'a str>,
    pub method: Option<&'a str>,
    /// Checked against the setup's bounds.
    pub start: Option<Vec<Vector6<f64>>>,
    pub n: Option<usize>,
    pub seed: u64,
    pub starts: Option<usize>,
    pub screen_steps: Option<usize>,
    pub polished: Option<usize>,
    pub max_evals: Option<usize>,
    pub gradient: &'a str,
    pub solver: &'a str,
    /// Checked against the robot's joint limits.
    pub pool: Option<Vec<Vector6<f64>>>,
    pub restarts: Option<usize>,
    pub target_pct: Option<f64>,
    /// mm.
    pub margin_mm: Option<f64>,
    pub for_candidates: bool,
    pub candidates: Option<Vec<String>>,
    /// Forbid near postures of a pool, by these distances (deg, mm; the defaults when None).
    pub distinct: bool,
    pub distinct_deg: Option<f64>,
    pub distinct_mm: Option<f64>,
    /// Stations of a robot with external axes, each in the cell's order, mm and deg.
    pub stations: Vec<Vec<f64>>,
    /// What the group is for.
    pub purpose: For<'a>,
}

/// Runs the select job (the GIL released) and returns its document, its warnings raised.
pub fn select<'py>(py: Python<'py>, setup: &Setup, r: Request) -> PyResult<Bound<'py, PyDict>> {
    let method = match (r.method, &r.start, &r.pool) {
        (Some(m), _, _) => m.parse().map_err(raise)?,
        (None, Some(_), _) => select::Method::Local,
        (None, None, Some(_)) => select::Method::Pool,
        (None, None, None) => select::Method::Global,
    };
    if !r.distinct && (r.distinct_deg.is_some() || r.distinct_mm.is_some()) {
        return Err(value("distinct_deg, distinct_mm: only with distinct=True"));
    }
    let distinct = match r.distinct {
        true => Some(Distinctness::try_from_deg_mm(r.distinct_deg, r.distinct_mm).map_err(raise)?),
        false => None,
    };
    let n = match (&r.start, r.n) {
        (Some(s), Some(n)) if s.len() != n => {
            return Err(value(format!(
                "n = {n} but start holds {} postures: give one or the other",
                s.len()
            )))
        }
        (Some(s), _) => s.len(),
        (None, n) => n.unwrap_or(r.purpose.parse()?.0.default_postures()),
    };
    check_postures(n)?;
    let mut options = SearchOptions {
        seed: r.seed,
        gradient: r.gradient.parse().map_err(raise)?,
        solver: r.solver.parse().map_err(raise)?,
        ..SearchOptions::default()
    };
    let defaults = [&mut options.starts, &mut options.screen_steps];
    for (slot, given) in defaults.into_iter().zip([r.starts, r.screen_steps]) {
        *slot = given.unwrap_or(*slot);
    }
    options.polished = r.polished.unwrap_or(options.polished);
    options.max_evals = r.max_evals.unwrap_or(options.max_evals);
    options.margin = r.margin_mm.map(|m| m * 1e-3);
    let (purpose, calibration) = r.purpose.parse()?;
    let given = select::Given {
        criterion: r.criterion.is_some(),
        starts: r.starts.is_some(),
        screen_steps: r.screen_steps.is_some(),
        polished: r.polished.is_some(),
        search: select::Given::search_of(r.max_evals.is_some(), options.gradient, options.solver),
        start: r.start.is_some(),
        seed: select::Given::seed_of(r.seed),
    };
    select::check_given(purpose, method, given).map_err(raise)?;
    let request = select::Request {
        setup,
        criterion: r.criterion.unwrap_or("relative-a").parse().map_err(raise)?,
        purpose,
        calibration,
        method,
        start: r.start,
        pool: r.pool.map(|postures| select::PoolInput {
            name: "arrays".into(),
            postures,
        }),
        postures: n,
        target_pct: r.target_pct,
        options,
        restarts: r.restarts,
        distinct,
        for_candidates: r.for_candidates,
        candidates: r.candidates,
        stations: stations(setup, &r.stations)?,
        progress: &(),
        out: None,
        report_dir: None,
    };
    let outcome = py.detach(|| select::run(&request)).map_err(raise)?;
    warn(py, &outcome.warnings)?;
    to_python(py, outcome.written(), &["postures_deg"])
}

/// The size of a searched group: 2 to 100 postures.
pub fn check_postures(n: usize) -> PyResult<()> {
    let most = limits::MAX_SEARCH_POSTURES as usize;
    check_count("n", n, 2, most).map_err(raise)
}

/// The stations (mm, deg, the cell's order) in SI, each with one value per external axis.
fn stations(
    setup: &Setup,
    given: &[Vec<f64>],
) -> PyResult<Vec<stiffid::internal::robot::external::ExternalValues>> {
    let Some(axes) = setup.robot().external() else {
        return match given.is_empty() {
            true => Ok(Vec::new()),
            false => Err(value("stations: the robot has no external axes: give none")),
        };
    };
    given
        .iter()
        .map(|s| {
            if s.len() != axes.len() {
                return Err(value(format!(
                    "stations: expected {} values per station ({}), got {}",
                    axes.len(),
                    axes.column_names().join(", "),
                    s.len()
                )));
            }
            stiffid::internal::robot::external::ExternalValues::new(&axes.to_si(s)).map_err(raise)
        })
        .collect()
}
