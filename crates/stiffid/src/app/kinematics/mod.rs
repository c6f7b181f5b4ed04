//! The kinematics job: forward kinematics, the geometric Jacobian of a tool point and the
//! dexterity index (Zhang et al. 2021, Eq. 20) of one posture of a robot, with the characteristic
//! length given or derived from the robot ([`crate::setup::prior::robot_characteristic_length`]).

pub mod document;

use crate::robot::kinematics::{Coordinates, Frames};
use crate::{common::limits, dexterity, setup::prior, Result, Robot};
use nalgebra::{Matrix6, Vector3, Vector6};

/// What to compute.
#[derive(Debug, Clone)]
pub struct Request<'a> {
    /// The robot.
    pub robot: &'a Robot,
    /// Axis angles q1..q6, rad, within the robot's limits.
    pub q: Vector6<f64>,
    /// The point of the Jacobian, flange frame, m.
    pub point: Vector3<f64>,
    /// The characteristic length `L` of the dexterity index, m; `None`: derived from the robot.
    pub characteristic_length: Option<f64>,
    /// The joint coordinates of the Jacobian's columns.
    pub coordinates: Coordinates,
}

/// What the kinematics job found.
#[derive(Debug, Clone)]
pub struct Report {
    /// Axis angles, rad.
    pub q: Vector6<f64>,
    /// The point of the Jacobian, flange frame, m.
    pub point: Vector3<f64>,
    /// The joint coordinates of the Jacobian's columns.
    pub coordinates: Coordinates,
    /// The characteristic length used, m.
    pub characteristic_length: f64,
    /// Whether it was derived from the robot (else given).
    pub derived: bool,
    /// The posture's frames, base frame, m.
    pub frames: Frames,
    /// The point's Jacobian, rows `[v; omega]` (m/rad, rad/rad), base frame.
    pub jacobian: Matrix6<f64>,
    /// The dexterity index `k(J_N)` (Eq. 20); `+infinity` at a singularity.
    pub dexterity: f64,
}

/// The characteristic length `L` (m) of the dexterity index at `point` (flange frame, m): the
/// `given` one, checked against [`limits::CHARACTERISTIC_LENGTH_MM`], or without one the robot's
/// own ([`prior::robot_characteristic_length`]).
///
/// # Errors
/// [`crate::Error::InvalidField`] (`characteristic_length_mm`) for a given length out of range;
/// without one, those of [`prior::robot_characteristic_length`].
pub fn characteristic_length_or_derived(
    robot: &Robot,
    point: &Vector3<f64>,
    given: Option<f64>,
) -> Result<f64> {
    match given {
        Some(l) => {
            let range = &limits::CHARACTERISTIC_LENGTH_MM;
            limits::check("characteristic_length_mm", &[l * 1e3], range)?;
            Ok(l)
        }
        None => prior::robot_characteristic_length(robot, point),
    }
}

/// Runs the kinematics job.
///
/// # Errors
/// [`crate::Error::OutsideBox`] (`q_deg[i]`) for an axis angle outside the robot's limits,
/// [`crate::Error::InvalidField`] (`characteristic_length_mm`) for a length outside
/// [`limits::CHARACTERISTIC_LENGTH_MM`], and without a length those of
/// [`prior::robot_characteristic_length`].
pub fn run(request: Request<'_>) -> Result<Report> {
    let Request {
        robot,
        q,
        point,
        characteristic_length,
        coordinates,
    } = request;
    let field = |a: usize| format!("q_deg[{}]", a + 1);
    robot.limits().check(&q, "the robot's limits", field)?;
    let length = characteristic_length_or_derived(robot, &point, characteristic_length)?;
    let frames = robot.frames(&q);
    let jacobian = frames.jacobian(&point, coordinates);
    Ok(Report {
        q,
        point,
        coordinates,
        characteristic_length: length,
        derived: characteristic_length.is_none(),
        dexterity: dexterity(&jacobian, length),
        frames,
        jacobian,
    })
}
