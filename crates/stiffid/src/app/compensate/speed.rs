//! The axes' speed limits at the program's feed in the compensate job: the time of every move
//! the free variables' dynamic programming keeps the axes within
//! ([`stiffid_machining::compensate::Feasible::move_times`]), and each axis's highest share of
//! its largest speed along the path at the path's own values and at those chosen.

use super::{in_input, Input};
use nalgebra::{Vector3, Vector6};
use serde::Serialize;
use std::sync::Arc;
use stiffid_core::common::warning::{Warning, WarningKind};
use stiffid_core::common::words::{as_given, count};
use stiffid_core::robot::external::ExternalValues;
use stiffid_core::robot::ik::tool_pose;
use stiffid_core::{Result, Robot, Setup};
use stiffid_machining::compensate::{
    has_speed_limits, move_times, speed_shares, Compensated, Options, PathPoint, Rate, Target,
};
use stiffid_machining::program::external::cell_values;
use stiffid_machining::program::speed::Speed;
use stiffid_machining::program::JointProgram;
use stiffid_machining::{path, Program};

/// Why the moves were not checked without a limit.
const NO_LIMITS: &str =
    "no axis has a speed limit (max_speed_deg_s, max_speed_mm_s, a URDF's <limit velocity>)";
/// Why the moves of a path file without feeds were not checked.
const NO_FEED_COLUMN: &str = "the path file has no feed_mm_s column";

/// The axes' speed limits at the program's feed (`compensate`'s free variables keep every axis
/// within its largest speed between consecutive points; the path's own moves are kept whatever
/// they do). A move's time is the TCP distance between the program's targets (in the part's
/// frame) over the feed of the move (a G-code program's `F` in force, a path file's
/// `feed_mm_s`, a robot program's programmed path speed), or the time a robot program gives
/// ([`stiffid_machining::program::speed`]); the first point, a rapid move (`G0`) and a joint
/// motion (the controller's own speed) have none, nor a linear motion whose speed the program
/// gives in a form stiffid does not read (`moves_not_read`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct SpeedLimits {
    /// Whether the moves were checked: an axis has a largest speed and the path a feed.
    pub checked: bool,
    /// Why they were not (no limit, no feed); `null` when they were.
    pub not_checked_because: Option<String>,
    /// A robot program's linear moves whose programmed speed is not read (a variable, a
    /// register, an orientation speed: a warning names the first and why): not checked.
    pub moves_not_read: usize,
    /// Every axis: the arm's six (`q1`..`q6`), then the cell's external axes in order.
    pub axes: Vec<AxisSpeed>,
}

/// One axis's largest speed and its highest share of it along the path, `|dq| / (v_max dt)`
/// over the moves with a time (above 1: faster than the axis can move at the feed). The shares
/// are of the nominal postures (the compensation's change of an axis is a small fraction of a
/// degree); `null` when the moves were not checked or the axis has no limit.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct AxisSpeed {
    /// The axis: `q1`..`q6` for the arm's, an external axis's name.
    pub axis: String,
    /// A rotary axis's largest speed, deg/s; `null` for a linear axis or none.
    pub max_speed_deg_s: Option<f64>,
    /// A linear axis's largest speed, mm/s; `null` for a rotary axis or none.
    pub max_speed_mm_s: Option<f64>,
    /// The highest share at the path's own values.
    pub own_highest_share: Option<f64>,
    /// The program or path file line of the point the own highest share moves to (`null` when
    /// no limited axis moves).
    pub own_line: Option<u64>,
    /// That point's number along the path, 1-based.
    pub own_point: Option<usize>,
    /// The highest share at the values chosen (the path's own without a free variable).
    pub chosen_highest_share: Option<f64>,
    /// The line of the point the chosen highest share moves to.
    pub chosen_line: Option<u64>,
    /// That point's number along the path, 1-based.
    pub chosen_point: Option<usize>,
}

/// The options with the move times of `input` on `setup` (`program`: the program it holds,
/// read and its Cartesian targets resolved; none where the moves are not checked), and the
/// tracker of the shares along the path.
///
/// # Errors
/// Those of [`path::feeds`] and [`path::points`] for a path file with a `feed_mm_s` column, of
/// [`cell_values`] for a robot program (as [`stiffid_core::Error::Input`] naming the file).
pub(super) fn prepare<'a>(
    setup: &'a Setup,
    input: &Input,
    program: Option<&Program>,
    mut options: Options,
) -> Result<(Options, Tracker<'a>)> {
    let robot = setup.robot();
    let (times, why, not_read) = match has_speed_limits(robot) {
        false => (None, Some(NO_LIMITS), Vec::new()),
        true => times(setup, input, program)?,
    };
    let times: Option<Arc<[Option<f64>]>> = times.map(Into::into);
    options.feasible.move_times = times.clone();
    let axes = 6 + robot.external().map_or(0, |c| c.len());
    let tracker = Tracker {
        robot,
        times,
        why,
        not_read,
        previous: None,
        own: vec![Highest::default(); axes],
        chosen: vec![Highest::default(); axes],
    };
    Ok((options, tracker))
}

/// The move times of a path (s, one per point), or why there are none; the lines of the moves
/// whose speed is not read and why.
type Times = (
    Option<Vec<Option<f64>>>,
    Option<&'static str>,
    Vec<(u64, String)>,
);

/// The move times of `input` (module docs), or why there are none.
fn times(setup: &Setup, input: &Input, program: Option<&Program>) -> Result<Times> {
    let robot = setup.robot();
    let tcp = setup.arm().tool().tcp;
    match (input, program) {
        (Input::Path { name, text, frame }, _) => {
            let Some(feeds) = path::feeds(text).map_err(|e| in_input(name, e))? else {
                return Ok((None, Some(NO_FEED_COLUMN), Vec::new()));
            };
            let points = path::points(text, *frame, robot.external());
            let points: Result<Vec<PathPoint>> = points.and_then(Iterator::collect);
            let points = points.map_err(|e| in_input(name, e))?;
            let at: Vec<Vector3<f64>> = (points.iter())
                .map(|p| match &p.target {
                    Target::Pose(x) => x.translation.vector,
                    Target::Posture(q) => in_part(robot, &tcp, q, p.external.as_slice()),
                })
                .collect();
            let rates: Vec<Option<Rate>> = feeds.iter().map(|f| f.map(Rate::Feed)).collect();
            Ok((Some(move_times(&at, &rates)), None, Vec::new()))
        }
        (_, Some(Program::GCode(g))) => {
            let at: Vec<Vector3<f64>> = g.points.iter().map(|p| p.position).collect();
            let rates: Vec<Option<Rate>> = (g.points.iter())
                .map(|p| match p.motion {
                    stiffid_machining::gcode::Motion::Feed => p.feed.map(Rate::Feed),
                    stiffid_machining::gcode::Motion::Rapid => None,
                })
                .collect();
            Ok((Some(move_times(&at, &rates)), None, Vec::new()))
        }
        (Input::Program { name, .. }, Some(Program::Robot(p))) => {
            robot_times(robot, &tcp, p).map_err(|e| in_input(name, e))
        }
        (Input::Program { .. }, None) => Ok((None, None, Vec::new())),
    }
}

/// The move times of a robot program's targets at their programmed speeds
/// ([`JointProgram`]'s [`Speed`]s).
fn robot_times(robot: &Robot, tcp: &Vector3<f64>, p: &JointProgram) -> Result<Times> {
    let external = cell_values(p, robot.external())?;
    let at: Vec<Vector3<f64>> = (p.targets.iter().zip(&external))
        .map(|(t, e)| {
            let q = Vector6::from(t.q_deg).map(f64::to_radians);
            in_part(robot, tcp, &q, e)
        })
        .collect();
    let mut not_read = Vec::new();
    let rates: Vec<Option<Rate>> = (p.targets.iter())
        .map(|t| match &t.speed {
            Speed::Joint => None,
            Speed::Path(v) => Some(Rate::Feed(*v)),
            Speed::Duration(s) => Some(Rate::Duration(*s)),
            Speed::Unread(why) => {
                not_read.push((t.line, why.clone()));
                None
            }
        })
        .collect();
    Ok((Some(move_times(&at, &rates)), None, not_read))
}

/// The TCP at the axis angles `q` (rad) and the external values `e` (SI, the cell's order) in
/// the part's frame (m): the arm on its carriage, through the cell back by the positioner.
fn in_part(robot: &Robot, tcp: &Vector3<f64>, q: &Vector6<f64>, e: &[f64]) -> Vector3<f64> {
    let at = tool_pose(&robot.frames(q), tcp);
    match robot.external() {
        None => at.translation.vector,
        Some(c) => {
            let part = c.positioner_pose(e).inverse() * c.carrier_pose(e) * at;
            part.translation.vector
        }
    }
}

/// An axis's highest share so far and where.
#[derive(Debug, Clone, Copy, Default)]
struct Highest {
    share: f64,
    line: u64,
    point: usize,
}

/// The shares of the axes' speeds along the path, point by point.
pub(super) struct Tracker<'a> {
    robot: &'a Robot,
    times: Option<Arc<[Option<f64>]>>,
    why: Option<&'static str>,
    /// The moves whose programmed speed is not read: their lines and why.
    not_read: Vec<(u64, String)>,
    /// The previous point's own and chosen axis angles and external values.
    previous: Option<[(Vector6<f64>, ExternalValues); 2]>,
    own: Vec<Highest>,
    chosen: Vec<Highest>,
}

impl Tracker<'_> {
    /// Adds the point of index `i` (0-based, path order) with its result.
    pub(super) fn add(&mut self, i: usize, p: &PathPoint, r: &Compensated) {
        let Some(times) = &self.times else { return };
        let chosen_e = match r.external.is_empty() {
            true => p.external,
            false => r.external,
        };
        let now = [(r.q_before.unwrap_or(r.q), p.external), (r.q, chosen_e)];
        if let (Some(before), Some(Some(dt))) = (&self.previous, times.get(i)) {
            for (k, highest) in [&mut self.own, &mut self.chosen].into_iter().enumerate() {
                let (from, to) = (&before[k], &now[k]);
                let shares = speed_shares(self.robot, *dt, (&from.0, &from.1), (&to.0, &to.1));
                for (h, s) in highest.iter_mut().zip(shares) {
                    if s > h.share {
                        *h = Highest {
                            share: s,
                            line: p.line,
                            point: i + 1,
                        };
                    }
                }
            }
        }
        self.previous = Some(now);
    }

    /// The document's object.
    pub(super) fn document(&self) -> SpeedLimits {
        let robot = self.robot;
        let mut axes: Vec<(String, f64, bool)> = (0..6)
            .map(|k| (format!("q{}", k + 1), robot.max_speeds()[k], true))
            .collect();
        for a in robot.external().map_or(&[][..], |c| c.axes()) {
            let rotary = a.kind == stiffid_core::robot::external::AxisKind::Rotary;
            axes.push((a.name.clone(), a.max_speed, rotary));
        }
        let checked = self.times.is_some();
        let axes = (axes.into_iter().enumerate())
            .map(|(k, (axis, v, rotary))| {
                let limited = v.is_finite();
                let shown = |h: &Highest| (checked && limited).then_some(*h);
                let at = |h: Option<Highest>| h.filter(|h| h.point > 0);
                let (own, chosen) = (shown(&self.own[k]), shown(&self.chosen[k]));
                AxisSpeed {
                    axis,
                    max_speed_deg_s: (limited && rotary).then(|| as_given(v.to_degrees())),
                    max_speed_mm_s: (limited && !rotary).then(|| as_given(v * 1e3)),
                    own_highest_share: own.map(|h| h.share),
                    own_line: at(own).map(|h| h.line),
                    own_point: at(own).map(|h| h.point),
                    chosen_highest_share: chosen.map(|h| h.share),
                    chosen_line: at(chosen).map(|h| h.line),
                    chosen_point: at(chosen).map(|h| h.point),
                }
            })
            .collect();
        SpeedLimits {
            checked,
            not_checked_because: self.why.map(str::to_string),
            moves_not_read: self.not_read.len(),
            axes,
        }
    }

    /// The warning that some moves' programmed speeds are not read, naming the first.
    pub(super) fn warning(&self) -> Option<Warning> {
        let (line, why) = self.not_read.first()?;
        let n = self.not_read.len();
        Some(Warning::new(
            WarningKind::Speed,
            format!(
                "the programmed speed of {} is not read, so the axes' speed limits are not checked there (the first, line {line}: {why})",
                count(n, "linear move")
            ),
        ))
    }
}
