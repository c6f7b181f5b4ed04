//! The kinematics job: forward kinematics, the geometric Jacobian of a tool point and the
//! dexterity index (Zhang et al. 2021, Eq. 20) of one posture of a robot, with the characteristic
//! length given or derived from the robot ([`crate::setup::prior::robot_characteristic_length`]);
//! where the robot gives its masses, the mass matrix, the operational-space inertia of the point
//! and, with a joint stiffness, the natural frequencies and mode shapes
//! ([`crate::robot::dynamics`]).

pub mod document;

use crate::common::warning::Warning;
use crate::robot::dynamics::modes::{self, Modes};
use crate::robot::dynamics::{operational_inertia, MassModel};
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
    /// The joint coordinates of the Jacobian's columns (and of the mass matrix, the stiffness
    /// and the mode shapes).
    pub coordinates: Coordinates,
    /// The six joints' stiffness, Nm/rad, in `coordinates`, each within
    /// [`limits::STIFFNESS_NM_PER_RAD`]: for the natural frequencies; `None`: none computed.
    pub stiffness: Option<Vector6<f64>>,
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
    /// The joint-space mass matrix (kg m^2, in `coordinates`); `None` where the robot gives no
    /// masses or they are placeholders (then a warning).
    pub mass_matrix: Option<Matrix6<f64>>,
    /// The operational-space inertia of the point (rows `[v; omega]`, SI); `None` without
    /// masses or at a singular posture.
    pub operational_inertia: Option<Matrix6<f64>>,
    /// The natural frequencies and mode shapes with the stiffness given; `None` without one or
    /// without masses.
    pub modes: Option<Modes>,
    /// The point's direction of motion in each mode (unit, base frame; zeros without modes).
    pub point_directions: [Vector3<f64>; 6],
    /// What to look at before trusting the report (placeholder masses).
    pub warnings: Vec<Warning>,
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
/// [`limits::CHARACTERISTIC_LENGTH_MM`] or `stiffness_nm_per_rad` for a stiffness outside
/// [`limits::STIFFNESS_NM_PER_RAD`], and without a length those of
/// [`prior::robot_characteristic_length`].
pub fn run(request: Request<'_>) -> Result<Report> {
    let Request {
        robot,
        q,
        point,
        characteristic_length,
        coordinates,
        stiffness,
    } = request;
    let field = |a: usize| format!("q_deg[{}]", a + 1);
    robot.limits().check(&q, "the robot's limits", field)?;
    if let Some(k) = &stiffness {
        limits::check(
            "stiffness_nm_per_rad",
            k.as_slice(),
            &limits::STIFFNESS_NM_PER_RAD,
        )?;
    }
    let length = characteristic_length_or_derived(robot, &point, characteristic_length)?;
    let frames = robot.frames(&q);
    let jacobian = frames.jacobian(&point, coordinates);
    let (masses, warning) = MassModel::optional(robot, None);
    let mass_matrix = masses.map(|m| m.mass_matrix(robot, &frames, coordinates));
    let compliance = stiffness.map(|k| Matrix6::from_diagonal(&k.map(|k| 1.0 / k)));
    let modes = mass_matrix
        .zip(compliance)
        .and_then(|(m, c)| modes::modes(&m, &c));
    let point_directions = modes::point_directions(&jacobian, modes.as_ref());
    Ok(Report {
        operational_inertia: mass_matrix.and_then(|m| operational_inertia(&m, &jacobian)),
        mass_matrix,
        modes,
        point_directions,
        warnings: Vec::from_iter(warning),
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
