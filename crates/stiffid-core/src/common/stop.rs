//! Why an iterative solver stopped: one stop reason for the calibration's Levenberg-Marquardt
//! fit (`stiffid_metrology::calibration::fit`), inverse kinematics ([`crate::robot::ik`]), the
//! robust reweighting of identification (`stiffid_identify::robust`) and the compensation's
//! Newton steps (`stiffid_machining::compensate`). Each
//! solver documents which reasons it gives; the posture search, whose reasons are those of an
//! SQP, has its own (`stiffid_design::Termination`).
//!
//! Documents carry it as `stop_reason`, a kebab-case string (`Stop::name`); a result from a
//! solver stopped at its iteration limit comes with a warning of kind
//! [`crate::common::warning::WarningKind::NotConverged`].

use serde::Serialize;
use std::fmt;

/// Why an iterative solver stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "kebab-case")]
pub enum Stop {
    /// The solver's tolerance was met: the step, the change or the residual fell below it.
    Converged,
    /// An accepted step no longer lowered the cost beyond its rounding: a minimum within
    /// rounding.
    Stalled,
    /// No step of the damping tried lowered the cost: a minimum within rounding for a
    /// least-squares fit, a point the solver cannot improve (a local minimum, a joint limit) for
    /// inverse kinematics.
    DampingExhausted,
    /// The solver took its most iterations with the tolerance not met: its result may still
    /// move.
    IterationLimit,
}

impl Stop {
    /// The name in documents and messages: `converged`, `stalled`, `damping-exhausted` or
    /// `iteration-limit`.
    pub(crate) fn name(self) -> &'static str {
        match self {
            Stop::Converged => "converged",
            Stop::Stalled => "stalled",
            Stop::DampingExhausted => "damping-exhausted",
            Stop::IterationLimit => "iteration-limit",
        }
    }
}

impl fmt::Display for Stop {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
impl Stop {
    /// Every stop reason, in the order of the variants.
    pub(crate) const ALL: [Stop; 4] = [
        Stop::Converged,
        Stop::Stalled,
        Stop::DampingExhausted,
        Stop::IterationLimit,
    ];
}
