//! The options of the free variables of a compensation as its document gives them, in the
//! units of the command line (`free_tool_axis`, `free_station`, `free_positioner`, `free_tilt`,
//! `free_lead_tilt`).

use crate::compensate::{FreeRange, FreeVariables};
use serde::Serialize;
use stiffid_core::common::choice::Choice;
use stiffid_core::common::words::as_given;

/// The options of the free tool axis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct FreeToolAxis {
    /// The largest change of the rotation about tool z between consecutive points, deg.
    pub max_step_deg: f64,
    /// The rotation stays within +- this of the path's, deg.
    pub range_deg: f64,
    /// What the rotation minimises: `deflection` (the TCP deflection at every point) or `surge`
    /// (the breakthrough surge at every drilling exit) or `bound` (the error bound at every
    /// point).
    pub objective: &'static str,
    /// How the points' costs add up: `sum` or `max` (the worst point's).
    pub aggregate: &'static str,
}

/// The options of the free track station.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct FreeStation {
    /// The station stays within +- this of the path's own, mm.
    pub range_mm: f64,
    /// The largest change of its offset from the path's own between consecutive points, mm.
    pub step_mm: f64,
    /// What it minimises: `deflection` or `bound`.
    pub objective: &'static str,
    /// How the points' costs add up: `sum` or `max` (the worst point's).
    pub aggregate: &'static str,
}

/// The options of a free positioner axis: its last (the table's turn, `free_positioner`) or a
/// two-axis positioner's first (the tilt, `free_tilt`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct FreePositioner {
    /// The angle stays within +- this of the path's own, deg.
    pub range_deg: f64,
    /// The largest change of its offset from the path's own between consecutive points, deg.
    pub step_deg: f64,
    /// What it minimises: `deflection` or `bound`.
    pub objective: &'static str,
    /// How the points' costs add up: `sum` or `max` (the worst point's).
    pub aggregate: &'static str,
}

/// The options of the free lead and tilt of the tool axis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct FreeLeadTilt {
    /// The cone's half angle the tool axis leans within about the path's own, deg
    /// (`--cone-deg`); `null` for a program, whose process file gives each operation's
    /// (`[tool_axis] cone_deg`).
    pub cone_deg: Option<f64>,
    /// The largest change of the lead, and of the tilt, between consecutive points, deg.
    pub step_deg: f64,
    /// What the lean minimises: `deflection` or `bound`.
    pub objective: &'static str,
    /// How the points' costs add up: `sum` or `max` (the worst point's).
    pub aggregate: &'static str,
}

/// The names of what `free`'s variables minimise and how their costs add up.
fn objective(free: &FreeVariables) -> (&'static str, &'static str) {
    (free.minimise.name(), free.aggregate.name())
}

impl FreeToolAxis {
    /// The free tool rotation of `free` in degrees, if free.
    pub(super) fn new(free: &FreeVariables) -> Option<Self> {
        let (objective, aggregate) = objective(free);
        free.tool_rotation.map(|f| FreeToolAxis {
            max_step_deg: as_given(f.step.to_degrees()),
            range_deg: as_given(f.range.to_degrees()),
            objective,
            aggregate,
        })
    }
}

impl FreeStation {
    /// The free station of `free` in mm, if free.
    pub(super) fn new(free: &FreeVariables) -> Option<Self> {
        let (objective, aggregate) = objective(free);
        free.station.map(|f| FreeStation {
            range_mm: as_given(f.range * 1e3),
            step_mm: as_given(f.step * 1e3),
            objective,
            aggregate,
        })
    }
}

impl FreePositioner {
    /// The free positioner axis `f` (the positioner's or the tilt's of `free`) in degrees, if
    /// free.
    pub(super) fn new(f: Option<FreeRange>, free: &FreeVariables) -> Option<Self> {
        let (objective, aggregate) = objective(free);
        f.map(|f| FreePositioner {
            range_deg: as_given(f.range.to_degrees()),
            step_deg: as_given(f.step.to_degrees()),
            objective,
            aggregate,
        })
    }
}

impl FreeLeadTilt {
    /// The free lead and tilt of `free` in degrees, if free.
    pub(super) fn new(free: &FreeVariables) -> Option<Self> {
        let (objective, aggregate) = objective(free);
        free.lead_tilt.map(|f| FreeLeadTilt {
            cone_deg: f.cone.map(|c| as_given(c.to_degrees())),
            step_deg: as_given(f.step.to_degrees()),
            objective,
            aggregate,
        })
    }
}
