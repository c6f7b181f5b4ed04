//! What a setup pointing at a calibrated robot file may not repeat of it: the mount the
//! calibration fitted, its external axes, a controller of another robot.

use crate::common::warning::{Warning, WarningKind};
use crate::robot::file::TransformFile;
use crate::{Error, Result, Robot};
use nalgebra::Isometry3;

/// What a setup pointing at a calibrated robot repeats of it: `[robot_base]` (the calibration
/// fitted the mount into the file's `[base]`: refused where the file records the mount it was
/// calibrated on, `[mount]`, which then places the controller's world; for a file without
/// `[mount]` a note, the mount not applied again, the field still the controller's world) and
/// `[[external_axis]]` tables beside the file's calibrated ones (refused).
///
/// # Errors
/// [`Error::InvalidField`] (`robot_base`, `external_axis`) naming both places.
pub(super) fn mount(
    robot: &Robot,
    reference: &str,
    (robot_base, tables): (Option<TransformFile>, bool),
    src: &str,
) -> Result<Option<Warning>> {
    if !robot.is_calibrated() {
        return Ok(None);
    }
    if let (Some(t), Some(m)) = (&robot_base, robot.mount()) {
        let short = crate::common::words::number;
        let words = |m: &Isometry3<f64>| {
            let p = m.translation.vector * 1e3;
            let [r, pi, y] = crate::robot::file::rpy(&m.rotation);
            format!(
                "xyz_mm = [{}, {}, {}], rpy_deg = [{}, {}, {}]",
                short(p.x),
                short(p.y),
                short(p.z),
                short(r.to_degrees()),
                short(pi.to_degrees()),
                short(y.to_degrees())
            )
        };
        return Err(Error::InvalidField {
            field: format!("{src}: robot_base"),
            message: format!(
                "{}: the calibrated robot file '{}' records the mount it was calibrated on ([mount] {}), which its [base] holds: the setup's [robot_base] would mount the robot again; leave [robot_base] out (the file's [mount] places the controller's world), or calibrate the robot on its new mount",
                words(&t.isometry()),
                reference,
                words(m)
            ),
        });
    }
    if let (true, Some(axes)) = (tables, robot.external()) {
        let names: Vec<&str> = axes.axes().iter().map(|a| a.name.as_str()).collect();
        return Err(Error::InvalidField {
            field: format!("{src}: external_axis"),
            message: format!(
                "the calibrated robot file '{}' holds the calibrated external axes ({}): the setup's [[external_axis]] tables would replace them; leave them out of the setup",
                reference,
                names.join(", ")
            ),
        });
    }
    Ok(robot_base.is_some().then(|| {
        Warning::new(
            WarningKind::Calibrated,
            format!(
                "{src}: [robot_base] with the calibrated robot file '{}': its [base] holds the mount the calibration fitted, so [robot_base] is not applied to it again (it still places the controller's world frame)",
                reference
            ),
        )
    }))
}

/// Refuses `[controller] robot` naming another robot than the calibrated `robot` was
/// calibrated from (its name without [`crate::robot::CALIBRATED`]).
///
/// # Errors
/// [`Error::InvalidField`] (`controller.robot`) naming both robots.
pub(super) fn same_robot(
    robot: &Robot,
    controller: Option<&Robot>,
    reference: &str,
    src: &str,
) -> Result<()> {
    let Some(c) = controller.filter(|_| robot.is_calibrated()) else {
        return Ok(());
    };
    let calibrated = robot.name().trim_end_matches(crate::robot::CALIBRATED);
    match c.name().trim_end_matches(crate::robot::CALIBRATED) == calibrated {
        true => Ok(()),
        false => Err(Error::InvalidField {
            field: format!("{src}: controller.robot"),
            message: format!(
                "'{}' where the setup's robot '{reference}' is '{}' calibrated: the controller runs the nominal robot of the one calibrated",
                c.name(),
                calibrated
            ),
        }),
    }
}
