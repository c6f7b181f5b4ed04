//! The axes' speed limits at the program's feed: which moves between consecutive path points
//! the free variables may take (module docs of [`super`], "Speed limits").

use nalgebra::{Vector3, Vector6};
use stiffid_core::robot::external::ExternalValues;
use stiffid_core::Robot;

/// How fast the move to a point goes, as the program or path file states it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Rate {
    /// The TCP's feed, m/s: the move takes its distance over the feed.
    Feed(f64),
    /// The move's time, s.
    Duration(f64),
}

/// The time of the move to each point of a path through the TCP `positions` (m, the part's
/// frame) at the `rates` of the moves to them (one per point), s: `|p_i - p_(i-1)| / feed_i`,
/// or the time given; `None` for the first point and a point without a rate (a rapid or joint
/// move: the controller's own speed).
pub fn move_times(positions: &[Vector3<f64>], rates: &[Option<Rate>]) -> Vec<Option<f64>> {
    (0..positions.len())
        .map(|i| match (i, rates.get(i).copied().flatten()) {
            (0, _) | (_, None) => None,
            (_, Some(Rate::Feed(f))) => Some((positions[i] - positions[i - 1]).norm() / f),
            (_, Some(Rate::Duration(t))) => Some(t),
        })
        .collect()
}

/// Each axis's share of its largest speed in a move of time `dt` (s) from the posture `from`
/// to `to` (axis angles, rad, and the external axes' values, SI): `|dq| / (v_max dt)` for the
/// six arm axes ([`Robot::max_speeds`]), then the external axes in the cell's order
/// ([`stiffid_core::robot::external::ExternalAxis::max_speed`]); 0 for an axis without a limit or
/// that does not move, infinite for one that moves in no time.
pub fn speed_shares(
    robot: &Robot,
    dt: f64,
    from: (&Vector6<f64>, &ExternalValues),
    to: (&Vector6<f64>, &ExternalValues),
) -> Vec<f64> {
    let share = |d: f64, v: f64| match (d == 0.0 || v.is_infinite(), dt > 0.0) {
        (true, _) => 0.0,
        (false, true) => d / (v * dt),
        (false, false) => f64::INFINITY,
    };
    let arm = (0..6).map(|k| share((to.0[k] - from.0[k]).abs(), robot.max_speeds()[k]));
    let axes = robot.external().map_or(&[][..], |c| c.axes());
    let external = (axes.iter().enumerate()).map(|(k, a)| {
        let (e0, e1) = (from.1.as_slice(), to.1.as_slice());
        match (e0.get(k), e1.get(k)) {
            (Some(x), Some(y)) => share((y - x).abs(), a.max_speed),
            _ => 0.0,
        }
    });
    arm.chain(external).collect()
}

/// Whether `robot` has a speed limit on any axis (arm or external).
pub fn has_speed_limits(robot: &Robot) -> bool {
    let axes = robot.external().map_or(&[][..], |c| c.axes());
    robot.max_speeds().iter().any(|v| v.is_finite()) || axes.iter().any(|a| a.max_speed.is_finite())
}

/// The speed limits of one path: the robot's axes and each point's move time.
pub(crate) struct Pace<'a> {
    robot: &'a Robot,
    times: &'a [Option<f64>],
}

impl<'a> Pace<'a> {
    /// The limits of `robot` at the move `times` (s, one per point, [`move_times`]); `None`
    /// without times or without any limit: no move is refused.
    pub(crate) fn new(robot: &'a Robot, times: Option<&'a [Option<f64>]>) -> Option<Self> {
        let times = times?;
        has_speed_limits(robot).then_some(Pace { robot, times })
    }

    /// Whether the move to point `i` from `from` to `to` (axis angles, rad; external values,
    /// SI) keeps every axis within its largest speed; any move to a point without a time.
    pub(crate) fn allows(
        &self,
        i: usize,
        from: (&Vector6<f64>, &ExternalValues),
        to: (&Vector6<f64>, &ExternalValues),
    ) -> bool {
        match self.times.get(i).copied().flatten() {
            None => true,
            Some(dt) => speed_shares(self.robot, dt, from, to)
                .iter()
                .all(|s| *s <= 1.0),
        }
    }
}
