//! Inverse kinematics of a tool pose for any 6R chain we load (presets, DH TOML, URDF): damped
//! least squares on our own geometric Jacobian, within the joint limits, continued from a start
//! posture. No analytic solver per robot.
//!
//! The pose of a tool point p in a posture is [`tool_pose`]: p in the base frame and the flange's
//! orientation. The error of a posture is `e = [p_target - p; phi]`, `phi` the rotation vector of
//! `R_target R^T` (base frame). Each step solves `(J J^T + lambda^2 I) y = e`, `dq = J^T y`
//! (damped least squares, Wampler 1986; Nakamura and Hanafusa 1986) with the rotation rows
//! weighted by `ROTATION_WEIGHT`, and adapts the damping Levenberg-Marquardt fashion: smaller
//! after a step that lowers `|e|`, larger (and the step refused) otherwise. Near the solution the
//! damping vanishes and the steps are Gauss-Newton's (quadratic convergence). Steps are clamped to
//! the joint limits.
//!
//! From the start posture first, so a path continued point by point stays on one branch of
//! solutions; if that fails, from [`Options::restarts`] seeded random postures within the limits.
//!
//! A descent stops ([`Stop`]) when the pose is reached within the tolerances
//! ([`Stop::Converged`]), when no damping up to `1e3` gives a step that lowers `|e|`
//! ([`Stop::DampingExhausted`]: a local minimum of the error, a joint limit, the edge of the
//! workspace), or after [`Options::max_iterations`] steps ([`Stop::IterationLimit`]). When no
//! start converges, the error says why the closest one stopped.

use crate::common::stop::Stop;
use crate::robot::kinematics::{Coordinates, Frames};
use crate::{common::limits, Error, Result, Robot};
use nalgebra::{Isometry3, Matrix6, Translation3, Vector3, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Metres per radian of the rotation rows of the error and the Jacobian (a characteristic length
/// of the workspace), so one step weighs a millimetre and a milliradian alike.
pub(crate) const ROTATION_WEIGHT: f64 = 1.0;

/// The pose of the tool point `point` (flange frame, m): its position in the base frame (m) and the
/// flange's orientation.
pub fn tool_pose(frames: &Frames, point: &Vector3<f64>) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::from(frames.point(point)),
        frames.flange.rotation,
    )
}

/// `[p_target - p; phi]`: translation (m) and rotation vector (rad) from `pose` to `target`,
/// base frame.
pub fn pose_error(target: &Isometry3<f64>, pose: &Isometry3<f64>) -> Vector6<f64> {
    let dp = target.translation.vector - pose.translation.vector;
    let phi = (target.rotation * pose.rotation.inverse()).scaled_axis();
    Vector6::new(dp.x, dp.y, dp.z, phi.x, phi.y, phi.z)
}

/// Tolerances and effort.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// Largest accepted distance of the tool point, m.
    pub position_tolerance: f64,
    /// Largest accepted rotation, rad.
    pub rotation_tolerance: f64,
    /// Steps per start, at least 1.
    pub max_iterations: usize,
    /// Seeded random starts tried after the given one fails.
    pub restarts: usize,
    /// Seed of the random starts.
    pub seed: u64,
}

impl Options {
    /// Checks every field against its documented limit: both tolerances within
    /// [`limits::IK_TOLERANCE`], `max_iterations` 1 to [`limits::MAX_IK_ITERATIONS`], `restarts`
    /// at most [`limits::MAX_IK_RESTARTS`]. [`solve`] calls it.
    ///
    /// # Errors
    /// [`Error::InvalidField`] naming the field (`ik::Options.restarts`), the value and the range.
    pub fn validate(&self) -> Result<()> {
        let tolerances = [
            ("position_tolerance", self.position_tolerance),
            ("rotation_tolerance", self.rotation_tolerance),
        ];
        for (field, value) in tolerances {
            limits::check(
                &format!("ik::Options.{field}"),
                &[value],
                &limits::IK_TOLERANCE,
            )?;
        }
        let (iterations, restarts) = (self.max_iterations as u64, self.restarts as u64);
        let most = limits::MAX_IK_ITERATIONS;
        limits::check_integer("ik::Options.max_iterations", iterations, 1, most)?;
        limits::check_integer("ik::Options.restarts", restarts, 0, limits::MAX_IK_RESTARTS)
    }
}

impl Default for Options {
    /// 1e-10 m and 1e-10 rad, 100 steps, 8 restarts, seed 1.
    fn default() -> Self {
        Self {
            position_tolerance: 1e-10,
            rotation_tolerance: 1e-10,
            max_iterations: 100,
            restarts: 8,
            seed: 1,
        }
    }
}

/// A posture that reaches the pose.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    /// Axis angles, rad, within the joint limits.
    pub q: Vector6<f64>,
    /// Steps taken (over every start tried).
    pub iterations: usize,
    /// Remaining distance, m.
    pub position_error: f64,
    /// Remaining rotation, rad.
    pub rotation_error: f64,
}

/// Axis angles (rad) within the joint limits that put the tool point `point` (flange frame, m) at
/// the pose `target` (base frame, m), starting from `q0` (rad).
///
/// # Errors
/// [`Error::InvalidField`] for `options` outside their limits ([`Options::validate`]);
/// [`Error::NotFinite`] for a non-finite target or start; [`Error::Unreachable`] with the smallest
/// remaining distance and rotation and why that start stopped ([`Stop`]) when no start converges
/// (the pose is outside the workspace or only reachable beyond a joint limit, or the steps ran out:
/// [`Stop::IterationLimit`]).
pub fn solve(
    robot: &Robot,
    point: &Vector3<f64>,
    target: &Isometry3<f64>,
    q0: &Vector6<f64>,
    options: &Options,
) -> Result<Solution> {
    options.validate()?;
    let finite = target.translation.vector.iter().all(|v| v.is_finite())
        && target.rotation.coords.iter().all(|v| v.is_finite());
    if !finite || !q0.iter().all(|v| v.is_finite()) {
        return Err(Error::NotFinite {
            what: "the target pose or the start posture of inverse kinematics".into(),
        });
    }
    let mut rng = ChaCha8Rng::seed_from_u64(options.seed);
    let mut iterations = 0;
    let mut best = (f64::INFINITY, f64::INFINITY, Stop::DampingExhausted);
    let mut start = *q0;
    for attempt in 0..=options.restarts {
        if attempt > 0 {
            start = random_posture(robot, &mut rng);
        }
        let (s, stop) = descend(robot, point, target, &start, options);
        iterations += s.iterations;
        if converged(&s, options) {
            return Ok(Solution { iterations, ..s });
        }
        if s.position_error + s.rotation_error * ROTATION_WEIGHT < best.0 + best.1 * ROTATION_WEIGHT
        {
            best = (s.position_error, s.rotation_error, stop);
        }
    }
    Err(Error::Unreachable {
        position_error_mm: best.0 * 1e3,
        rotation_error_deg: best.1.to_degrees(),
        stop: best.2,
        starts: options.restarts + 1,
    })
}

/// Where the target of [`solve_at`] is given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TargetFrame {
    /// The cell frame (the robot's world frame).
    Cell,
    /// The part's frame on the positioner: the part's frame at `e = 0` in the cell (a setup's
    /// `[workpiece]`), the target in it; the part turns with the positioner's axes at `e`.
    Part(Isometry3<f64>),
}

/// [`solve`] for the arm of a cell with external axes at their values `e` (SI, the cell's
/// order, [`crate::robot::external`]): the arm on its carrier at `e`, the target in the cell
/// frame or in the part's frame on the positioner at `e` (`P(e) * workpiece * target`). The
/// external axes stay as given: the axis angles alone are solved for. Without external axes,
/// `e` empty and [`TargetFrame::Cell`]: [`solve`].
///
/// # Errors
/// [`Error::InvalidField`] (`external`) when `e` are not the robot's external axes' values
/// within their travel ([`crate::robot::external::ExternalAxes::check`]); those of [`solve`].
pub fn solve_at(
    robot: &Robot,
    point: &Vector3<f64>,
    target: &Isometry3<f64>,
    frame: TargetFrame,
    e: &[f64],
    q0: &Vector6<f64>,
    options: &Options,
) -> Result<Solution> {
    robot.check_external(e, "external")?;
    let (carrier, positioner) = match robot.external() {
        Some(axes) => (axes.carrier_pose(e), axes.positioner_pose(e)),
        None => (Isometry3::identity(), Isometry3::identity()),
    };
    let in_cell = match frame {
        TargetFrame::Cell => *target,
        TargetFrame::Part(workpiece) => positioner * workpiece * target,
    };
    solve(robot, point, &(carrier.inverse() * in_cell), q0, options)
}

fn converged(s: &Solution, options: &Options) -> bool {
    s.position_error <= options.position_tolerance && s.rotation_error <= options.rotation_tolerance
}

/// A uniform random posture within the joint limits (within +-pi on an unlimited axis).
pub fn random_posture(robot: &Robot, rng: &mut ChaCha8Rng) -> Vector6<f64> {
    Vector6::from_fn(|i, _| {
        let lo = robot.limits().lower[i].max(-std::f64::consts::PI);
        let hi = robot.limits().upper[i].min(std::f64::consts::PI);
        lo + (hi - lo) * rng.random::<f64>()
    })
}

/// The weighted error and its squared norm at posture `q`.
fn weighted_error(
    robot: &Robot,
    point: &Vector3<f64>,
    target: &Isometry3<f64>,
    q: &Vector6<f64>,
) -> (Frames, Vector6<f64>) {
    let frames = robot.frames(q);
    let mut e = pose_error(target, &tool_pose(&frames, point));
    e.fixed_rows_mut::<3>(3).scale_mut(ROTATION_WEIGHT);
    (frames, e)
}

/// Damped least squares from one start (module docs), and why it stopped.
fn descend(
    robot: &Robot,
    point: &Vector3<f64>,
    target: &Isometry3<f64>,
    start: &Vector6<f64>,
    options: &Options,
) -> (Solution, Stop) {
    let mut q = robot.limits().clamp(start);
    let (mut frames, mut e) = weighted_error(robot, point, target, &q);
    let mut lambda = 1e-4;
    let mut iterations = 0;
    let done = |e: &Vector6<f64>| {
        e.fixed_rows::<3>(0).norm() <= options.position_tolerance
            && e.fixed_rows::<3>(3).norm() <= options.rotation_tolerance * ROTATION_WEIGHT
    };
    let mut stop = Stop::IterationLimit;
    while iterations < options.max_iterations.max(1) && !done(&e) {
        iterations += 1;
        let mut j = frames.jacobian(point, Coordinates::Axis);
        j.fixed_rows_mut::<3>(3).scale_mut(ROTATION_WEIGHT);
        let a = j * j.transpose() + Matrix6::identity() * (lambda * lambda);
        let Some(y) = a.cholesky().map(|c| c.solve(&e)) else {
            lambda *= 10.0;
            continue;
        };
        let mut dq = j.tr_mul(&y);
        let largest = dq.amax();
        if largest > 0.5 {
            dq *= 0.5 / largest;
        }
        let q_new = robot.limits().clamp(&(q + dq));
        let (frames_new, e_new) = weighted_error(robot, point, target, &q_new);
        if e_new.norm_squared() < e.norm_squared() {
            (q, frames, e) = (q_new, frames_new, e_new);
            lambda = (lambda * 0.3).max(1e-12);
        } else {
            lambda *= 5.0;
            if lambda > 1e3 {
                stop = Stop::DampingExhausted;
                break;
            }
        }
    }
    if done(&e) {
        stop = Stop::Converged;
    }
    let solution = Solution {
        q,
        iterations,
        position_error: e.fixed_rows::<3>(0).norm(),
        rotation_error: e.fixed_rows::<3>(3).norm() / ROTATION_WEIGHT,
    };
    (solution, stop)
}
