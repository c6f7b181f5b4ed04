//! The links' axes of [`super::Gravity::Arm`] and the check that the robot is an
//! anthropomorphic arm (module docs of [`super`]).

use nalgebra::{Vector3, Vector6};
use stiffid_core::{Error, Result, Robot};

/// How far (rad, the sine of the angle) joint 1 may lean from the vertical, joint 2 from the
/// horizontal and joint 3 from joint 2's direction for [`super::Gravity::Arm`]: 0.01 rad, the
/// torques' error then within 1% of the weight's.
pub(crate) const ARM_TOLERANCE: f64 = 0.01;

/// The unit axis of the upper arm (in link 1's frame) and of the forearm (in link 2's), zero for
/// the other links: from joint 2's axis to joint 3's, and from joint 3's axis to the wrist point
/// (on joint 4's axis, nearest joint 5's), each across its joint's axis.
///
/// # Errors
/// [`Error::InvalidField`] (`gravity`) naming the joint when the robot is not an
/// anthropomorphic arm (its module docs).
pub(super) fn axes(robot: &Robot) -> Result<[Vector3<f64>; 6]> {
    let f = robot.frames(&Vector6::zeros());
    let (z, p) = (&f.axis_directions, &f.axis_points);
    let up = Vector3::z();
    let refuse = |what: String| {
        Err(Error::InvalidField {
            field: "gravity".into(),
            message: format!(
                "arm: the robot '{}' is not an anthropomorphic arm ({what}, beyond {ARM_TOLERANCE} rad): its three terms do not hold; use lumped",
                robot.name()
            ),
        })
    };
    if z[0].cross(&up).norm() > ARM_TOLERANCE {
        return refuse("joint 1 is not vertical".into());
    }
    if z[1].dot(&up).abs() > ARM_TOLERANCE {
        return refuse("joint 2 is not horizontal".into());
    }
    if z[1].cross(&z[2]).norm() > ARM_TOLERANCE {
        return refuse("joint 3 is not parallel to joint 2".into());
    }
    let wrist = nearest_on(p[3], z[3], p[4], z[4]);
    let size = (p[2] - p[1]).norm() + (wrist - p[2]).norm();
    let across = |from: Vector3<f64>, axis: Vector3<f64>, to: Vector3<f64>| {
        let d = to - from;
        let d = d - axis * axis.dot(&d);
        (d.norm() > 1e-6 * size.max(1e-3)).then(|| d.normalize())
    };
    let Some(upper) = across(p[1], z[1], p[2]) else {
        return refuse("the upper arm has no length: joint 3's axis meets joint 2's".into());
    };
    let Some(fore) = across(p[2], z[2], wrist) else {
        return refuse("the forearm has no length: the wrist is on joint 3's axis".into());
    };
    let mut axes = [Vector3::zeros(); 6];
    axes[1] = f.joints[1].rotation.inverse() * upper;
    axes[2] = f.joints[2].rotation.inverse() * fore;
    Ok(axes)
}

/// The point of the line `(a, u)` (point, unit direction) nearest the line `(b, v)`; `a` for
/// parallel lines.
fn nearest_on(a: Vector3<f64>, u: Vector3<f64>, b: Vector3<f64>, v: Vector3<f64>) -> Vector3<f64> {
    let w = a - b;
    let (uv, uw, vw) = (u.dot(&v), u.dot(&w), v.dot(&w));
    let den = 1.0 - uv * uv;
    if den < 1e-12 {
        return a;
    }
    a + u * ((uv * vw - uw) / den)
}
