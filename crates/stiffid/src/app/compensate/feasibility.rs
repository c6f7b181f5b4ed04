//! What the feasibility checks of the free variables kept out of the optimisation
//! ([`stiffid_machining::compensate::Feasible`]): their limits and how many states each removed.

use serde::Serialize;
use stiffid_machining::compensate::{Options, Removed};

/// The feasibility of the moved postures of the free variables (`--free tool-rotation`,
/// `--free station`, `--free positioner`, `--free tilt`, `--free lead-tilt`; with `--free configuration` a configuration whose posture
/// fails a check at a point is refused): a state (a value of the
/// free variables at a path point) that inverse kinematics reaches with a cost no larger than
/// the path's own is removed when its posture fails a check; each removed state is counted
/// once, by the first check it fails in the order joint-limit margin, singularity, collision.
/// The path's own posture is kept as it is.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Feasibility {
    /// Every axis angle of a moved posture keeps at least this distance to its joint limits,
    /// deg (`--margin-deg`).
    pub margin_deg: f64,
    /// The largest condition number of a moved posture's TCP Jacobian (`--max-condition`).
    pub max_condition: f64,
    /// Whether the cell's collision checks (floor, obstacles, self-collision) applied: with a
    /// `[cell]` (an arm on a carrier on its carriage at each state's station).
    pub collisions_checked: bool,
    /// The states removed within the margin of a joint limit, summed over the path's points.
    pub states_removed_limit_margin: usize,
    /// The states removed near a singularity (condition number above the largest).
    pub states_removed_singularity: usize,
    /// The states removed by a collision.
    pub states_removed_collision: usize,
    /// The moves between feasible states of consecutive points refused because an axis would
    /// exceed its largest speed at the program's feed (`speed_limits`), summed over the path.
    pub moves_refused_speed: usize,
}

impl Feasibility {
    /// The feasibility of `options` with the states `removed` over the path; `None` without a
    /// free variable.
    pub(crate) fn new(options: &Options, removed: Removed) -> Option<Self> {
        if options.free.tool_rotation().is_none()
            && options.free.lead_tilt().is_none()
            && options.free.configuration().is_none()
            && !options.free.frees_external()
        {
            return None;
        }
        let f = &options.feasible;
        Some(Feasibility {
            margin_deg: stiffid_core::common::words::as_given(f.margin.to_degrees()),
            max_condition: f.max_condition,
            collisions_checked: f.checks_cell(),
            states_removed_limit_margin: removed.limit_margin,
            states_removed_singularity: removed.singularity,
            states_removed_collision: removed.collision,
            moves_refused_speed: removed.speed,
        })
    }
}
