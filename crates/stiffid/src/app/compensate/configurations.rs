//! The document's part of the free configuration (`--free-configuration`,
//! [`crate::machining::compensate::FreeConfiguration`]): every configuration of the arm found
//! at the path's first point, whether it takes the path or why not, its objective, and the one
//! chosen.

use crate::common::choice::Choice;
use crate::machining::compensate::{Branch, Configurations};
use serde::Serialize;

/// Every configuration of the arm evaluated over the path, and the one chosen.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct ConfigurationsDocument {
    /// What a point costs: `deflection` (the TCP deflection's length) or `bound` (its error
    /// bound), as the other free variables minimise.
    pub objective: &'static str,
    /// How the costs add up along the path: `sum` or `max`.
    pub aggregate: &'static str,
    /// The name of the configuration chosen (`name` of one of `configurations`).
    pub chosen: String,
    /// The name of the path's own configuration; `null` when the start posture reaches no
    /// posture at the path's first point.
    pub own: Option<String>,
    /// The configurations found at the first point: front before back, elbow up before down,
    /// axis 5 positive before negative.
    pub configurations: Vec<ConfigurationRow>,
}

/// One configuration of the arm over the path.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct ConfigurationRow {
    /// `front` or `back` (the wrist centre before or behind axis 1), `elbow up` or `elbow
    /// down`, `axis 5 positive` or `axis 5 negative`, e.g. `front, elbow up, axis 5 negative`.
    pub name: String,
    /// FANUC's `CONFIG` at the first point (`N U T, 0, 0, 0`).
    pub fanuc: String,
    /// KUKA's status `S` at the first point (bit 0 behind axis 1, bit 1 elbow up, bit 2 axis 5
    /// <= 0).
    pub kuka_status: u8,
    /// ABB's `cfx` at the first point (4 behind axis 1 + 2 elbow down + 1 axis 5 negative).
    pub abb_cfx: i64,
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
        ConfigurationsDocument {
            objective: c.objective.name(),
            aggregate: c.aggregate.name(),
            chosen: rows[c.chosen].name.clone(),
            own: rows.iter().find(|r| r.own).map(|r| r.name.clone()),
            configurations: rows,
        }
    }
}

/// The name of a configuration ([`ConfigurationRow::name`]).
pub fn name(c: &crate::robot::configuration::Configuration) -> String {
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
        crate::machining::compensate::Aggregate::Sum => b.sum,
        crate::machining::compensate::Aggregate::Max => b.peak,
    };
    ConfigurationRow {
        name: name(a),
        fanuc: a.fanuc(),
        kuka_status: a.kuka().0,
        abb_cfx: a.abb()[3],
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
