//! The free variables of a compensation as its document gives them (`free`: one
//! [`FreeVariable`] each, in the units of `--free`), and what they minimise together
//! (`minimise`, `objective`).

use serde::Serialize;
use stiffid_core::common::choice::Choice;
use stiffid_core::common::words::as_given;
use stiffid_machining::compensate::{Free, FreeVariables};

/// One free variable of a compensation (`--free NAME=-R..R/STEP`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct FreeVariable {
    /// The variable as `--free` names it: `tool-rotation` (the rotation about tool z),
    /// `lead-tilt` (the tool axis' lean within a cone), `station` (the track's carrier axis),
    /// `positioner` (the positioner's last axis, the table's turn), `tilt` (a two-axis
    /// positioner's first axis) or `configuration` (the arm's).
    pub variable: &'static str,
    /// It stays within +- this of the path's own value, in `unit`; for `lead-tilt` the cone's
    /// half angle, `null` for a program, whose process file gives each operation's
    /// (`[tool_axis] cone_deg`); `null` for the configuration.
    pub range: Option<f64>,
    /// The grid's step, also its largest change between consecutive points, in `unit` (for
    /// `lead-tilt` of the lead, and of the tilt); `null` for the configuration.
    pub step: Option<f64>,
    /// The unit of `range` and `step`: `mm` for the station, `deg` otherwise; `null` for the
    /// configuration.
    pub unit: Option<&'static str>,
    /// For the configuration: `program` (one for the whole path) or `run` (one per run); else
    /// `null`.
    pub per: Option<&'static str>,
}

impl FreeVariable {
    /// The free variable `free` in the units of `--free` (mm for the station, deg otherwise).
    pub(crate) fn new(free: &Free) -> Self {
        let (range, step, unit) = match free {
            Free::Station(f) => (Some(f.range * 1e3), Some(f.step * 1e3), Some("mm")),
            Free::ToolRotation(f) | Free::Positioner(f) | Free::Tilt(f) => (
                Some(f.range.to_degrees()),
                Some(f.step.to_degrees()),
                Some("deg"),
            ),
            Free::LeadTilt(l) => (
                l.cone.map(f64::to_degrees),
                Some(l.step.to_degrees()),
                Some("deg"),
            ),
            Free::Configuration(_) => (None, None, None),
        };
        FreeVariable {
            variable: free.name(),
            range: range.map(as_given),
            step: step.map(as_given),
            unit,
            per: match free {
                Free::Configuration(per) => Some(per.name()),
                _ => None,
            },
        }
    }

    /// Every free variable of `free`, in its order.
    pub(crate) fn all(free: &FreeVariables) -> Vec<Self> {
        free.free.iter().map(FreeVariable::new).collect()
    }
}

/// The names of what `free`'s variables minimise (`deflection`, `surge` or `bound`) and how
/// their costs add up (`sum` or `max`); `None` when nothing is free.
pub(super) fn objective(free: &FreeVariables) -> Option<(&'static str, &'static str)> {
    free.any()
        .then(|| (free.minimise.name(), free.aggregate.name()))
}
