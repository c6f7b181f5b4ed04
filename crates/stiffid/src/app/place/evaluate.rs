//! One placement of the part evaluated: the program (or path) compensated with the part there
//! ([`stiffid_machining::compensate()`], [`stiffid_machining::compensate::path`]), every point reachable in the start's configuration and
//! compensated within the joint limits, then the checks of the placement (module docs of
//! [`super`]) and the path's error bounds.

use super::work::{self, Work};
use nalgebra::Isometry3;
use stiffid_core::cell::{CheckKind, Checker};
use stiffid_core::math::jacobi;
use stiffid_core::robot::kinematics::Coordinates;
use stiffid_core::Setup;
use stiffid_machining as machining;
use stiffid_machining::compensate::{self, Compensated, Compliance, Options};

/// The cell's checks a placement must pass at every point: the bodies against the floor, the
/// obstacles and each other (the rope, the tracker's sight and the experiment's bounds belong
/// to the identification, not to machining).
const CHECKS: [CheckKind; 3] = [
    CheckKind::Floor,
    CheckKind::Obstacles,
    CheckKind::SelfCollision,
];

/// What a placement is checked against.
pub(super) struct Context<'a> {
    pub setup: &'a Setup,
    pub compliance: &'a Compliance,
    pub work: Work<'a>,
    pub options: &'a Options,
    /// The smallest distance of every axis angle to its joint limits, rad.
    pub margin: f64,
    /// The largest condition number of the TCP Jacobian.
    pub max_condition: f64,
    /// The cell's checker, when the setup has a `[cell]`.
    pub checker: Option<Checker<'a>>,
}

/// A placement's figures, SI.
#[derive(Debug, Clone, PartialEq)]
pub struct Evaluation {
    /// The part frame in the robot base frame (`[workpiece] base_from_part`).
    pub base_from_part: Isometry3<f64>,
    /// The largest error bound over the path, m.
    pub peak: f64,
    /// The sum of the points' bounds, m.
    pub sum: f64,
    /// The path's points.
    pub points: usize,
    /// The program line of the largest bound.
    pub worst_line: u64,
    /// The smallest distance of an axis angle (nominal or compensated) to its joint limits over
    /// the path, rad.
    pub limit_margin: f64,
    /// The largest condition number of the TCP Jacobian over the path.
    pub condition: f64,
    /// The smallest clearance of the cell's checks over the path, m; `None` without a `[cell]`.
    pub clearance: Option<f64>,
}

impl Context<'_> {
    /// The evaluation of the part at `pose`, or why it is not feasible there.
    pub(super) fn evaluate(&self, pose: &Isometry3<f64>) -> Result<Evaluation, String> {
        let arm = self.setup.arm();
        let (lines, results) = self.compensate(pose).map_err(|e| e.to_string())?;
        let robot = arm.robot();
        let limits = robot.limits();
        let (mut margin, mut condition, mut clearance) = (f64::INFINITY, 0f64, None::<f64>);
        let (mut peak, mut sum, mut worst_line) = (0f64, 0.0, 0);
        for (&line, r) in lines.iter().zip(&results) {
            for q in [&r.q, &r.q_compensated] {
                margin = margin.min(limits.distance(q));
            }
            let j = robot
                .frames(&r.q)
                .jacobian(&arm.tool().tcp, Coordinates::Axis);
            condition = condition.max(jacobi::cond(&j));
            if let Some(checker) = &self.checker {
                let f = checker.feasibility_at(&r.q, r.external.as_slice());
                for c in f.checks.iter().filter(|c| CHECKS.contains(&c.kind)) {
                    if !c.ok {
                        return Err(format!(
                            "line {}: {} between {} and {}",
                            line,
                            c.kind.key(),
                            c.between.0,
                            c.between.1
                        ));
                    }
                    let m = c.clearance.unwrap_or(c.margin);
                    clearance = Some(clearance.map_or(m, |v| v.min(m)));
                }
            }
            let bound = r.budget.bound;
            sum += bound;
            if bound > peak {
                (peak, worst_line) = (bound, line);
            }
        }
        if margin < self.margin {
            return Err(format!(
                "an axis comes {:.2} deg from its joint limit (at least {:.2} deg asked)",
                margin.to_degrees(),
                self.margin.to_degrees()
            ));
        }
        if condition.is_nan() || condition > self.max_condition {
            return Err(format!(
                "the TCP Jacobian's condition number reaches {condition:.1} (at most {:.1} asked: near a singularity)",
                self.max_condition
            ));
        }
        Ok(Evaluation {
            base_from_part: *pose,
            peak,
            sum,
            points: results.len(),
            worst_line,
            limit_margin: margin,
            condition,
            clearance,
        })
    }

    /// The work compensated with the part at `pose`: each point's line and compensation.
    fn compensate(
        &self,
        pose: &Isometry3<f64>,
    ) -> stiffid_core::Result<(Vec<u64>, Vec<Compensated>)> {
        let arm = self.setup.arm();
        match self.work {
            Work::Program { program, process } => {
                let placed = match program {
                    machining::Program::Robot(_) => Some(pose),
                    machining::Program::GCode(_) => None,
                };
                let program = machining::resolve(program, self.setup, placed, self.options)?;
                let report = machining::compensate(
                    arm,
                    Some(pose),
                    self.compliance,
                    &program,
                    process,
                    self.options,
                )?;
                let lines = report.points.iter().map(|p| p.line).collect();
                Ok((lines, report.results))
            }
            Work::Path(points) => {
                let placed = work::placed(points, pose);
                let results = compensate::path(arm, self.compliance, &placed, self.options)?;
                Ok((placed.iter().map(|p| p.line).collect(), results))
            }
        }
    }
}
