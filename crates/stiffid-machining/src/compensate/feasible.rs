//! Which moved postures the free variables may take: the joint-limit margin, the distance to a
//! singularity and the cell's collision checks (module docs of [`super`], "Feasibility").

use super::speed::Pace;
use super::Model;
use nalgebra::{Vector3, Vector6};
use std::sync::Arc;
use stiffid_core::cell::{CheckKind, Checker, Margin, Thing};
use stiffid_core::common::error::JobOption;
use stiffid_core::common::words::number;
use stiffid_core::math::jacobi;
use stiffid_core::robot::external::ExternalValues;
use stiffid_core::robot::kinematics::Coordinates;
use stiffid_core::robot::parts::Part;
use stiffid_core::{Error, Result, Robot, Setup};

/// What every posture the free variables move a point to must keep (module docs of [`super`],
/// "Feasibility"); the path's own posture is kept as it is. The defaults are those of
/// `stiffid place`.
#[derive(Debug, Clone, PartialEq)]
pub struct Feasible {
    /// The smallest distance of every axis angle to its joint limits, rad, in [0, pi/2].
    pub margin: f64,
    /// The largest condition number of the TCP Jacobian (axis coordinates, rows `[v; omega]`
    /// in m/rad and rad/rad), finite and >= 1: away from singularities.
    pub max_condition: f64,
    /// The setup whose `[cell]` checks (floor, obstacles, self-collision; parry3d-f64 distances,
    /// [`stiffid_core::cell::Checker`]) every moved posture passes; `None`: no collision check. An arm
    /// on a carrier is checked on its carriage at the state's external values (the station
    /// chosen, or the point's own; [`stiffid_core::cell::Checker::feasibility_at`]); the cell's floor
    /// and fixed obstacles stand in the cell frame, the boxes a positioner carries turn with the
    /// state's angles ([`stiffid_core::setup::Obstacle::carried_by`]).
    pub cell: Option<Arc<Setup>>,
    /// The time of the move to each path point, s, from the program's feed
    /// ([`super::move_times`]; `None` for a point whose move has no limit: the first, a rapid
    /// move): a move of the free variables between consecutive points is taken only where every
    /// axis with a largest speed ([`stiffid_core::Robot::max_speeds`],
    /// [`stiffid_core::robot::external::ExternalAxis::max_speed`]) moves at most that speed times it
    /// (the path's own moves are kept whatever they do). `None`: no speed check (no feed).
    pub move_times: Option<Arc<[Option<f64>]>>,
}

impl Feasible {
    /// The default of [`Feasible::margin`], deg.
    pub(crate) const DEFAULT_MARGIN_DEG: f64 = 5.0;
    /// The default of [`Feasible::max_condition`].
    pub(crate) const DEFAULT_MAX_CONDITION: f64 = 1000.0;

    /// The defaults for `setup`: a margin of 5 deg, a condition number of at most 1000 and, when
    /// the setup has a `[cell]`, its collision checks; no speed check ([`Feasible::move_times`]).
    pub fn for_setup(setup: &Setup) -> Self {
        Self {
            margin: Self::DEFAULT_MARGIN_DEG.to_radians(),
            max_condition: Self::DEFAULT_MAX_CONDITION,
            cell: setup.cell().map(|_| Arc::new(setup.clone())),
            move_times: None,
        }
    }

    /// Checks the margin (0 to 90 deg) and the condition number (finite, >= 1).
    ///
    /// # Errors
    /// [`Error::InvalidOption`] ([`JobOption::MarginDeg`] or [`JobOption::MaxCondition`]) with
    /// the value given.
    pub(crate) fn validate(&self) -> Result<()> {
        if !(0.0..=std::f64::consts::FRAC_PI_2).contains(&self.margin) {
            return Err(Error::InvalidOption {
                option: JobOption::MarginDeg,
                message: format!("{}: expected 0 to 90", number(self.margin.to_degrees())),
            });
        }
        if !(self.max_condition >= 1.0 && self.max_condition.is_finite()) {
            return Err(Error::InvalidOption {
                option: JobOption::MaxCondition,
                message: format!(
                    "{}: expected a finite number >= 1",
                    number(self.max_condition)
                ),
            });
        }
        Ok(())
    }

    /// Whether the cell's collision checks apply to the moved postures: with a `[cell]`.
    pub fn checks_cell(&self) -> bool {
        self.cell.is_some()
    }
}

/// The states the checks removed ([`Feasible`]): over the grid's states at a path point (or,
/// summed, over the path), those reached by inverse kinematics and no worse than the path's own
/// that a check refused, each counted once, by the first check it fails in this order.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Removed {
    /// Within [`Feasible::margin`] of a joint limit.
    pub limit_margin: usize,
    /// A TCP Jacobian's condition number above [`Feasible::max_condition`] (or not finite).
    pub singularity: usize,
    /// A collision of the cell's checks.
    pub collision: usize,
    /// Moves between feasible states of consecutive points refused because an axis would
    /// exceed its largest speed ([`Feasible::move_times`]): transitions, not states, counted at
    /// the point they move to.
    pub speed: usize,
}

impl std::ops::AddAssign for Removed {
    fn add_assign(&mut self, other: Self) {
        self.limit_margin += other.limit_margin;
        self.singularity += other.singularity;
        self.collision += other.collision;
        self.speed += other.speed;
    }
}

/// The cell's checks a moved posture must pass: the bodies against the floor, the obstacles and
/// each other (as `stiffid place`'s).
const COLLISIONS: [CheckKind; 3] = [
    CheckKind::Floor,
    CheckKind::Obstacles,
    CheckKind::SelfCollision,
];

/// The checks of [`Feasible`] for one arm, worked out once for every posture.
pub(super) struct Checks<'a> {
    robot: &'a Robot,
    tcp: Vector3<f64>,
    margin: f64,
    max_condition: f64,
    checker: Option<Checker<'a>>,
    /// The axes' speed limits at the path's move times; `None`: none.
    pub pace: Option<Pace<'a>>,
}

impl<'a> Checks<'a> {
    /// The checks of `feasible` for the arm of `model`, the collisions with a `[cell]`, the
    /// speeds with move times and limits.
    pub(super) fn new(model: &Model<'a>, feasible: &'a Feasible) -> Self {
        let robot = model.arm.robot();
        let checker = feasible.cell.as_deref().map(Checker::new);
        Checks {
            robot,
            tcp: model.arm.tool().tcp,
            margin: feasible.margin,
            max_condition: feasible.max_condition,
            checker,
            pace: Pace::new(robot, feasible.move_times.as_deref()),
        }
    }

    /// The obstacles the tool touches at the path's own posture `own` (rad; none without one)
    /// with the external axes at `e`: the part or stock being cut, whose contact with the tool
    /// is no collision of a moved posture ([`Checks::fails`]).
    pub(crate) fn touching(&self, own: Option<&Vector6<f64>>, e: &ExternalValues) -> Vec<usize> {
        let (Some(checker), Some(q)) = (&self.checker, own) else {
            return Vec::new();
        };
        (checker.margins_at(q, e.as_slice()).iter())
            .filter(|m| m.margin < 0.0)
            .filter_map(tool_on_obstacle)
            .collect()
    }

    /// `Removed` with a count of one for the first check posture `q` (rad) fails with the
    /// external axes at `e` (the arm on its carriage there), `None` when it passes every check;
    /// the tool's contact with an obstacle of `touching` (those it touches at the path's own
    /// posture, [`Checks::touching`]) is not a collision.
    pub(crate) fn fails(
        &self,
        q: &Vector6<f64>,
        e: &ExternalValues,
        touching: &[usize],
    ) -> Option<Removed> {
        let distance = self.robot.limits().distance(q);
        if distance.is_nan() || distance < self.margin {
            return Some(Removed {
                limit_margin: 1,
                ..Removed::default()
            });
        }
        let j = self.robot.frames(q).jacobian(&self.tcp, Coordinates::Axis);
        let condition = jacobi::cond(&j);
        if condition.is_nan() || condition > self.max_condition {
            return Some(Removed {
                singularity: 1,
                ..Removed::default()
            });
        }
        let collides = self.checker.as_ref().is_some_and(|c| {
            (c.margins_at(q, e.as_slice()).iter()).any(|m| {
                COLLISIONS.contains(&m.kind)
                    && m.margin < 0.0
                    && tool_on_obstacle(m).is_none_or(|o| !touching.contains(&o))
            })
        });
        collides.then(|| Removed {
            collision: 1,
            ..Removed::default()
        })
    }
}

/// The obstacle of a margin between the tool and an obstacle, else `None`.
fn tool_on_obstacle(m: &Margin) -> Option<usize> {
    match m.between {
        (Thing::Part(Part::Tool), Thing::Obstacle(o))
        | (Thing::Obstacle(o), Thing::Part(Part::Tool)) => Some(o),
        _ => None,
    }
}
