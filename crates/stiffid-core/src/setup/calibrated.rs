//! What a setup pointing at a calibrated robot file may not repeat of it: the mount the
//! calibration fitted, its external axes, the part's frame it located, a controller of another
//! robot.

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

/// The part's frame of a setup pointing at `robot` (`base_from_part`, the setup's
/// `[workpiece] base_from_part`, m): the calibrated robot's located part ([`Robot::part`]) when
/// the setup gives none (with a note), the setup's when the robot records none or the two agree
/// within [`PART_TOLERANCE_M`] and [`PART_TOLERANCE_RAD`].
///
/// # Errors
/// [`Error::InvalidField`] (`workpiece.base_from_part`) naming both places and how far apart
/// they are (mm, deg).
pub(super) fn part(
    robot: &Robot,
    reference: &str,
    base_from_part: Option<Isometry3<f64>>,
    src: &str,
) -> Result<(Option<Isometry3<f64>>, Option<Warning>)> {
    let Some(located) = robot.part() else {
        return Ok((base_from_part, None));
    };
    let Some(given) = base_from_part else {
        let note = Warning::new(
            WarningKind::Calibrated,
            format!(
                "{src}: the part's frame is the one the calibration located from the reflectors on the table or the part ([part] of the calibrated robot file '{reference}': {})",
                words(located)
            ),
        );
        return Ok((Some(*located), Some(note)));
    };
    let (origin, angle) = (
        (located.translation.vector - given.translation.vector).norm(),
        given.rotation.angle_to(&located.rotation),
    );
    if origin <= PART_TOLERANCE_M && angle <= PART_TOLERANCE_RAD {
        return Ok((Some(given), None));
    }
    let short = crate::common::words::number;
    Err(Error::InvalidField {
        field: format!("{src}: workpiece.base_from_part"),
        message: format!(
            "{}: the calibrated robot file '{reference}' records the part's frame the calibration located from the reflectors on the table or the part ([part] {}), its origin {} mm away and turned {} deg: leave base_from_part out (the file's [part] places the part), or, if the part moved since, locate it again (calibrate --update with the reflectors' readings)",
            words(&given),
            words(located),
            short(origin * 1e3),
            short(angle.to_degrees())
        ),
    })
}

/// How far a setup's `[workpiece] base_from_part` may lie from the calibrated robot file's
/// `[part]` and still repeat it: 1 µm (the file's numbers are written to far better).
pub(super) const PART_TOLERANCE_M: f64 = 1e-6;

/// How far a setup's `[workpiece] base_from_part` may turn from the calibrated robot file's
/// `[part]` and still repeat it: 1 µrad.
pub(super) const PART_TOLERANCE_RAD: f64 = 1e-6;

/// A frame as a setup or robot file writes it (`xyz_mm = [..], rpy_deg = [..]`), short numbers
/// (no negative zero).
pub(super) fn words(m: &Isometry3<f64>) -> String {
    let short = |v: f64| crate::common::words::number(v + 0.0);
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
}
