//! Deflection compensation of a machining path: the axis angles that put the loaded tool where
//! the unloaded robot would.
//!
//! ## The loaded robot
//! At commanded axis angles q a wrench `W` (base frame) at the tool centre point (TCP) deflects the
//! joint springs by `dq = h .* (J^T W)` (Zhang et al. 2021, Eq. 4-5, the torques of the unloaded
//! posture: the complementary stiffness is neglected, see [`stiffid_core::observation::cartesian`]), and the rigid links
//! then put the tool at the forward kinematics of the deflected joints, [`Model::loaded_pose`]. (Eq. 6's
//! `J dq` is its first-order approximation; the two differ by about `|dq|^2` times the reach,
//! a micrometre, which matters at the 0.1 micrometre this module solves to.)
//!
//! ## Compensation
//! The compensated axis angles `q_c` solve `loaded_pose(q_c) = T_nominal`, the TCP pose of the
//! unloaded (rigid) robot at the nominal posture, the loaded pose sagging under the robot's own
//! weight too when the compliance carries a calibration's gravity terms
//! ([`crate::weight`]), by Newton steps `q += J^-1 e` from the nominal posture
//! (the first step is the classical `q - J^-1 J dq`), until the residual is below
//! 1e-10 m and 1e-10 rad ([`Stop::Converged`]) or for at most
//! [`Options::max_iterations`] steps ([`Stop::IterationLimit`]; success needs 0.1 micrometre and
//! 1 microradian: a point stopped at the limit within them
//! is kept, and the compensate job warns). The Jacobian neglects `d(dq)/dq`, so the convergence
//! is linear with a rate of about `|dq|`: three or four steps.
//!
//! ## The free tool axis
//! In 5-axis milling and drilling the rotation about the spindle (tool z) is free. With
//! [`FreeVariables::tool_rotation`], every path point's pose is turned about its tool z by the
//! angle that minimises the TCP translation deflection, within the joint limits and with at most
//! its step ([`FreeRange::step`]) between consecutive points: dynamic programming over a grid of
//! angles, each angle's postures continued along the path by inverse kinematics; a point only takes
//! an angle whose deflection is no larger than at the nominal angle (so the nominal path is always
//! feasible and no point's deflection rises); the sum of the deflections is minimised, plus a
//! tie-breaking cost of 1e-6 times each point's nominal deflection per full range away from the
//! path's own angle and per full step between points: where the angles tie (a TCP on the spindle
//! axis turns nothing) the path keeps its own angle, and a rotation is smooth along the path, never
//! a zig-zag between equal angles; a gain below about 1e-6 of the deflection is not worth a turn.
//! The wrench stays fixed in the base frame (the process force does not turn with the spindle).
//! This is the redundancy resolution of stiffness-oriented posture optimisation for robotic
//! machining: Caro, Dumas, Garnier and Furet, "Workpiece placement optimization for machining
//! operations with a KUKA KR270-2 robot", IEEE ICRA 2013; Xiong, Ding and Zhu, "Stiffness-based
//! pose optimization of an industrial robot for five-axis milling", Robotics and
//! Computer-Integrated Manufacturing 55, 2019.
//!
//! With [`Objective::Bound`] the cost of a point is its error bound ([`Budget`], without the
//! residual the Newton steps leave), taken only where it is no larger than at the path's own
//! angle; with [`Aggregate::Max`] the dynamic programming minimises the worst point's cost along
//! the path (a bottleneck path: each angle keeps the least worst cost of the paths reaching it,
//! ties broken by the sum with the tie-breaking costs) instead of the sum. Every point's budget
//! is stated whatever the objective ([`Compensated::budget`]); [`map`] gives every point's bound,
//! deflection, condition number and distance to the joint limits at every angle of the grid.
//!
//! ## The free station
//! On a robot on a track the station is free too: with `FreeVariables::station`, [`path_on_track`] moves
//! the carrier's first axis at every point of a path file (and [`crate::compensate()`]
//! at every target of a program, written back with the stations chosen) by an offset from the
//! path's own station on a grid of `max_step` spacing within `+-range` (and the axis's travel), jointly
//! with the rotation about tool z when the free tool axis is given: the states are the
//! (station, rotation) pairs, each state's postures continued along the path by inverse
//! kinematics to the same point of the part (the TCP stays where the path puts it in the cell;
//! the wrench stays fixed in the cell frame), and the same dynamic programming chooses them,
//! the offset changing by at most one grid step between consecutive points and the rotation by
//! at most its `max_step`, a state taken only where its cost is no larger than at the path's own
//! values, the tie-breaking cost summed over both variables. The station moves at most
//! `max_step` per point (at a feed `v` and points `s` apart, `max_step v / s`); the axes' own
//! speed limits bind further ("Speed limits").
//!
//! ## Refining the grid
//! The grid's step is also the largest change between points, and a fine grid everywhere costs
//! `states^2` transitions per point and a column of inverse kinematics per state. With
//! [`Options::refine`] `= L` (at most 4) the line the dynamic programming
//! chose on the grid is refined `L` times ([`refine`]): at each level every free axis' step is
//! halved and the states at each point are the previous level's values plus `k` halved steps, `|k|
//! <= 2` on every axis (a band of +-1 of the previous level's cells), within each axis' range, the
//! travel and the cone. Each band state's postures are continued along the path by inverse
//! kinematics at its per-point values, a state is taken where its cost is no larger than at the
//! path's own values and its posture passes the checks below, and a dynamic programming over the
//! bands chooses the line of least value whose every free variable changes by at most its
//! `max_step` between points (the user's step keeps its meaning: the refined line moves in finer
//! steps, never faster), with the same tie-breaking costs. The previous line is in the band with
//! its own postures, so the refined line's value (the sum, or the worst point's) is never above the
//! grid's, and no point's cost rises above the path's own. One level costs `(4 BAND + 1)^axes`
//! columns, 5 on one free axis: a fraction of a grid of the halved step everywhere.
//!
//! ## Feasibility
//! Every posture a free variable moves a point to must be feasible ([`Feasible`], the checks
//! `stiffid place` asks of a placement): each axis angle at least [`Feasible::margin`] from its
//! joint limits, the TCP Jacobian's condition number at most [`Feasible::max_condition`] and,
//! with the setup's `[cell]` ([`Feasible::checks_cell`]), the robot's bodies clear of the floor,
//! the obstacles and each other ([`stiffid_core::cell::Checker`]; an arm on a carrier on its carriage at
//! the state's station, [`stiffid_core::cell::Checker::feasibility_at`]). A state whose posture
//! fails is not taken at that point; the path's own posture is kept as it is whatever it fails
//! (the no-worse rule: the path stays feasible as given). Each result counts its point's states
//! each check removed ([`Compensated::removed`]: states that inverse kinematics reaches with a
//! cost no larger than the path's own, counted by the first check they fail). The floor and the
//! fixed obstacles stand in the cell frame; the boxes a positioner carries
//! ([`stiffid_core::setup::Obstacle::carried_by`]) turn with the state's table and tilt.
//!
//! ## Speed limits
//! At the program's feed every axis must keep within its largest speed
//! ([`stiffid_core::Robot::max_speeds`], [`stiffid_core::robot::external::ExternalAxis::max_speed`]), or the
//! controller slows the TCP below the feed. With [`Feasible::move_times`] (the time of the move
//! to each point: the TCP distance between the program's targets over the feed, or the time a
//! robot program gives, [`move_times`])
//! the dynamic programming takes a move from a state at point `i - 1` to a state at point `i`
//! only where every axis with a limit moves at most `v_max dt_i` ([`speed_shares`]): the arm's
//! six by the two states' nominal postures, the external axes by their values. The path's own
//! moves are kept whatever they do (no point worse than the program); a point without a time
//! (the first, a rapid or joint move, a robot program's linear move whose speed is not read,
//! [`crate::program::speed`]) takes any move. Each result counts the moves to it refused
//! ([`Removed::speed`]).
//!
//! ## The free positioner
//! With `FreeVariables::positioner` the positioner's last axis (the table's turn; a turntable's only
//! axis) is a variable of the same grid, with its own range and step (deg), alone or jointly
//! with the station and the rotation (the states are their combinations). Turning the table
//! turns the part, so each point's target in the arm's frame moves by
//! `C(e')^-1 P(e') P(e)^-1 C(e)` ([`stiffid_core::robot::external`]; the station's shift is the case
//! `P(e') = P(e)`), the process force turns with the part (the cut follows it: a path file's
//! wrench too), and a program's tool weight stays along the cell's `-z` at the turned tool. The
//! same rules hold: the axis's travel, one grid step at most between points, no point worse
//! than at the path's own values. With `FreeVariables::tilt` a two-axis positioner's first
//! axis (the tilt, which carries the table's axis) is a variable of the grid too, by the same
//! shift with both angles in `P(e')`.
//!
//! ## Lead and tilt
//! In ball-end milling and deburring the tool's axis may lean from the program's within a cone
//! the process allows (never in drilling: a drill's axis is the hole's). With [`FreeVariables::lead_tilt`]
//! the lead and the tilt are two more variables of the same grid, alone or jointly with the
//! rotation, the station and the positioner (the states are their combinations). At every point
//! the lean's frame is `f`, the feed direction across the tool axis (the TCP's motion from the
//! previous point; the first point's to the second; a point that does not move across the axis
//! takes the previous point's, else the tool's own x axis), and `c = z x f` across it, `z` the
//! path's own tool axis: the lead leans the axis towards the feed, the tilt across it, and the
//! leaned tool is the path's pose turned by `sqrt(lead^2 + tilt^2)` about `lead c - tilt f`
//! through the TCP ([`lean`]): its axis `cos(a) z + sin(a) (lead f + tilt c) / a` makes the
//! angle `a = sqrt(lead^2 + tilt^2)` with the path's. The TCP stays on the path's point; only
//! the tool's axis leans (after the rotation about it). Lead and tilt take the values
//! `k max_step` within the cone's half angle (a state with `a` above a point's cone is not a
//! state there; a program's point takes its operation's cone, a rapid move, a point no
//! operation covers and a drilling point none), each changing by at most one step between
//! consecutive points. The wrench at the TCP stays fixed in the part frame (on a fixed base,
//! the base frame), as for the rotation: the process force is the process file's mean over a
//! revolution in the frame of the feed and the surface, which a lean within the cone does not
//! move, and the change of the cutting edge's engagement with a small lean is a second-order
//! change of that mean the force model's tolerance covers; the tool's weight is kept at the
//! path's axis (its moment about the TCP changes by at most `2 sin(cone / 2)` of itself, 17% of
//! a small moment at 10 deg).
//!
//! ## The free configuration
//! A pose is reached in up to eight configurations of the arm (the shoulder, elbow and wrist
//! choices, [`stiffid_core::robot::configuration`]). With [`FreeVariables::configuration`] the
//! whole path is compensated in each ([`path_configurations`], [`crate::compensate()`]): the path's
//! own as given, every other from its posture at the first point (inverse kinematics from 128
//! seeded starts, the solution nearest to the path's own posture in each configuration), continued
//! point by point, a joint target solved from its nominal pose; the other free variables are chosen
//! in each by their dynamic programming. A configuration cannot change along a continuous cut, so
//! one holds the whole path ([`Scope::Program`]), or, with [`Scope::Run`], each run ([`starts`]: a
//! cut and the joint moves that lead to it, where the arm may change configuration): each run is
//! compensated alone in each configuration, from the posture the path's own reaches at its first
//! point, so the other free variables' step limits start afresh at each run (the joint move between
//! runs is a move of its own), and the runs' choices minimise the program's objective (the max over
//! the runs, or the sum: per run). A configuration is refused for a path or a run at the first
//! point inverse kinematics cannot reach in it, that its compensation fails, whose posture fails a
//! check of [`Feasible`] or leaves the configuration. Of the others the one of least path objective
//! is kept (each point's TCP deflection or bound, as the other free variables minimise, summed or
//! the worst, [`Aggregate`]), the path's own on a tie: no path is worse than in its own
//! configuration, which is kept whatever the checks say. When no other configuration takes the
//! path, its own is kept with a warning; when the path's own cannot take it, the best other one is,
//! with a warning; when none can, the path's own error.
//!
//! With [`Objective::Surge`] the same dynamic programming minimises the breakthrough surge of a
//! drilling program instead (`path_with_exits`, [`crate::dynamics`]): a drilling exit's cost is the
//! surge of its thrust at the turned posture, taken only where it is no larger than at the path's
//! own angle; every other point costs nothing but the tie-breaking cost, here 1e-6 times the path's
//! largest surge (a rotation about the drill axis changes neither the exits nor the thrust). Where
//! the surge cannot be computed at the path's own angle (a singular posture) the point keeps that
//! angle.

use nalgebra::{Isometry3, Vector6};
pub(crate) use stiffid_core::common::stop::Stop;
use stiffid_core::observation::deflection::Frame;

pub mod budget;
mod configuration;
mod feasible;
mod fixed_base;
pub mod free;
pub mod grammar;
mod lead_tilt;
mod map;
mod model;
mod options;
pub mod refine;
pub(crate) mod runs;
mod scope;
mod speed;
mod station;
mod stream;
pub(crate) mod tool_axis;
mod validate;
pub(crate) mod variables;

pub(crate) use budget::Budget;
pub use configuration::{Branch, Configurations, Run};
pub use feasible::{Feasible, Removed};
pub use free::{FreeOption, Freedom};
pub(crate) use lead_tilt::cones;
pub use lead_tilt::lean;
pub use map::{map, ChosenValues, Map};
pub use model::{Model, Newton};
pub use options::{MapVariable, Options};
pub(crate) use runs::choose;
pub use runs::{path_configurations, path_runs, starts};
pub use scope::Scope;
pub use speed::{has_speed_limits, move_times, speed_shares, Rate};
pub(crate) use station::on_track;
pub use station::path_on_track;
pub(crate) use stream::path_in_cones;
pub use stream::{path, stream, CHUNK};
pub use variables::{
    Aggregate, Free, FreeRange, FreeVariables, LeadTilt, Limits, Objective, Variable,
};
pub(crate) use variables::{
    CONFIGURATION_SEEDS, LEAD_TILT_MAX_CONE_DEG, MAX_CONFIGURATION_POINTS, MAX_GRID_CELLS,
};
/// The residual the Newton steps aim at, m.
pub(crate) const TOLERANCE_M: f64 = 1e-10;
/// The residual rotation the Newton steps aim at, rad.
pub(crate) const TOLERANCE_RAD: f64 = 1e-10;
/// The residual a compensated point must reach: 0.1 micrometre.
pub(crate) const REQUIRED_M: f64 = 1e-7;
/// The residual rotation a compensated point must reach: 1 microradian.
pub(crate) const REQUIRED_RAD: f64 = 1e-6;
/// Newton steps at most per point, and the default of [`Options::max_iterations`].
pub const MAX_ITERATIONS: usize = 30;
/// The relative weight of the free tool axis' tie-breaking cost (module docs).
pub(crate) const TIE_BREAK: f64 = 1e-6;

/// Where a path point is: axis angles, or a TCP pose reached by inverse kinematics.
#[derive(Debug, Clone, PartialEq)]
pub enum Target {
    /// Axis angles, rad.
    Posture(Vector6<f64>),
    /// TCP position (m) and tool orientation, base frame.
    Pose(Isometry3<f64>),
}

/// One point of a machining path.
#[derive(Debug, Clone, PartialEq)]
pub struct PathPoint {
    /// Its line in the path file (for errors), 1-based.
    pub line: u64,
    /// Where the TCP is.
    pub target: Target,
    /// The wrench `[f; m]` at the TCP, N and Nm, in `frame`.
    pub wrench: Vector6<f64>,
    /// The frame of the wrench.
    pub frame: Frame,
    /// The values of the cell's external axes at the point (SI: m, rad; the cell's order), as a
    /// path file or a program gives them ([`crate::path`],
    /// [`crate::compensate()`]); empty for a cell without external axes. The
    /// compensation itself works in the arm's frame: a path file's points are placed there by
    /// [`crate::cell::on_carriage`], a program's by [`crate::compensate()`].
    pub external: stiffid_core::robot::external::ExternalValues,
}

/// The compliance of every parameter of the setup's model and, from an identification, its
/// covariance ([`stiffid_core::model::Compliance`]).
pub use stiffid_core::model::Compliance;

/// One compensated path point, SI units, base frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Compensated {
    /// The nominal axis angles (after the tool-axis rotation, if optimised), rad.
    pub q: Vector6<f64>,
    /// The nominal TCP pose (m).
    pub pose: Isometry3<f64>,
    /// The wrench at the TCP, base frame, N and Nm.
    pub wrench: Vector6<f64>,
    /// TCP translation (m) and tool rotation (rad) under the wrench at the nominal posture (Eq. 6).
    pub deflection: Vector6<f64>,
    /// Its standard deviation per coordinate, given the compliance covariance.
    pub deflection_std: Option<Vector6<f64>>,
    /// The standard deviation of the translation's length `|dp|` (first order:
    /// `sqrt(u^T Cov(dp) u)`, `u = dp / |dp|`), m.
    pub translation_norm_std: Option<f64>,
    /// The prediction interval of the translation (m, base frame) at [`Options::level`], given
    /// the compliance's prediction calibration ([`stiffid_core::model::prediction`]).
    pub deflection_interval: Option<stiffid_core::model::prediction::Interval>,
    /// The compensated axis angles `q_c`, rad.
    pub q_compensated: Vector6<f64>,
    /// `|p_nominal - p_loaded(q_c)|`, m.
    pub residual_position: f64,
    /// The rotation between the nominal and the loaded tool at `q_c`, rad.
    pub residual_rotation: f64,
    /// Newton steps taken.
    pub iterations: usize,
    /// Why the Newton steps stopped ([`Newton::stop`]).
    pub stop: Stop,
    /// The rotation about tool z chosen by [`FreeVariables::tool_rotation`] (0 without), rad.
    pub tool_rotation: f64,
    /// The lead chosen by [`FreeVariables::lead_tilt`] (0 without), rad: the tool axis leaned towards the
    /// feed ([`lean`]).
    pub lead: f64,
    /// The tilt chosen by [`FreeVariables::lead_tilt`] (0 without), rad: the tool axis leaned across the
    /// feed ([`lean`]).
    pub tilt: f64,
    /// With [`FreeVariables::tool_rotation`]: the deflection at the path's own rotation, before optimisation.
    pub deflection_before: Option<Vector6<f64>>,
    /// With [`FreeVariables::tool_rotation`]: the nominal axis angles at the path's own rotation, before
    /// optimisation, rad.
    pub q_before: Option<Vector6<f64>>,
    /// The axes of `q` outside the region the compliance was identified from
    /// ([`stiffid_core::model::region`]): empty inside; `None` when the compliance records no region.
    pub outside_region: Option<Vec<stiffid_core::common::limits::Violation>>,
    /// The error budget at [`Options::level`] ([`Budget`]).
    pub budget: Budget,
    /// With [`FreeVariables::tool_rotation`]: the bound at the path's own rotation, before optimisation, with
    /// this point's residual, m.
    pub bound_before: Option<f64>,
    /// The values of the cell's external axes at the point (SI, the cell's order): the station
    /// and table angle chosen by `FreeVariables::station` and `FreeVariables::positioner`, else the path's or the
    /// program's own; empty for a robot without external axes.
    pub external: stiffid_core::robot::external::ExternalValues,
    /// With a free variable: the states of its grid at this point that the feasibility checks
    /// removed ([`Feasible`]); zero without.
    pub removed: Removed,
}

#[cfg(test)]
mod budget_tests;

#[cfg(test)]
mod free_tests;

#[cfg(test)]
mod refine_tests;

#[cfg(test)]
mod runs_tests;

#[cfg(test)]
mod tool_axis_tests;

#[cfg(test)]
mod variables_tests;
