//! The kinematics job: forward kinematics, the geometric Jacobian of a tool point and the
//! dexterity index (Zhang et al. 2021, Eq. 20) of one posture of a robot, with the characteristic
//! length given or derived from the robot ([`stiffid_core::setup::prior::robot_characteristic_length`]);
//! where the robot gives its masses, the mass matrix, the operational-space inertia of the point
//! and, with a joint stiffness, the natural frequencies and mode shapes
//! ([`stiffid_core::robot::dynamics`]).
//!
//! ## A cell with external axes
//! A robot with external axes ([`stiffid_core::robot::external`]: a track under the arm, a positioner
//! under the part) needs their values `e` ([`Request::external`]; refused without them: a
//! posture of such a cell is `q` and `e`). Positions are then in the cell frame (the robot's
//! world frame when it has no external axes), the arm on its carrier at `e`
//! ([`Robot::frames_at`]). [`Report::external_jacobian`] has one column per external axis, in
//! the cell's order, rows `[v; omega]` like the arm's: the velocity of the tool point relative
//! to the part (cell frame) per unit of the axis (m/m for a carrier axis, m/rad for a
//! positioner axis): a carrier axis's column is `[d; 0]` (its direction, the error motions'
//! slopes left out), a positioner axis's is `[-d x (x - o); -d]` (the part turning under the
//! tool at `x` about the axis's line through `o` along `d`). The tool's velocity over the part
//! is `J q' + J_e e'`, `J` the arm's 6 x 6 Jacobian ([`Report::jacobian`]) and `J_e` this 6 x n
//! matrix. The dexterity index and the dynamics are the arm's alone.

pub mod document;

use nalgebra::{Isometry3, Matrix6, Vector3, Vector6};
use serde::Serialize;
use stiffid_core::common::warning::Warning;
use stiffid_core::robot::dynamics::modes::{self, Modes};
use stiffid_core::robot::dynamics::{operational_inertia, MassModel};
use stiffid_core::robot::external::ExternalAxes;
use stiffid_core::robot::kinematics::{Coordinates, Frames};
use stiffid_core::{common::limits, dexterity, setup::prior, Result, Robot};

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
    /// The external axes' values `e` (SI: m for a linear axis, rad for a rotary one) in the
    /// cell's order ([`ExternalAxes`]), within their travel; empty for a
    /// robot without external axes.
    pub external: Vec<f64>,
    /// The part's frame at `e = 0`, cell frame, m (a setup's `[workpiece]`); `None`: the
    /// positioner's own frame (the identity) when the cell has a positioner, no part frame
    /// otherwise.
    pub workpiece: Option<Isometry3<f64>>,
}

/// What the kinematics job found. It serialises to its document (`stiffid kinematics --json`,
/// Python's `Robot.kinematics(...)`) through the borrowed view [`document::Document`]
/// ([`Report::document`]: mm and degrees, built as it is written).
#[derive(Debug, Clone)]
pub struct Report {
    /// The robot's name.
    pub robot: String,
    /// Where the robot comes from (for a URDF: the file and the tip link used).
    pub robot_source: String,
    /// The robot's external axes (their names, roles and units, for the document), `None`
    /// without.
    pub external_axes: Option<ExternalAxes>,
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
    /// The external axes' values, SI, the cell's order (empty without external axes).
    pub external: Vec<f64>,
    /// The posture's frames, base frame (the cell frame), m.
    pub frames: Frames,
    /// The point's Jacobian, rows `[v; omega]` (m/rad, rad/rad), base frame.
    pub jacobian: Matrix6<f64>,
    /// The point's Jacobian columns of the external axes (module docs), one per axis in the
    /// cell's order, rows `[v; omega]` (m/m or m/rad, 0 or rad/rad), cell frame; empty without
    /// external axes.
    pub external_jacobian: Vec<Vector6<f64>>,
    /// The part's frame at `e` (`P(e) * workpiece`), cell frame, m: with a positioner or a
    /// workpiece given; `None` otherwise.
    pub part: Option<Isometry3<f64>>,
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
/// [`stiffid_core::Error::InvalidField`] (`characteristic_length_mm`) for a given length out of range;
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

impl Serialize for Report {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        self.document().serialize(s)
    }
}

/// The kinematics job's report, which is its document (serialised through
/// [`document::Document`]).
pub(crate) type Outcome = crate::app::Outcome<Report>;

/// Runs the kinematics job.
///
/// # Errors
/// [`stiffid_core::Error::OutsideBox`] (`q_deg[i]`) for an axis angle outside the robot's limits,
/// [`stiffid_core::Error::InvalidField`] (`characteristic_length_mm`) for a length outside
/// [`limits::CHARACTERISTIC_LENGTH_MM`] or `stiffness_nm_per_rad` for a stiffness outside
/// [`limits::STIFFNESS_NM_PER_RAD`], and without a length those of
/// [`prior::robot_characteristic_length`]; for the external axes, those of [`check_external`].
pub fn run(request: &Request<'_>) -> Result<Outcome> {
    Ok(Outcome {
        report: find(request)?,
        document: crate::app::Itself,
    })
}

/// What [`run`] finds, before its document.
fn find(request: &Request<'_>) -> Result<Report> {
    let Request {
        robot,
        q,
        point,
        characteristic_length,
        coordinates,
        stiffness,
        external,
        workpiece,
    } = request;
    let (robot, q, point, coordinates) = (*robot, *q, *point, *coordinates);
    let (characteristic_length, stiffness, workpiece) =
        (*characteristic_length, *stiffness, *workpiece);
    let external = external.clone();
    let field = |a: usize| format!("q_deg[{}]", a + 1);
    robot.limits().check(&q, "the robot's limits", field)?;
    check_external(robot, &external, "external")?;
    if let Some(k) = &stiffness {
        limits::check(
            "stiffness_nm_per_rad",
            k.as_slice(),
            &limits::STIFFNESS_NM_PER_RAD,
        )?;
    }
    let length = characteristic_length_or_derived(robot, &point, characteristic_length)?;
    let frames = robot.frames_at(&q, &external);
    let jacobian = frames.jacobian(&point, coordinates);
    let x = frames.point(&point);
    let external_jacobian = robot
        .external()
        .map_or(Vec::new(), |axes| external_columns(axes, &external, &x));
    let has_positioner = robot.external().is_some_and(|a| a.len() > a.carrier_len());
    let part = (has_positioner || workpiece.is_some()).then(|| {
        let turned = robot
            .external()
            .map_or(Isometry3::identity(), |a| a.positioner_pose(&external));
        turned * workpiece.unwrap_or_default()
    });
    let (masses, warning) = MassModel::optional(robot, None);
    let mass_matrix = masses.map(|m| m.mass_matrix(robot, &frames, coordinates));
    let compliance = stiffness.map(|k| Matrix6::from_diagonal(&k.map(|k| 1.0 / k)));
    let modes = mass_matrix
        .zip(compliance)
        .and_then(|(m, c)| modes::modes(&m, &c));
    let point_directions = modes::point_directions(&jacobian, modes.as_ref());
    Ok(Report {
        robot: robot.name().to_string(),
        robot_source: robot.source().to_string(),
        external_axes: robot.external().cloned(),
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
        external,
        external_jacobian,
        part,
    })
}

/// Whether `e` (SI, the cell's order) are the values of `robot`'s external axes within their
/// travel ([`ExternalAxes::check`]), or empty for a robot without.
///
/// # Errors
/// [`stiffid_core::Error::InvalidField`] (`field`) when the robot has external axes and `e` is empty
/// (the message names the axes and their columns) or of another length, a value outside its
/// travel (naming the axis), or values given for a robot without external axes.
pub fn check_external(robot: &Robot, e: &[f64], field: &str) -> Result<()> {
    robot.check_external(e, field)
}

/// The Jacobian columns of the external axes for the tool point at `x` (cell frame, m): the
/// tool point's velocity relative to the part per unit of each axis (module docs).
pub(crate) fn external_columns(
    axes: &ExternalAxes,
    e: &[f64],
    x: &Vector3<f64>,
) -> Vec<Vector6<f64>> {
    let carrier = axes.carrier_columns(e).into_iter().map(|d| {
        let mut c = Vector6::zeros();
        c.fixed_rows_mut::<3>(0).copy_from(&d);
        c
    });
    let positioner = axes.positioner_lines(e).into_iter().map(|(d, o)| {
        let v = -d.cross(&(x - o));
        Vector6::new(v.x, v.y, v.z, -d.x, -d.y, -d.z)
    });
    carrier.chain(positioner).collect()
}
