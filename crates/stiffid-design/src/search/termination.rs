//! Why a local search stopped.

use std::fmt;
use std::str::FromStr;

/// Why a local search ([`super::local`], or one start of [`super::global`]) stopped.
///
/// Only [`Termination::Converged`] and [`Termination::StepTolerance`] say that the SQP found a
/// point where a step no longer helps; the others say the search was cut short, and a larger
/// budget or another start may do better. Whatever the reason, the search returns the best point
/// it evaluated (the least violating of the cell's checks, then the lowest criterion).
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Termination {
    /// An SQP step at a point within the cell's constraints changed `ln(criterion)` by less than
    /// [`super::SearchOptions::ftol`].
    Converged,
    /// An SQP step at a point within the cell's constraints moved every angle by less than
    /// [`super::SearchOptions::xtol`].
    StepTolerance,
    /// The budget [`super::SearchOptions::max_evals`] was spent (for a start of a global search
    /// that was screened out, the screening budget).
    EvaluationLimit,
    /// The line search found no step that decreases the merit function along the SQP direction
    /// (rounding limits the progress, or the QP's direction is not a descent direction).
    LineSearchFailed,
    /// The best point evaluated fails the cell's checks, whatever stopped the SQP: the search
    /// found no group of postures within the cell from its start.
    Infeasible,
    /// The QP subproblem of an SQP step failed: the constraints linearised at the current point
    /// have no solution within the bounds, or the subproblem hit its own iteration limit or a
    /// singular system.
    SubproblemFailed,
}

impl Termination {
    /// Every stop reason, in the order of the variants.
    pub const ALL: [Termination; 6] = [
        Termination::Converged,
        Termination::StepTolerance,
        Termination::EvaluationLimit,
        Termination::LineSearchFailed,
        Termination::Infeasible,
        Termination::SubproblemFailed,
    ];

    /// The name used in reports and documents: `converged`, `step-tolerance`,
    /// `evaluation-limit`, `line-search-failed`, `infeasible`, `subproblem-failed`.
    pub fn name(self) -> &'static str {
        match self {
            Termination::Converged => "converged",
            Termination::StepTolerance => "step-tolerance",
            Termination::EvaluationLimit => "evaluation-limit",
            Termination::LineSearchFailed => "line-search-failed",
            Termination::Infeasible => "infeasible",
            Termination::SubproblemFailed => "subproblem-failed",
        }
    }

    /// Whether the search stopped at a point a step no longer improves
    /// ([`Termination::Converged`] or [`Termination::StepTolerance`]).
    #[cfg(test)]
    pub(crate) fn is_converged(self) -> bool {
        matches!(self, Termination::Converged | Termination::StepTolerance)
    }

    /// How many of `terminations` are `self`.
    pub fn count(self, terminations: &[Termination]) -> usize {
        terminations.iter().filter(|&&t| t == self).count()
    }
}

impl fmt::Display for Termination {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Termination {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Self, Self::Err> {
        Termination::ALL
            .into_iter()
            .find(|t| t.name() == s)
            .ok_or_else(|| {
                let known: Vec<&str> = Termination::ALL.iter().map(|t| t.name()).collect();
                format!("unknown termination '{s}' (known: {})", known.join(", "))
            })
    }
}

/// What `slsqp::minimize` returns: its status, the point and the value.
pub(super) type SlsqpOutcome =
    Result<(slsqp::SuccessStatus, Vec<f64>, f64), (slsqp::FailStatus, Vec<f64>, f64)>;

/// The stop reason of an `slsqp` run (NLopt's statuses): `ftol` and `xtol` are tested only at
/// feasible points, so both mean convergence; NLopt reports a failed line search (positive
/// directional derivative, mode 8) and a singular least-squares subproblem (modes 5-7) both as
/// "roundoff limited", and incompatible linearised constraints (mode 4) together with the
/// subproblem's iteration limits (modes 3, 9) as "failure".
pub(super) fn from_slsqp(outcome: &SlsqpOutcome) -> Termination {
    use slsqp::{FailStatus as F, SuccessStatus as S};
    match outcome {
        Ok((S::FtolReached | S::Success | S::StopValReached, ..)) => Termination::Converged,
        Ok((S::XtolReached, ..)) => Termination::StepTolerance,
        Ok((S::MaxEvalReached | S::MaxTimeReached, ..)) => Termination::EvaluationLimit,
        Err((F::RoundoffLimited, ..)) => Termination::LineSearchFailed,
        Err((F::Failure, ..)) => Termination::SubproblemFailed,
        Err((F::InvalidArgs | F::OutOfMemory | F::ForcedStop | F::UnexpectedError, ..)) => {
            Termination::SubproblemFailed
        }
    }
}
