//! The robot file a controller runs (`[controller] robot`) must be the setup's robot as the
//! controller knows it: its nominal kinematics, not a calibrated file, and not another robot. A
//! controller of another robot would put every Cartesian target decimetres to metres away; a
//! calibrated file run as the nominal one would move every target by the calibration's
//! correction (millimetres) without a word. One controller has one world: a controller's robot
//! whose world ([`Robot::controller_world`]) is not the setup robot's would leave a program's
//! positions read in one and written in the other.

use crate::{Error, Result, Robot};
use nalgebra::Vector6;

/// How far the controller's flange may be from the setup robot's at the same axis angles and
/// still be the same robot, mm: a calibration moves a robot's flange by a few millimetres
/// (geometric errors of industrial robots: 1 to 5 mm before calibration), another robot model by
/// decimetres.
pub(crate) const SAME_ROBOT_MM: f64 = 20.0;

/// How far the controller's flange frame may turn from the setup robot's at the same axis angles
/// and still be the same flange, deg: a calibration turns a flange by milliradians, another
/// convention of the flange's axes (ROS's x along the tool, a controller's z) by 90 deg.
pub(crate) const SAME_FLANGE_DEG: f64 = 1.0;

/// Refuses a `[controller] robot` that is a calibrated file (with nominal kinematics), or whose
/// flange lies more than [`SAME_ROBOT_MM`] from the setup's robot's at any of 13 postures spread
/// over the setup robot's joint limits (the centre, and each axis at a quarter and three
/// quarters of its range) or whose flange frame turns more than [`SAME_FLANGE_DEG`] from it
/// there (the setup's `[tool]` is in its robot's flange frame, the controller's tool in its
/// own), or whose controller's world lies more than
/// [`super::calibrated::PART_TOLERANCE_M`] or [`super::calibrated::PART_TOLERANCE_RAD`] from the
/// setup robot's. `reference` is the setup's `robot` field, `src` the file name.
///
/// # Errors
/// [`Error::InvalidField`] (`controller.robot`) naming both robots, and for another robot the
/// posture and the distance (or the angle), for another world both worlds and how far apart
/// they are.
pub(super) fn check(robot: &Robot, controller: &Robot, reference: &str, src: &str) -> Result<()> {
    let fail = |message: String| Error::InvalidField {
        field: format!("{src}: controller.robot"),
        message,
    };
    if controller.is_calibrated() {
        return Err(fail(format!("'{}' is a calibrated robot file, and kinematics = \"nominal\" says the controller runs its nominal robot: name the robot file or preset the controller runs, or say kinematics = \"calibrated\" for a controller loaded with the calibrated model", controller.name())));
    }
    let postures = postures(robot);
    let far = postures.iter().find_map(|q| {
        let d = flange_distance_mm(robot, controller, q);
        (d.is_nan() || d > SAME_ROBOT_MM).then_some((q, d))
    });
    let degrees = |q: &Vector6<f64>| {
        let q: Vec<String> = q.iter().map(|a| format!("{:.1}", a.to_degrees())).collect();
        q.join(", ")
    };
    if let Some((q, angle)) = postures.iter().find_map(|q| {
        let a = flange_angle_deg(robot, controller, q);
        (far.is_none() && (a.is_nan() || a > SAME_FLANGE_DEG)).then_some((q, a))
    }) {
        return Err(fail(format!(
            "'{}' is the setup's robot '{reference}' ('{}') with another flange frame: at the axis angles [{}] deg their flanges are turned {} deg apart (more than {SAME_FLANGE_DEG} deg, more than any calibration turns a flange), and the setup's [tool] is in its robot's flange frame while the controller's tool is in its own; name a robot file whose flange frame is the controller's (a URDF: the tip link of the controller's flange, robot_tip; a robot file: its [flange])",
            controller.name(),
            robot.name(),
            degrees(q),
            crate::common::words::number(angle),
        )));
    }
    match far {
        None => same_world(robot, controller, reference).map_err(fail),
        Some((q, d)) => Err(fail(format!(
            "'{}' is not the setup's robot '{reference}' ('{}'): at the axis angles [{}] deg their flanges are {} mm apart (more than {SAME_ROBOT_MM} mm, more than any calibration moves a robot); name the robot file the controller of this robot runs",
            controller.name(),
            robot.name(),
            degrees(q),
            crate::common::words::number(d),
        ))),
    }
}

/// The 13 postures the robots are compared at: the centre of `robot`'s joint limits, and each
/// axis at a quarter and three quarters of its range.
pub(super) fn postures(robot: &Robot) -> Vec<Vector6<f64>> {
    let (lower, upper) = (robot.limits().lower, robot.limits().upper);
    let centre = (lower + upper) / 2.0;
    let mut postures = vec![centre];
    for k in 0..6 {
        for f in [0.25, 0.75] {
            let mut q = centre;
            q[k] = lower[k] + f * (upper[k] - lower[k]);
            postures.push(q);
        }
    }
    postures
}

/// The distance between the two robots' flanges at axis angles `q` (rad), mm.
fn flange_distance_mm(a: &Robot, b: &Robot, q: &Vector6<f64>) -> f64 {
    let (fa, fb) = (a.frames(q).flange, b.frames(q).flange);
    (fa.translation.vector - fb.translation.vector).norm() * 1e3
}

/// The angle between the two robots' flange frames at axis angles `q` (rad), deg.
fn flange_angle_deg(a: &Robot, b: &Robot, q: &Vector6<f64>) -> f64 {
    let (fa, fb) = (a.frames(q).flange, b.frames(q).flange);
    fa.rotation.angle_to(&fb.rotation).to_degrees()
}

/// Whether the controller's robot places the controller's world where the setup's robot does
/// (within [`super::calibrated::PART_TOLERANCE_M`] and [`super::calibrated::PART_TOLERANCE_RAD`]),
/// else why not: the program's positions are stated in that world, and a world taken from one
/// file while the controller runs the other moves every position by the difference.
fn same_world(
    robot: &Robot,
    controller: &Robot,
    reference: &str,
) -> std::result::Result<(), String> {
    let (a, b) = (robot.controller_world(), controller.controller_world());
    let origin = (a.translation.vector - b.translation.vector).norm();
    let angle = a.rotation.angle_to(&b.rotation);
    use super::calibrated::{words, PART_TOLERANCE_M, PART_TOLERANCE_RAD};
    if origin <= PART_TOLERANCE_M && angle <= PART_TOLERANCE_RAD {
        return Ok(());
    }
    let short = crate::common::words::number;
    Err(format!(
        "'{}' places the controller's world (where a program's positions are) at {} in its base frame, the setup's robot '{reference}' ('{}') at {}: {} mm and {} deg apart, and one controller has one world; give both robot files the controller's world ([controller_world]; a URDF: its ROS-Industrial base link)",
        controller.name(),
        words(b),
        robot.name(),
        words(a),
        short(origin * 1e3),
        short(angle.to_degrees())
    ))
}
