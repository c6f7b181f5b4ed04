//! Joint targets taught on the robot or computed by a controller's inverse kinematics
//! (`[controller] joint_targets`, [`JointTargets`]).
//!
//! A joint target taught on this robot (jogged to and recorded) is a posture of the real robot:
//! the pose is wherever that robot went, and compensating it corrects the deflection only. A
//! joint target computed by a controller's inverse kinematics (an offline program, a CAM post,
//! Cartesian targets converted to joint ones) holds the controller's geometry: the pose meant is
//! the controller's forward kinematics of the angles, and the setup's robot (a calibrated one)
//! is solved for it as a Cartesian target is ([`super::resolve`]): the compensation then corrects
//! the geometry and the deflection. Where the two robots put the tool at the same angles within
//! 1 micrometre and 1 microradian (an uncalibrated robot, a controller running the
//! calibrated model), both readings are one and the setup need not say; elsewhere a program of
//! joint targets is refused until it does.
//!
//! On a cell with external axes the pose meant is the tool's over the part: the controller's
//! track (or the cell's, where the controller's robot has none) carries the arm, the positioner
//! turns the part, and the setup's robot is solved at the same external values.

use super::same;
use crate::program::{at, external, JointProgram};
use nalgebra::{Isometry3, Vector6};
use stiffid_core::robot::configuration::Configuration;
use stiffid_core::robot::ik::{self, tool_pose, TargetFrame};
use stiffid_core::robot::ExternalAxes;
use stiffid_core::setup::{JointTargets, Kinematics};
use stiffid_core::{Error, Result, Robot, Setup};

/// The program with its joint targets as `setup` says they were made (module docs): `None`
/// where nothing changes (no joint target, taught ones, or a controller whose robot puts the
/// tool where the setup's does); else each joint target's axis angles those of the setup's robot
/// at the controller's pose of them, from them, with `options` (no random restarts).
///
/// # Errors
/// [`Error::InvalidField`] (`controller.joint_targets`) for joint targets the two robots place
/// apart when the setup does not say which they are (naming the line, the distance and both
/// choices); those of [`Setup::controller_robot`] for computed ones without the controller's
/// robot; those of [`external::cell_values`]; [`Error::Program`] naming the line of a pose the
/// setup's robot does not reach in the controller's configuration.
pub(crate) fn joint_targets(
    program: &JointProgram,
    setup: &Setup,
    options: &ik::Options,
) -> Result<Option<JointProgram>> {
    let joint: Vec<usize> = (program.targets.iter().enumerate())
        .filter(|(_, t)| t.cartesian.is_none() && !t.is_held())
        .map(|(i, _)| i)
        .collect();
    let c = setup.workcell().controller();
    let (Some(&first), Kinematics::Nominal) = (joint.first(), c.kinematics) else {
        return Ok(None);
    };
    if c.joint_targets == Some(JointTargets::Taught) {
        return Ok(None);
    }
    let line = program.targets[first].line;
    let (truth, nominal) = match (setup.controller_robot(), c.joint_targets) {
        (Ok(r), _) => (setup.robot(), r),
        (Err(e), Some(_)) => return Err(e),
        (Err(_), None) => return Err(unstated(line, None)),
    };
    if std::ptr::eq(truth, nominal) {
        return Ok(None);
    }
    let e = external::cell_values(program, truth.external())?;
    let tcp = setup.tool().tcp;
    let cell = axes_of(truth);
    let on = (nominal, axes_of(nominal).or(cell));
    let mut out = program.clone();
    // The target the two robots place furthest apart: the distance, m, and its line.
    let mut apart: Option<(f64, u64)> = None;
    for i in joint {
        let t = &mut out.targets[i];
        let q = Vector6::from(t.q_deg).map(f64::to_radians);
        let meant = over_part(on, &tcp, &q, &e[i]);
        let here = over_part((truth, cell), &tcp, &q, &e[i]);
        let d = (meant.translation.vector - here.translation.vector).norm();
        if !same(&meant, &here) && apart.is_none_or(|(worst, _)| d > worst) {
            apart = Some((d, t.line));
        }
        if c.joint_targets == Some(JointTargets::Computed) {
            let s = solved(truth, nominal, (&tcp, &meant), (&q, &e[i]), options);
            t.q_deg = s
                .map_err(|why| at(t.line, why))?
                .map(f64::to_degrees)
                .into();
        }
    }
    match (apart, c.joint_targets) {
        (None, _) => Ok(None),
        (Some((d, line)), None) => Err(unstated(line, Some(d))),
        (Some(_), Some(_)) => Ok(Some(out.with_read_kept(program))),
    }
}

/// The external axes of `robot`, if it has any.
fn axes_of(robot: &Robot) -> Option<&ExternalAxes> {
    robot.external().filter(|a| !a.is_empty())
}

/// The tool's pose (the flange's axes at `tcp`) over the part at axis angles `q` and external
/// values `e` (SI): the arm on the carrier of `axes`, the part turned by its positioner.
fn over_part(
    (robot, axes): (&Robot, Option<&ExternalAxes>),
    tcp: &nalgebra::Vector3<f64>,
    q: &Vector6<f64>,
    e: &[f64],
) -> Isometry3<f64> {
    let (carrier, positioner) = match axes {
        Some(a) => (a.carrier_pose(e), a.positioner_pose(e)),
        None => (Isometry3::identity(), Isometry3::identity()),
    };
    positioner.inverse() * carrier * tool_pose(&robot.frames(q), tcp)
}

/// The setup's robot's posture that puts the tool on `meant` (over the part) at external values
/// `e`, from the controller's posture `q`, in its configuration.
fn solved(
    truth: &Robot,
    nominal: &Robot,
    (tcp, meant): (&nalgebra::Vector3<f64>, &Isometry3<f64>),
    (q, e): (&Vector6<f64>, &[f64]),
    options: &ik::Options,
) -> std::result::Result<Vector6<f64>, String> {
    let one = ik::Options {
        restarts: 0,
        ..*options
    };
    let part = TargetFrame::Part(Isometry3::identity());
    let s = ik::solve_at(truth, tcp, meant, part, e, q, &one).map_err(|e| {
        format!("a joint target computed by the controller's inverse kinematics ([controller] joint_targets = \"computed\"): the setup's robot does not reach the controller's pose of it near its axis angles: {e}")
    })?;
    match Configuration::of(truth, &s.q).change_from(&Configuration::of(nominal, q)) {
        Some(change) => Err(format!("a joint target computed by the controller's inverse kinematics: the setup's robot reaches the controller's pose of it only in another configuration ({change})")),
        None => Ok(s.q),
    }
}

/// The refusal of joint targets whose reading the setup does not state, `line` the target the
/// two robots place furthest apart (`apart`, m; `None`: the controller's robot is not given).
fn unstated(line: u64, apart: Option<f64>) -> Error {
    let why = match apart {
        Some(d) => format!("at the same axis angles the controller's robot puts the tool {:.3} mm from where the setup's robot does (line {line})", d * 1e3),
        None => format!("the setup's robot is a calibrated one, whose geometry is not the controller's (line {line} is a joint target)"),
    };
    Error::InvalidField {
        field: "controller.joint_targets".into(),
        message: format!("missing: {why}, so the program's joint targets mean two different poses: say joint_targets = \"taught\" for targets taught on this robot (the pose is wherever it went: the deflection alone is corrected), or joint_targets = \"computed\" for targets computed by the controller's inverse kinematics with its nominal geometry (the pose is its forward kinematics of them: the geometry is corrected too; name the robot file it runs in [controller] robot)"),
    }
}
