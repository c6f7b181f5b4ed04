//! The select job: the group of postures that minimises a design criterion (Zhang et al. 2021,
//! Section III), by a local SQP search from a start group, a global multistart search, or the
//! best group of a pool of postures; optionally the smallest group for a target accuracy
//! ([`stiffid_design::target`]), and the same search without the cell's checks (what they cost).

mod campaign;
mod check;
mod choose;
pub mod document;
mod pool;
mod station;
mod table;

use check::check;
pub use check::{check_given, Given};
pub(crate) use station::Station;
pub use table::CANDIDATE_ANGLES;

use choose::{choose, smallest, unconstrained};
use pool::{in_pool, Candidates};

use super::purpose::{self, CalibrationOptions, Purpose};
use crate::app::Warning;
use nalgebra::Vector6;
use std::time::Instant;
use stiffid_core::common::error::JobOption;
use stiffid_core::common::progress::Progress;
use stiffid_core::{Error, Result, Setup};
use stiffid_design::candidates::{self, Verdicts};
use stiffid_design::distinct::{Distinctness, Near};
use stiffid_design::identifiable;
use stiffid_design::observability::{CalibrationCriteria, CalibrationCriterion, CalibrationDesign};
use stiffid_design::selection::search::in_cell;
use stiffid_design::target::TargetOutcome;
use stiffid_design::{
    evaluate, Criterion, Evaluation, Gradient, PoolMethod, SearchOptions, Solver, Termination,
};

/// How the group is chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// One SQP search from a start group ([`stiffid_design::local`]).
    Local,
    /// Local searches from seeded start groups, the best kept ([`stiffid_design::global`]).
    Global,
    /// The best group of a pool of postures ([`stiffid_design::Pool::best`]).
    Pool,
}

impl Method {
    /// Every method.
    pub(crate) const ALL: [Method; 3] = [Method::Local, Method::Global, Method::Pool];
}

impl stiffid_core::common::choice::Choice for Method {
    const FIELD: &'static str = "method";
    const ALL: &'static [Self] = &Method::ALL;
    fn name(self) -> &'static str {
        match self {
            Method::Local => "local",
            Method::Global => "global",
            Method::Pool => "pool",
        }
    }
    fn help(self) -> &'static str {
        match self {
            Method::Local => "One SQP search from a start group",
            Method::Global => "Local searches from seeded start groups, the best kept",
            Method::Pool => "The best group of a pool of postures",
        }
    }
}

stiffid_core::common::choice::by_name!(Method);

/// A pool of candidate postures.
#[derive(Debug, Clone)]
pub struct PoolInput {
    /// Its name in the report and in errors: a file's name, or `arrays`.
    pub name: String,
    /// The postures (axis angles, rad, within the robot's joint limits), at most
    /// [`MAX_POOL`](stiffid_design::pool::MAX_POOL); those that fail a check of the cell are reported and skipped.
    pub postures: Vec<Vector6<f64>>,
}

/// What to select and how.
#[derive(Clone)]
pub struct Request<'a> {
    /// The setup: robot, tool, load, noise, nominal stiffness, bounds, cell, model.
    pub setup: &'a Setup,
    /// The stiffness criterion to minimise ([`Purpose::Stiffness`] or [`Purpose::Both`]).
    pub criterion: Criterion,
    /// What the group is for: the stiffness identification, the calibration, or both.
    pub purpose: Purpose,
    /// The calibration the group is designed for ([`Purpose::Calibration`] or
    /// [`Purpose::Both`]; [`purpose::design`]).
    pub calibration: CalibrationOptions,
    /// How.
    pub method: Method,
    /// [`Method::Local`] only: the start group (axis angles, rad, within the setup's bounds;
    /// 2 to [`MAX_SEARCH_POSTURES`](stiffid_core::common::limits::MAX_SEARCH_POSTURES) postures); `None` for a seeded random group
    /// ([`stiffid_design::random_group`]).
    pub start: Option<Vec<Vector6<f64>>>,
    /// [`Method::Pool`] only, and then required: the pool.
    pub pool: Option<PoolInput>,
    /// The group size (2 to [`MAX_SEARCH_POSTURES`](stiffid_core::common::limits::MAX_SEARCH_POSTURES)); the start group's size with a
    /// start group; unused with a target.
    pub postures: usize,
    /// The smallest group whose predicted mean deviation rate at noise level multiple 1 is at
    /// most this many percent on every parameter
    /// ([`stiffid_core::common::limits::TARGET_PCT`]; [`Method::Global`] or [`Method::Pool`];
    /// [`Purpose::Stiffness`] only).
    pub target_pct: Option<f64>,
    /// The budget and tolerances of the searches; its seed seeds the random start group, the
    /// global starts and the pool's exchange runs.
    pub options: SearchOptions,
    /// [`Method::Pool`] only: exchange runs of the pool choice (1 to
    /// [`MAX_POOL_RESTARTS`](stiffid_core::common::limits::MAX_POOL_RESTARTS)); `None` for [`PoolOptions`](stiffid_design::PoolOptions)' default.
    pub restarts: Option<usize>,
    /// Forbid postures that are not distinct by these distances ([`Method::Pool`] only: the
    /// pool keeps the first of every near pair, [`stiffid_design::distinct::distinct_pool`]);
    /// `None` allows them. Either way the group's near pairs are flagged, by these distances or
    /// the defaults.
    pub distinct: Option<Distinctness>,
    /// Design for the setup's model and the candidates of the model comparison together
    /// ([`stiffid_design::candidates`]): the search runs on the setup with every linear candidate
    /// added to its model, and the report says how the group identifies each candidate.
    /// [`Purpose::Stiffness`] only, without a target.
    pub for_candidates: bool,
    /// With `for_candidates`: the candidates, as `identify --compare-models --candidates` names
    /// them (families or single candidates); `None` for the default pool.
    pub candidates: Option<Vec<String>>,
    /// For a robot with external axes (a track, [`stiffid_core::robot::external`]): where the arm
    /// stands for the whole group, each station one value per axis (SI, the cell's order); with
    /// several, the group is designed at each and the best kept ([`Station`]); for
    /// [`Purpose::Calibration`] on a robot with a carrier, the group is one campaign over all
    /// of them, its postures dealt over the stations and designed together with the track's
    /// parameters ([`Report::placed`]). Empty for a robot without external axes;
    /// 1 to `MAX_STATIONS` with them (empty on a cell whose only external axes are a
    /// positioner's: the positioner at zero).
    pub stations: Vec<stiffid_core::robot::external::ExternalValues>,
    /// Where the searches report their progress (`&()` for nowhere): each search begins a stage
    /// (`global search (relative-a)` with its starts as the total; a local search and the choice
    /// from a pool with total 0).
    pub progress: &'a dyn Progress,
    /// The postures file the front end writes, as the document names it (the command's
    /// `--out`); `None` when it writes none.
    pub out: Option<String>,
    /// The measurement plan's directory the front end writes, as the document names it (the
    /// command's `--report`); `None` when it writes none.
    pub report_dir: Option<String>,
}

pub(crate) use stiffid_design::distinct::{DISTINCT_DEG, DISTINCT_MM};

/// What the selection found. It serialises to its document, `stiffid select --json`, through
/// the borrowed view [`document::Document`] ([`Report::document`]: mm and deg, units in every
/// key), built as it is written.
#[derive(Debug, Clone)]
pub struct Report {
    /// The setup's name.
    pub setup: String,
    /// The robot's external axes (their names and units, which name the stations' values in the
    /// document), `None` without.
    pub external_axes: Option<stiffid_core::robot::external::ExternalAxes>,
    /// How it was chosen.
    pub method: Method,
    /// The stiffness criterion minimised (unused for [`Purpose::Calibration`]).
    pub criterion: Criterion,
    /// What the group is for.
    pub purpose: Purpose,
    /// With [`Purpose::Calibration`] or [`Purpose::Both`]: the calibration criteria of the group.
    pub calibration: Option<CalibrationReport>,
    /// The seed.
    pub seed: u64,
    /// The gradient of the searches; `None` for a pool choice.
    pub gradient: Option<Gradient>,
    /// The SQP the searches ran ([`Solver::resolve`]d for the criterion: never
    /// [`Solver::Auto`]); `None` for a pool choice.
    pub solver: Option<Solver>,
    /// The group chosen (axis angles, rad).
    pub postures: Vec<Vector6<f64>>,
    /// The value minimised for the start group (`None` for a pool choice): the stiffness
    /// criterion, the calibration criterion's loss (`CalibrationCriterion::loss`) or their
    /// weighted geometric mean ([`Goal`](stiffid_design::Goal)).
    pub start_value: Option<f64>,
    /// The value minimised for the group chosen.
    pub value: f64,
    /// Criterion evaluations, over every group size tried with a target.
    pub evaluations: usize,
    /// Why every local search of the last search stopped ([`SearchOutcome::terminations`](stiffid_design::SearchOutcome::terminations)); empty
    /// for a pool choice.
    pub terminations: Vec<Termination>,
    /// Why the search that found the group stopped; `None` for a pool choice.
    pub termination: Option<Termination>,
    /// Wall-clock time of the selection, s.
    pub elapsed_s: f64,
    /// Every criterion of the group chosen.
    pub evaluation: Evaluation,
    /// With a pool: what it held and what was chosen.
    pub pool: Option<PoolReport>,
    /// With a target: every group size tried.
    pub target: Option<TargetOutcome>,
    /// With cell checks, for a local or global search without a target: the same search without
    /// them.
    pub unconstrained: Option<Unconstrained>,
    /// The pairs of postures of the group that are not distinct ([`stiffid_design::distinct`]),
    /// by the request's distances or the defaults.
    pub near: Vec<Near>,
    /// The margin every posture was chosen to keep to every constraint of the cell, m
    /// (the request's, else the tracker's registration uncertainty, else 0).
    pub margin: f64,
    /// Each chosen posture's smallest margin to a constraint of the cell's lengths (m, from the
    /// exact checks: [`stiffid_core::cell::Feasibility::min_margin`]; the tool, where the rope and the
    /// lines of sight start, counted beyond `margin` as the design keeps it), `None` without
    /// such checks.
    pub min_margins: Vec<Option<f64>>,
    /// With [`Request::for_candidates`]: what the design was for and how the group identifies
    /// each candidate.
    pub candidates: Option<CandidatesReport>,
    /// The job's warnings: one per pair of `near`.
    pub warnings: Vec<Warning>,
    /// With external axes: the station of the group (its postures are measured there).
    pub station: Option<stiffid_core::robot::external::ExternalValues>,
    /// With external axes: every station tried and its group's value, in the request's order;
    /// for a campaign over the stations, the campaign's value with the postures up to each.
    pub stations: Vec<Station>,
    /// A campaign over several stations: where each posture is read (the external axes' values,
    /// SI, the cell's order), in the order of `postures`; with reflectors on a positioner's
    /// table ([`Purpose::Calibration`]), each posture's station with the positioner's angles
    /// chosen for the table's readings at that posture (`table`); empty otherwise.
    pub placed: Vec<stiffid_core::robot::external::ExternalValues>,
    /// The postures file the front end writes ([`Request::out`]).
    pub out: Option<String>,
    /// The measurement plan's directory the front end writes ([`Request::report_dir`]).
    pub report_dir: Option<String>,
}

/// A design for the candidates ([`Request::for_candidates`]).
#[derive(Debug, Clone)]
pub struct CandidatesReport {
    /// The linear candidates designed for (added to the model of the design), by name: the
    /// designable ones.
    pub designed: Vec<String>,
    /// How the group chosen identifies each candidate of the pool with the setup's model (and
    /// the linear candidates no group can identify with the others, `designable.left_out`).
    pub verdicts: Verdicts,
}

/// The calibration a group was designed for, and its criteria.
#[derive(Debug, Clone)]
pub struct CalibrationReport {
    /// The calibration criterion minimised.
    pub criterion: CalibrationCriterion,
    /// The options (criterion, geometry, gravity, weight).
    pub options: CalibrationOptions,
    /// Every calibration criterion of the group chosen.
    pub criteria: CalibrationCriteria,
    /// The weight of the calibration's log-criterion (1 for [`Purpose::Calibration`]).
    pub weight: f64,
}

/// A pool, and what was chosen from it.
#[derive(Debug, Clone)]
pub struct PoolReport {
    /// Its name.
    pub name: String,
    /// Postures in the pool.
    pub total: usize,
    /// Postures that pass every check of the cell.
    pub usable: usize,
    /// The postures skipped, and why.
    pub skipped: Vec<Skipped>,
    /// How the group was chosen.
    pub method: PoolMethod,
    /// The chosen postures' numbers in the pool (1-based), ascending.
    pub chosen: Vec<usize>,
    /// With [`Request::distinct`]: the usable postures left out because they are near one kept
    /// before them, `(left out, kept)`, numbers in the pool (1-based).
    pub not_distinct: Vec<(usize, usize)>,
}

pub(crate) use stiffid_design::selection::pool::Skipped;
pub(crate) use stiffid_design::selection::search::Unconstrained;

impl Report {
    /// The document this report is written as (`stiffid select --json`, Python's
    /// `Setup.select`), to read: what the command's text and campaign plan print.
    pub fn document(&self) -> document::Document<'_> {
        document::Document::new(self)
    }
}

impl serde::Serialize for Report {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        self.document().serialize(s)
    }
}

/// The select job's report, which is its document (serialised through
/// [`document::Document`]).
pub(crate) type Outcome = crate::app::Outcome<Report>;

/// Selects the group.
///
/// # Errors
/// [`Error::InvalidOption`] for a start group or target that does not fit the method
/// ([`JobOption::Start`], [`JobOption::TargetPct`]); [`Error::InvalidField`] for a pool that does
/// not (`pool`) or a count out of range (`postures`, `restarts`, the search options); the
/// pool's errors named by it (more postures asked for than pass the cell's checks, naming the
/// checks failed most often); a target that no group size reaches ([`JobOption::TargetPct`], naming the best
/// rate reachable); with `for_candidates`: [`JobOption::ForCandidates`] with another purpose, a
/// target or too few postures for the model and the candidates (naming the count needed),
/// [`JobOption::Candidates`] without it, those of [`candidates::pool`] and
/// [`candidates::design_setup`]; the searches' errors; a group that cannot identify every parameter (for a calibration: separate its parameters, [`Error::Input`] of an [`Error::InvalidField`] `calibration`).
pub fn run(request: &Request) -> Result<Outcome> {
    let setup = request.setup;
    let report = Report {
        setup: setup.name().into(),
        external_axes: setup.robot().external().cloned(),
        out: request.out.clone(),
        report_dir: request.report_dir.clone(),
        ..find(request)?
    };
    Ok(Outcome {
        report,
        document: crate::app::Itself,
    })
}

/// What [`run`] finds, without the names [`run`] gives it (the setup's, its external axes', the
/// front end's files).
fn find(request: &Request) -> Result<Report> {
    check(request)?;
    table::check(request)?;
    let report = if campaign::is_campaign(request) {
        station::checked(request)?;
        campaign::campaign(request)?
    } else {
        match request.setup.robot().external().is_some() || !request.stations.is_empty() {
            true => station::at_stations(request, run_here)?,
            false => run_here(request)?,
        }
    };
    table::with_table(request, report)
}

/// [`run`] on the request's setup as it stands.
fn run_here(request: &Request) -> Result<Report> {
    if !request.for_candidates {
        return run_on(request);
    }
    let setup = request.setup;
    let pool = candidates::pool(setup, request.candidates.as_deref())?;
    let (design, _) = candidates::design_setup(setup, &pool)?;
    check_for_candidates(request, &design)?;
    let on_design = Request {
        setup: &design,
        for_candidates: false,
        candidates: None,
        ..request.clone()
    };
    let mut report = run_on(&on_design)?;
    let springs = design.model().springs()[setup.model().springs().len()..].iter();
    report.candidates = Some(CandidatesReport {
        designed: springs.map(|s| s.name.clone()).collect(),
        verdicts: candidates::verdicts(setup, &report.postures, &pool)?,
    });
    Ok(report)
}

/// Refuses a design for the candidates that cannot identify them: fewer postures than the model
/// and the linear candidates need ([`candidates::fewest_postures`]).
fn check_for_candidates(r: &Request, design: &Setup) -> Result<()> {
    let (n, parameters) = (size(r), design.model().len());
    let fewest = candidates::fewest_postures(design, parameters);
    if n >= fewest {
        return Ok(());
    }
    Err(Error::InvalidOption {
        option: JobOption::ForCandidates,
        message: format!(
            "the model and the {} candidates a design can identify together are {parameters} parameters, which {n} postures cannot identify: each posture gives at most {} independent rows, so at least {fewest} postures are needed (or name fewer candidates)",
            parameters - r.setup.model().len(),
            (3 * design.tool().measuring_points.len()).min(6)
        ),
    })
}

/// [`run`] on the request's setup, without the candidates.
fn run_on(request: &Request) -> Result<Report> {
    let design = match request.purpose {
        Purpose::Stiffness => None,
        _ => Some(purpose::design(
            request.setup,
            &request.calibration.of(request.purpose),
        )?),
    };
    let goal = purpose::goal(
        request.purpose,
        request.criterion,
        design.as_ref(),
        &request.calibration.of(request.purpose),
    );
    let pool = request
        .pool
        .as_ref()
        .map(|p| pool::screened(request, p))
        .transpose()?;
    let started = Instant::now();
    let (found, target) = match request.target_pct {
        None => (
            choose(request, &goal, request.setup, pool.as_ref(), size(request))?,
            None,
        ),
        Some(pct) => {
            let (found, outcome) = smallest(request, pool.as_ref(), pct)?;
            (found, Some(outcome))
        }
    };
    let elapsed_s = started.elapsed().as_secs_f64();
    if !request.purpose.calibration_only() {
        identifiable(request.setup, &found.postures).map_err(|e| Error::Input {
            source_name: "postures: the best group the search found".into(),
            error: Box::new(e),
        })?;
    }
    if let (Some(d), false) = (&design, found.value.is_finite()) {
        return Err(Error::Input {
            source_name: "postures: the best group the search found".into(),
            error: Box::new(Error::InvalidField {
                field: "calibration".into(),
                message: format!(
                    "the {} postures do not separate the calibration's {} parameters (its predicted error is infinite): choose more postures or measuring points, or a smaller --geometry",
                    found.postures.len(),
                    d.kept().len()
                ),
            }),
        });
    }
    let distances = request.distinct.unwrap_or_default();
    let margin = request.options.margin;
    let postures = std::slice::from_ref(&found.postures);
    let held = in_cell(request.setup, postures, &[], margin, &distances)?;
    let unconstrained = match pool.is_none() && target.is_none() {
        true => unconstrained(request, &goal, found.postures.len())?,
        false => None,
    };
    let calibration = match (&design, goal.calibration) {
        (Some(d), Some(c)) => Some(calibration_report(d, request, c.weight, &found.postures)?),
        _ => None,
    };
    Ok(Report {
        method: request.method,
        criterion: request.criterion,
        purpose: request.purpose,
        calibration,
        seed: request.options.seed,
        gradient: (request.method != Method::Pool).then_some(request.options.gradient),
        solver: (request.method != Method::Pool).then(|| goal.solver(request.options.solver)),
        evaluation: evaluate(request.setup, &found.postures),
        start_value: found.start_value,
        value: found.value,
        evaluations: found.evaluations,
        termination: found.terminations.first().map(|_| found.termination),
        terminations: found.terminations,
        elapsed_s,
        pool: pool.map(|p| pool::report(p, found.chosen)),
        target,
        unconstrained,
        warnings: held.near.iter().map(Near::warning).collect(),
        station: None,
        stations: Vec::new(),
        placed: Vec::new(),
        near: held.near,
        margin: held.margin,
        min_margins: held.min_margins,
        postures: found.postures,
        candidates: None,
        // Named by `run`.
        setup: String::new(),
        external_axes: None,
        out: None,
        report_dir: None,
    })
}

/// The calibration criteria of `postures` under `design`.
fn calibration_report(
    design: &CalibrationDesign,
    request: &Request,
    weight: f64,
    postures: &[Vector6<f64>],
) -> Result<CalibrationReport> {
    Ok(CalibrationReport {
        criterion: request.calibration.of(request.purpose).criterion(),
        options: request.calibration.of(request.purpose),
        criteria: design.evaluate(postures)?,
        weight,
    })
}

/// The group size of a request without a target.
fn size(request: &Request) -> usize {
    request.start.as_ref().map_or(request.postures, Vec::len)
}
