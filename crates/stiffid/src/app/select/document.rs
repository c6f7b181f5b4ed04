//! The document of the select job ([`crate::app::select`]): `stiffid select --json`, Python's
//! `Setup.select`.

use crate::app::document::candidates::CandidatesDoc;
use crate::app::document::feasibility::describe;
use crate::app::document::group::{self, CalibrationDoc, Criteria};
use crate::app::document::{finite, units};
use crate::app::select::{CandidatesReport, PoolReport, Report, Unconstrained};
use nalgebra::Vector6;
use serde::{Serialize, Serializer};
use std::collections::BTreeMap;
use stiffid_core::common::choice::Choice;
use stiffid_core::robot::external::{ExternalAxes, ExternalValues};
use stiffid_design::distinct::Near;
use stiffid_design::target::{TargetOutcome, TargetStep};
use stiffid_design::Termination;

/// The select document: the group found, how, why the search stopped, and its criteria.
///
/// A view of the report ([`Report::document`]), built as it is written: its lengths and angles
/// are the report's, in SI, written in the units their keys name by the unit adapters
/// ([`units`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "select")]
#[cfg_attr(
    feature = "schema",
    schemars(
        description = "The select document: the group found, how, why the search stopped, and its criteria."
    )
)]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("select")))]
pub struct Document<'a> {
    /// The setup's name.
    pub setup: &'a str,
    /// What the group is designed for: `stiffness`, `calibration` or `both`.
    #[serde(rename = "for")]
    pub purpose: &'static str,
    /// The stiffness criterion minimised (`relative-a`, ...; with `for` `calibration`, the one
    /// the `criteria` are reported beside, not minimised).
    #[cfg_attr(
        feature = "schema",
        schemars(schema_with = "crate::app::document::criterion")
    )]
    pub criterion: &'static str,
    /// `local`, `global` or `pool`.
    #[cfg_attr(feature = "schema", schemars(schema_with = "schema::method"))]
    pub search: &'static str,
    /// The SQP objective's gradient (`exact` or `fd`); absent for a pool choice.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gradient: Option<&'static str>,
    /// The SQP the searches ran (`slsqp` or `active-set`: the default `auto` resolved for the
    /// criterion); absent for a pool choice.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[cfg_attr(feature = "schema", schemars(schema_with = "schema::solver"))]
    pub solver: Option<&'static str>,
    /// The seed of the random start group, the global starts or the pool's exchange runs.
    pub seed: u64,
    /// The value minimised for the start group: the stiffness criterion, the calibration
    /// criterion's loss (the reciprocal of an index, SI: 1/m or 1/m^2; the predicted RMS error,
    /// m) or, for `both`, their weighted geometric mean `c_s^(1-w) c_c^w`; `null` for a pool
    /// choice (no start group) or an infinite value.
    pub start_value: Option<f64>,
    /// The value minimised for the group found (`null` if infinite).
    pub value: Option<f64>,
    /// Criterion evaluations of the search (of every group size tried, with a target).
    pub evaluations: usize,
    /// Wall-clock time of the search, s.
    pub elapsed_s: f64,
    /// Why the local search that found the group stopped (`converged`, `step-tolerance`,
    /// `evaluation-limit`, `line-search-failed`, `infeasible`, `subproblem-failed`; only the
    /// first two say that the SQP found a local optimum); absent for a pool choice.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[cfg_attr(feature = "schema", schemars(schema_with = "schema::termination"))]
    pub termination: Option<&'static str>,
    /// With external axes (a track): where the arm stands for the group, one value per axis
    /// named as the data files' columns (`e1_mm`, `e2_deg`, ...); absent without.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub station: Option<BTreeMap<String, f64>>,
    /// With external axes: every station tried, in the request's order, with its group's value
    /// (`null` if infinite); the group is the smallest's.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub stations: Vec<StationDoc>,
    /// A calibration campaign over several stations of a track: where each posture is read
    /// (`e1_mm`, ...), in the order of `postures_deg`; `stations` then holds the campaign's
    /// value with the postures up to each station. With reflectors on a positioner's table
    /// (`for` `calibration`): each posture's station with the positioner's angles chosen for
    /// the table's readings at that posture (`e2_deg`, ...). Absent otherwise.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub posture_stations: Vec<BTreeMap<String, f64>>,
    /// How many local searches (the global search's starts; one for a local search) stopped for
    /// each reason, every reason listed; absent for a pool choice.
    #[serde(skip_serializing_if = "Option::is_none", serialize_with = "counts")]
    #[cfg_attr(feature = "schema", schemars(with = "Option<Vec<TerminationCount>>"))]
    pub terminations: Option<&'a [Termination]>,
    /// The group found, axis angles q1..q6, one row per posture: rad, written in deg.
    #[serde(rename = "postures_deg", serialize_with = "units::deg6_each")]
    #[cfg_attr(feature = "schema", schemars(with = "Vec<[f64; 6]>"))]
    pub postures: &'a [Vector6<f64>],
    /// The margin every posture was chosen to keep to every constraint of the cell (line of
    /// sight, incidence, floor, obstacles, bodies, rope, `[constraints]`): `margin_mm`, else the
    /// tracker's `registration_uncertainty_mm`, else 0: m, written in mm.
    #[serde(rename = "margin_mm", serialize_with = "units::mm_as_given")]
    pub margin: f64,
    /// Each posture's smallest margin to a constraint of the cell's lengths (every check but the
    /// bounds and the incidence), in the order of `postures_deg`; `null` without such checks: m,
    /// written in mm.
    #[serde(rename = "min_margin_mm", serialize_with = "units::mm_option_each")]
    #[cfg_attr(feature = "schema", schemars(with = "Vec<Option<f64>>"))]
    pub min_margins: &'a [Option<f64>],
    /// Every criterion of the group found.
    pub criteria: Criteria,
    /// With `for` `calibration` or `both`: the group's calibration criteria.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub calibration: Option<CalibrationDoc>,
    /// With `for` `both`: the weight `w` of the calibration's log-criterion.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub calibration_weight: Option<f64>,
    /// With a pool: the pool and the postures chosen from it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pool: Option<Pool<'a>>,
    /// With a target: every group size tried.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub target: Option<Target>,
    /// With cell checks, for a local or global search: the same search without them.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unconstrained: Option<Free<'a>>,
    /// Pairs of postures that are not distinct (axis angles within 2 deg, or the same flange
    /// pose within 10 mm and 2 deg: a wrist flip counts; or the distances of `distinct`).
    #[serde(rename = "near_postures", serialize_with = "group::near")]
    #[cfg_attr(feature = "schema", schemars(with = "Vec<group::NearDoc>"))]
    pub near: &'a [Near],
    /// With `--for-candidates`: the candidates designed for and how the group identifies each
    /// together with the setup's model (as `evaluate`'s `candidates`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub candidates: Option<ForCandidates<'a>>,
    /// The postures file written (the command's `--out`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub out: Option<&'a str>,
    /// The measurement plan's directory (the command's `--report`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub report: Option<&'a str>,
}

/// A design for the candidates of the model comparison.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct ForCandidates<'a> {
    /// The linear candidates the group was designed for (added to the model of the design, whose
    /// parameters the `criteria` are over), by name.
    pub designed: &'a [String],
    /// The lost motion and load-dependent candidates, left out of the design (what separates
    /// them is the load levels of each posture, which the postures do not give), by name.
    pub nonlinear: Vec<&'a str>,
    /// How the group chosen identifies each candidate together with the setup's model.
    #[serde(flatten)]
    pub identified: CandidatesDoc,
}

impl<'a> ForCandidates<'a> {
    /// The design for the candidates `c`.
    fn new(c: &'a CandidatesReport) -> Self {
        use stiffid_core::model::ParameterKind::{Rotation, Translation};
        Self {
            designed: &c.designed,
            nonlinear: (c.verdicts.candidates.iter())
                .filter(|v| {
                    v.needs_load_steps || !matches!(v.parameter.kind, Rotation | Translation)
                })
                .map(|v| v.parameter.name.as_str())
                .collect(),
            identified: CandidatesDoc::of(&c.verdicts),
        }
    }
}

/// How many local searches stopped for one reason.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub(crate) struct TerminationCount {
    /// The reason.
    #[cfg_attr(feature = "schema", schemars(schema_with = "schema::termination"))]
    pub termination: &'static str,
    /// Local searches that stopped for it.
    pub searches: usize,
}

/// The pool and what was chosen from it.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Pool<'a> {
    /// The pool file (`arrays` for a pool given as arrays).
    pub file: &'a str,
    /// Postures in the pool.
    pub postures: usize,
    /// Postures that pass every check of the cell.
    pub usable: usize,
    /// The postures skipped, and why.
    pub skipped: Vec<Skipped>,
    /// How the group was chosen (`enumeration` or `exchange`).
    pub method: &'static str,
    /// The chosen postures' numbers in the pool (1-based).
    pub chosen: &'a [usize],
    /// With `distinct`: the usable postures left out because they are near one kept before
    /// them, `[left out, kept]`, numbers in the pool (1-based).
    #[cfg_attr(feature = "schema", schemars(with = "Vec<[usize; 2]>"))]
    pub not_distinct: &'a [(usize, usize)],
}

/// A pool posture that cannot be measured, and why.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Skipped {
    /// Its number in the pool (1-based).
    pub posture: usize,
    /// The checks it fails (`floor`, `rope`, ...).
    pub checks: Vec<&'static str>,
    /// Every failing check in words, `; `-separated.
    pub reason: String,
}

/// The group sizes tried for a target.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Target {
    /// The target: predicted mean deviation rate at noise level multiple 1, percent.
    pub target_pct: f64,
    /// The size of the group chosen.
    pub postures: usize,
    /// Every group size tried, smallest first.
    pub steps: Vec<Step>,
}

/// One group size tried.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Step {
    /// Postures in the group.
    pub postures: usize,
    /// The joint (1-based) with the largest predicted rate.
    pub worst_joint: usize,
    /// Its predicted mean deviation rate, percent (`null`: the group cannot identify it).
    pub worst_joint_pct: Option<f64>,
    /// Predicted mean deviation rate of each joint, percent.
    pub deviation_pct: [Option<f64>; 6],
}

/// The unconstrained optimum beside the feasible one: what feasibility costs.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Free<'a> {
    /// Its criterion (`null` if infinite).
    pub value: Option<f64>,
    /// Why its search stopped.
    #[cfg_attr(feature = "schema", schemars(schema_with = "schema::termination"))]
    pub termination: &'static str,
    /// Axis angles q1..q6, one row per posture: rad, written in deg.
    #[serde(rename = "postures_deg", serialize_with = "units::deg6_each")]
    #[cfg_attr(feature = "schema", schemars(with = "Vec<[f64; 6]>"))]
    pub postures: &'a [Vector6<f64>],
    /// Every criterion of the unconstrained group.
    pub criteria: Criteria,
    /// What the cell's checks cost: the feasible group's minimised value over the unconstrained
    /// one's, minus 1, % (`null` unless finite).
    pub cost_pct: Option<f64>,
    /// The feasible group's predicted mean deviation rate (over the noise levels and joints), %;
    /// `null` for a setup without a nominal stiffness.
    pub feasible_predicted_average_pct: Option<f64>,
    /// The unconstrained group's, %.
    pub predicted_average_pct: Option<f64>,
    /// `feasible_predicted_average_pct` over `predicted_average_pct`, minus 1, %.
    pub predicted_average_change_pct: Option<f64>,
}

impl<'a> Document<'a> {
    /// The document of `r` ([`Report::document`]).
    pub(crate) fn new(r: &'a Report) -> Self {
        let axes = r.external_axes.as_ref();
        Self {
            setup: &r.setup,
            purpose: r.purpose.name(),
            criterion: r.criterion.name(),
            search: r.method.name(),
            gradient: r.gradient.map(|g| g.name()),
            solver: r.solver.map(|s| s.name()),
            seed: r.seed,
            start_value: r.start_value.and_then(finite),
            value: finite(r.value),
            evaluations: r.evaluations,
            elapsed_s: r.elapsed_s,
            termination: r.termination.map(Termination::name),
            station: (r.station.as_ref()).map(|e| station(axes, e)),
            stations: (r.stations.iter())
                .map(|s| StationDoc {
                    external: station(axes, &s.e),
                    value: finite(s.value),
                })
                .collect(),
            posture_stations: r.placed.iter().map(|e| station(axes, e)).collect(),
            terminations: r.termination.map(|_| r.terminations.as_slice()),
            postures: &r.postures,
            margin: r.margin,
            min_margins: &r.min_margins,
            criteria: Criteria::of(&r.evaluation),
            calibration: (r.calibration.as_ref())
                .map(|c| CalibrationDoc::new(&c.options, &c.criteria)),
            calibration_weight: (r.calibration.as_ref())
                .filter(|c| c.weight < 1.0)
                .map(|c| c.weight),
            pool: r.pool.as_ref().map(Pool::new),
            target: r.target.as_ref().map(Target::new),
            unconstrained: r.unconstrained.as_ref().map(|u| Free::new(r, u)),
            near: &r.near,
            candidates: r.candidates.as_ref().map(ForCandidates::new),
            out: r.out.as_deref(),
            report: r.report_dir.as_deref(),
        }
    }
}

/// One station tried ([`crate::app::select::Station`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct StationDoc {
    /// The external axis values, `e1_mm`, `e2_deg`, ...
    #[serde(flatten)]
    pub external: BTreeMap<String, f64>,
    /// Its group's value minimised (`null` if infinite).
    pub value: Option<f64>,
}

/// External axis values `e` (SI) of the axes `axes` by their columns' names, in mm and deg;
/// empty without axes.
fn station(axes: Option<&ExternalAxes>, e: &ExternalValues) -> BTreeMap<String, f64> {
    let Some(axes) = axes else {
        return Default::default();
    };
    (axes.column_names().into_iter())
        .zip(axes.to_display(e.as_slice()))
        .collect()
}

/// The local searches' `terminations`, written as how many are of each reason, every reason
/// listed, or `null`. Schema: `Option<Vec<TerminationCount>>`.
fn counts<S: Serializer>(terminations: &Option<&[Termination]>, s: S) -> Result<S::Ok, S::Error> {
    let count = |all: &[Termination]| -> Vec<TerminationCount> {
        (Termination::ALL.iter())
            .map(|t| TerminationCount {
                termination: t.name(),
                searches: t.count(all),
            })
            .collect()
    };
    terminations.map(count).serialize(s)
}

impl<'a> Pool<'a> {
    /// The pool `p` and what was chosen from it.
    fn new(p: &'a PoolReport) -> Self {
        Self {
            file: &p.name,
            postures: p.total,
            usable: p.usable,
            skipped: (p.skipped.iter())
                .map(|s| Skipped {
                    posture: s.posture,
                    checks: s.checks.iter().map(|c| c.kind.key()).collect(),
                    reason: s.checks.iter().map(describe).collect::<Vec<_>>().join("; "),
                })
                .collect(),
            method: p.method.name(),
            chosen: &p.chosen,
            not_distinct: &p.not_distinct,
        }
    }
}

impl Target {
    /// Every group size tried for the target `t`.
    fn new(t: &TargetOutcome) -> Self {
        Self {
            target_pct: t.target_pct,
            postures: t.steps.last().map_or(0, |s| s.postures.len()),
            steps: t.steps.iter().map(Step::new).collect(),
        }
    }
}

impl Step {
    /// The group size tried `s`.
    fn new(s: &TargetStep) -> Self {
        let (j, worst) = s.worst_joint();
        Self {
            postures: s.postures.len(),
            worst_joint: j + 1,
            worst_joint_pct: finite(worst),
            deviation_pct: s.deviation_pct.map(finite),
        }
    }
}

impl<'a> Free<'a> {
    /// The unconstrained optimum `u` of the search `r`, beside `r`'s feasible group.
    fn new(r: &Report, u: &'a Unconstrained) -> Self {
        let (feasible, free) = (
            r.evaluation.predicted_average_pct(),
            u.evaluation.predicted_average_pct(),
        );
        Self {
            value: finite(u.value),
            termination: u.termination.name(),
            postures: &u.postures,
            criteria: Criteria::of(&u.evaluation),
            cost_pct: finite(100.0 * (r.value / u.value - 1.0)),
            feasible_predicted_average_pct: finite(feasible),
            predicted_average_pct: finite(free),
            predicted_average_change_pct: finite(100.0 * (feasible / free - 1.0)),
        }
    }
}

#[cfg(feature = "schema")]
mod schema {
    use crate::app::document::schema::one_of;
    use crate::app::select::Method;
    use schemars::{json_schema, Schema, SchemaGenerator};
    use stiffid_design::{Solver, Termination};

    pub(crate) fn method(_: &mut SchemaGenerator) -> Schema {
        one_of::<Method>()
    }

    /// The solvers a search runs (never `auto`).
    pub(crate) fn solver(_: &mut SchemaGenerator) -> Schema {
        let names: Vec<&str> = Solver::CONCRETE.iter().map(|s| s.name()).collect();
        json_schema!({ "type": "string", "enum": names })
    }

    pub(crate) fn termination(_: &mut SchemaGenerator) -> Schema {
        let names: Vec<&str> = Termination::ALL.iter().map(|t| t.name()).collect();
        json_schema!({ "type": "string", "enum": names })
    }
}
