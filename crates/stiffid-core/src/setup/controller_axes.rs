//! The external axes a controller's robot models (`[controller] robot` with its own
//! `[[external_axis]]`) against the setup's: the controller moves the arm on its carriage and the
//! part on its positioner by its own model, so a track that runs another way than the cell's (a
//! degree off, along another axis) would put every Cartesian target of a long travel
//! centimetres away. Compared as the robots are ([`super::controller_robot`]): within what a
//! calibration corrects, [`super::controller_robot::SAME_ROBOT_MM`] and
//! [`super::controller_robot::SAME_FLANGE_DEG`].

use super::controller_robot::{postures, SAME_FLANGE_DEG, SAME_ROBOT_MM};
use crate::robot::ExternalAxes;
use crate::{Error, Result, Robot};
use nalgebra::{Isometry3, Point3, Vector3};

/// Refuses a `[controller] robot` whose external axes move the arm or the part elsewhere than
/// the setup's robot's ([`same_axes`]); `reference` is the setup's `robot` field, `src` the file.
///
/// # Errors
/// [`Error::InvalidField`] (`controller.robot`) naming both robots, the axes' values and the
/// distance and angle.
pub(super) fn check(robot: &Robot, controller: &Robot, reference: &str, src: &str) -> Result<()> {
    same_axes(robot, controller, reference).map_err(|message| Error::InvalidField {
        field: format!("{src}: controller.robot"),
        message,
    })
}

/// Whether the controller's robot moves the arm and the part where the setup's robot does at
/// every station of [`stations`] (the carried flange at the centre of the joint limits, the
/// points of the positioner's axes and half a metre beside them), else why not. Robots without
/// external axes, or whose axes differ in count or role, pass here: the paths that need the
/// controller's axes refuse those (`app::compensate`).
fn same_axes(
    robot: &Robot,
    controller: &Robot,
    reference: &str,
) -> std::result::Result<(), String> {
    let (Some(cell), Some(own)) = (robot.external(), controller.external()) else {
        return Ok(());
    };
    let roles =
        |a: &ExternalAxes| -> Vec<_> { a.axes().iter().map(|x| (x.role, x.kind)).collect() };
    if roles(cell) != roles(own) || cell.is_empty() {
        return Ok(());
    }
    let q = postures(robot)[0];
    let flange = robot.frames(&q).flange.translation.vector;
    let points = probe_points(cell, flange);
    for e in stations(cell) {
        let pose = |a: &ExternalAxes, carried: bool| -> Isometry3<f64> {
            match carried {
                true => a.carrier_pose(&e),
                false => a.positioner_pose(&e),
            }
        };
        for (p, carried) in &points {
            let (a, b) = (pose(cell, *carried), pose(own, *carried));
            let d = ((a * Point3::from(*p)) - (b * Point3::from(*p))).norm() * 1e3;
            let angle = a.rotation.angle_to(&b.rotation).to_degrees();
            if d.is_nan() || d > SAME_ROBOT_MM || angle.is_nan() || angle > SAME_FLANGE_DEG {
                return Err(message(
                    robot,
                    controller,
                    reference,
                    (&e, *carried),
                    (d, angle),
                ));
            }
        }
    }
    Ok(())
}

/// The points compared, each with whether the carrier (`true`) or the positioner moves it: the
/// flange, and each positioner axis's point and that point half a metre off along x, y and z.
fn probe_points(cell: &ExternalAxes, flange: Vector3<f64>) -> Vec<(Vector3<f64>, bool)> {
    let mut points = vec![(flange, true)];
    for axis in &cell.axes()[cell.carrier_len()..] {
        points.push((axis.point, false));
        for k in 0..3 {
            points.push((axis.point + 0.5 * Vector3::ith(k, 1.0), false));
        }
    }
    points
}

/// The external axes' values compared at (SI, the cell's order): every axis at the centre of its
/// travel, then each axis at either end of it with the others at their centres.
fn stations(cell: &ExternalAxes) -> Vec<Vec<f64>> {
    let centre: Vec<f64> = (cell.axes().iter())
        .map(|a| (a.lower + a.upper) / 2.0)
        .collect();
    let mut out = vec![centre.clone()];
    for (k, a) in cell.axes().iter().enumerate() {
        for end in [a.lower, a.upper] {
            let mut e = centre.clone();
            e[k] = end;
            out.push(e);
        }
    }
    out
}

/// The refusal's words: both robots, the station (mm, deg, named by column), what is apart.
fn message(
    robot: &Robot,
    controller: &Robot,
    reference: &str,
    (e, carried): (&[f64], bool),
    (d, angle): (f64, f64),
) -> String {
    let short = crate::common::words::number;
    let cell = robot.external().map(ExternalAxes::axes).unwrap_or_default();
    let at: Vec<String> = (cell.iter().zip(e))
        .map(|(a, v)| format!("{}_{} = {}", a.name, a.unit(), short(a.to_display(*v))))
        .collect();
    let (what, moved) = match carried {
        true => ("the arm on its carriage", "the flange"),
        false => ("the part on its positioner", "the positioner's table"),
    };
    format!(
        "'{}' moves {what} by another model of the cell's external axes than the setup's robot '{reference}' ('{}'): at {} {moved} is {:.1} mm and {:.1} deg apart in the two (more than {SAME_ROBOT_MM} mm or {SAME_FLANGE_DEG} deg, more than a calibration corrects); the controller moves the axes by its own model, so its robot file's [[external_axis]] must be that model of this cell's axes (the setup's tables, or its robot file's)",
        controller.name(),
        robot.name(),
        at.join(", "),
        d,
        angle
    )
}
