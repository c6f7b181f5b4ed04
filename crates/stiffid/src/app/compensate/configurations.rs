//! The document's part of the free configuration (`--free configuration`,
//! [`stiffid_machining::compensate::FreeVariables::configuration`]): every configuration of the arm found
//! at the path's first point, whether it takes the path or why not, its objective, and the one
//! chosen; with one configuration per run (`--free configuration=run`), each run's.

use serde::Serialize;
use std::collections::BTreeMap;
use stiffid_core::common::choice::Choice;
use stiffid_core::robot::configuration::Configuration;
use stiffid_machining::compensate::{Aggregate, Branch, Configurations, Run};
use stiffid_machining::program::Dialect;

/// Every configuration of the arm evaluated over the path, and the one chosen.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct ConfigurationsDocument {
    /// What a point costs: `deflection` (the TCP deflection's length) or `bound` (its error
    /// bound), as the other free variables minimise.
    pub objective: &'static str,
    /// How the costs add up along the path: `sum` or `max`.
    pub aggregate: &'static str,
    /// What one configuration holds: `program` (the whole path or program) or `run` (each run:
    /// a cut and the rapid or joint moves that lead to it).
    pub per: &'static str,
    /// The program's objective as compensated (the sum or the max of every point's cost, over
    /// every run), mm; `null` when infinite.
    pub objective_mm: Option<f64>,
    /// The name of the configuration chosen (`name` of one of `configurations`; per run, the
    /// first run's).
    pub chosen: String,
    /// The name of the path's own configuration; `null` when the start posture reaches no
    /// posture at the path's first point.
    pub own: Option<String>,
    /// The configurations found at the first point: front before back, elbow up before down,
    /// axis 5 positive before negative (per run, the first run's).
    pub configurations: Vec<ConfigurationRow>,
    /// Per run: each run's choice, in program order; empty for one configuration per program.
    pub runs: Vec<RunRow>,
}

/// One run's configuration (`--free configuration=run`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct RunRow {
    /// The run's number, from 1 in program order.
    pub run: usize,
    /// The line of its first point (the joint move that starts it).
    pub first_line: u64,
    /// The line of its last point.
    pub last_line: u64,
    /// Its points.
    pub points: usize,
    /// The configuration chosen (a `name` as in `configurations`).
    pub chosen: String,
    /// The chosen configuration's data at the run's first point as each robot language writes
    /// them, by language (`krl`, `rapid`, `ls`, `inform`): [`ConfigurationRow::configuration_data`].
    pub configuration_data: BTreeMap<String, String>,
    /// The posture that starts the run in the chosen configuration, deg.
    pub q_first_deg: [f64; 6],
    /// The program's own configuration at the run's first point (the one the path's own
    /// postures reach there); `null` when the program's own reaches no posture there.
    pub own: Option<String>,
    /// Whether the chosen one is the run's own.
    pub chosen_own: bool,
    /// The configurations found at the run's first point.
    pub found: usize,
    /// Of them, those that take the run (every point reached, every posture feasible and in
    /// the configuration).
    pub feasible: usize,
    /// The run's objective in the chosen configuration (its `sum_mm` or `max_mm` as
    /// `aggregate` says), mm; `null` when infinite.
    pub objective_mm: Option<f64>,
    /// The largest point cost in it, mm.
    pub max_mm: Option<f64>,
    /// The sum of its points' costs, mm.
    pub sum_mm: Option<f64>,
    /// The run's objective in its own configuration, mm; `null` when the own cannot take it.
    pub own_objective_mm: Option<f64>,
}

/// One configuration of the arm over the path.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct ConfigurationRow {
    /// `front` or `back` (the wrist centre before or behind axis 1), `elbow up` or `elbow
    /// down`, `axis 5 positive` or `axis 5 negative`, e.g. `front, elbow up, axis 5 negative`.
    pub name: String,
    /// Its configuration data at the first point as each robot language writes them, by
    /// language: `krl` (`S` and `T`), `rapid` (`confdata` `[cf1,cf4,cf6,cfx]`), `ls` (`CONFIG`
    /// `N U T, 0, 0, 0`), `inform` (the shoulder, elbow and wrist).
    pub configuration_data: BTreeMap<String, String>,
    /// The posture that starts the path in it: the axis angles at the first point, deg.
    pub q_first_deg: [f64; 6],
    /// Whether it is the path's own configuration.
    pub own: bool,
    /// Whether it is the one chosen.
    pub chosen: bool,
    /// Whether it takes the path: every point reached and compensated, every posture passes
    /// the feasibility checks and stays in the configuration (the path's own is kept whatever
    /// the checks say).
    pub feasible: bool,
    /// When it does not: the line of the first point that fails (`null` when no point is to
    /// blame).
    pub failed_line: Option<u64>,
    /// When it does not: why.
    pub failed_because: Option<String>,
    /// The path's objective in it (the `sum_mm` or the `max_mm` as `aggregate` says), mm;
    /// `null` when a point is not reached (or the bound is infinite).
    pub objective_mm: Option<f64>,
    /// The largest point cost, mm; `null` when a point is not reached (or the bound is infinite).
    pub max_mm: Option<f64>,
    /// The sum of the points' costs, mm; `null` when a point is not reached (or the bound is infinite).
    pub sum_mm: Option<f64>,
}

impl ConfigurationsDocument {
    /// The document's part of `c`.
    pub fn new(c: &Configurations) -> Self {
        let rows: Vec<ConfigurationRow> = (c.branches.iter().enumerate())
            .map(|(k, b)| row(b, k == c.chosen, c))
            .collect();
        let chosen: Vec<&Branch> = match c.runs.is_empty() {
            true => vec![&c.branches[c.chosen]],
            false => c.runs.iter().map(|r| &r.branches[r.chosen]).collect(),
        };
        let objective = match c.aggregate {
            Aggregate::Sum => chosen.iter().map(|b| b.sum).sum::<Option<f64>>(),
            Aggregate::Max => {
                (chosen.iter().map(|b| b.peak)).try_fold(0.0, |m, p| p.map(|p| f64::max(m, p)))
            }
        };
        ConfigurationsDocument {
            objective: c.objective.name(),
            aggregate: c.aggregate.name(),
            per: if c.runs.is_empty() { "program" } else { "run" },
            objective_mm: mm(objective),
            chosen: rows[c.chosen].name.clone(),
            own: rows.iter().find(|r| r.own).map(|r| r.name.clone()),
            configurations: rows,
            runs: (c.runs.iter().enumerate())
                .map(|(k, r)| run_row(k, r, c.aggregate))
                .collect(),
        }
    }
}

/// The row of run `k` (0-based).
fn run_row(k: usize, r: &Run, aggregate: Aggregate) -> RunRow {
    let b = &r.branches[r.chosen];
    let own = r.branches.iter().find(|b| b.own);
    let objective = |b: &Branch| match aggregate {
        Aggregate::Sum => b.sum,
        Aggregate::Max => b.peak,
    };
    RunRow {
        run: k + 1,
        first_line: r.first_line,
        last_line: r.last_line,
        points: r.points.len(),
        chosen: name(&b.configuration),
        configuration_data: configuration_data(&b.configuration),
        q_first_deg: b.configuration.q_deg,
        own: own.map(|o| name(&o.configuration)),
        chosen_own: b.own,
        found: r.branches.len(),
        feasible: r.branches.iter().filter(|b| b.refused.is_none()).count(),
        objective_mm: mm(objective(b)),
        max_mm: mm(b.peak),
        sum_mm: mm(b.sum),
        own_objective_mm: mm(own.and_then(objective)),
    }
}

/// The configuration data of `a` as each robot language writes them, by language key.
fn configuration_data(a: &Configuration) -> BTreeMap<String, String> {
    (Dialect::ALL.iter())
        .map(|d| {
            (
                d.controller().key().to_string(),
                d.controller().flags(a).text(),
            )
        })
        .collect()
}

/// The name of a configuration ([`ConfigurationRow::name`]).
pub(crate) fn name(c: &Configuration) -> String {
    format!(
        "{}, elbow {}, axis 5 {}",
        if c.behind() { "back" } else { "front" },
        if c.elbow_down() { "down" } else { "up" },
        if c.wrist_negative() {
            "negative"
        } else {
            "positive"
        }
    )
}

/// A length in mm, `None` when not finite (an infinite bound).
fn mm(v: Option<f64>) -> Option<f64> {
    v.map(|v| v * 1e3).filter(|v| v.is_finite())
}

/// The row of branch `b`.
fn row(b: &Branch, chosen: bool, c: &Configurations) -> ConfigurationRow {
    let a = &b.configuration;
    let objective = match c.aggregate {
        Aggregate::Sum => b.sum,
        Aggregate::Max => b.peak,
    };
    ConfigurationRow {
        name: name(a),
        configuration_data: configuration_data(a),
        q_first_deg: a.q_deg,
        own: b.own,
        chosen,
        feasible: b.refused.is_none(),
        failed_line: b.refused.as_ref().and_then(|r| r.0),
        failed_because: b.refused.as_ref().map(|r| r.1.clone()),
        objective_mm: mm(objective),
        max_mm: mm(b.peak),
        sum_mm: mm(b.sum),
    }
}
