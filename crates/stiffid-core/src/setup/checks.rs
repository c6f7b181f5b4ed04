//! The checks a setup's builder runs before it builds ([`super::SetupBuilder::build`]): every
//! field within its documented range, the tool, the load and its steps, the noise, the bounds and
//! test postures within the robot's limits.

use super::{invalid, Noise, RopeLoad};
use crate::common::limits::{self, JointBox};
use crate::common::words::distinct;
use crate::{Result, Robot};
use nalgebra::{Vector3, Vector6};

/// The model's frame deviations (m, rad) and the masses' relative deviation within their limits.
pub(super) fn check_accuracy(frame_sd: (f64, f64), mass_sd: f64) -> Result<()> {
    let (p, o) = frame_sd;
    limits::check("robot_accuracy.frame_sd_mm", &[p * 1e3], &limits::FRAME_SD)?;
    limits::check(
        "robot_accuracy.frame_sd_mrad",
        &[o * 1e3],
        &limits::FRAME_SD,
    )?;
    limits::check("masses.sd_pct", &[mass_sd * 1e2], &limits::MASS_SD_PERCENT)?;
    Ok(())
}

/// The characteristic length (m) and the nominal stiffness (Nm/rad) within their limits.
pub(super) fn check_scales(
    characteristic_length: Option<f64>,
    nominal_stiffness: Option<&Vector6<f64>>,
) -> Result<()> {
    if let Some(l) = characteristic_length {
        check_scaled(
            "characteristic_length_mm",
            &[l],
            1e3,
            &limits::CHARACTERISTIC_LENGTH_MM,
        )?;
    }
    if let Some(k) = nominal_stiffness {
        limits::check(
            "nominal_stiffness_nm_per_rad",
            k.as_slice(),
            &limits::STIFFNESS_NM_PER_RAD,
        )?;
    }
    Ok(())
}

pub(super) fn required<T>(value: Option<T>, field: &str) -> Result<T> {
    value.ok_or_else(|| invalid(field, "expected a value: the setup has none"))
}

/// [`limits::check`] of SI `values` against a `range` in the file's unit (`scale` per SI unit),
/// the values shown in that unit.
pub(super) fn check_scaled(
    field: &str,
    values: &[f64],
    scale: f64,
    range: &limits::Range,
) -> Result<()> {
    let scaled: Vec<f64> = values.iter().map(|v| v * scale).collect();
    limits::check(field, &scaled, range)
}

pub(super) fn check_points(field: &str, points: &[Vector3<f64>]) -> Result<()> {
    let values: Vec<f64> = points.iter().flat_map(|p| p.iter().copied()).collect();
    check_scaled(field, &values, 1e3, &limits::LENGTH_MM)
}

/// Refuses reflectors fixed in the cell (on the positioner's table, or on a fixed part)
/// beyond `limits::MAX_TABLE_REFLECTORS` or [`limits::LENGTH_MM`], or without a workpiece
/// frame.
pub(super) fn check_table_reflectors(reflectors: &[Vector3<f64>], workpiece: bool) -> Result<()> {
    let field = "workpiece.reflectors_mm";
    if reflectors.is_empty() {
        return Ok(());
    }
    limits::check_count(field, reflectors.len(), 0, limits::MAX_TABLE_REFLECTORS)?;
    check_points(field, reflectors)?;
    match workpiece {
        true => Ok(()),
        false => Err(crate::Error::InvalidField {
            field: field.into(),
            message: "reflectors on the part (or the positioner's table) are given in the part's frame: give [workpiece] base_from_part".into(),
        }),
    }
}

pub(super) fn check_tool(
    loading_point: &Vector3<f64>,
    measuring_points: &[Vector3<f64>],
    tcp: Option<Vector3<f64>>,
) -> Result<()> {
    check_points("tool.loading_point_mm", std::slice::from_ref(loading_point))?;
    let n = measuring_points.len();
    limits::check_count(
        "tool.measuring_points_mm",
        n,
        1,
        limits::MAX_MEASURING_POINTS,
    )?;
    check_points("tool.measuring_points_mm", measuring_points)?;
    check_points("tool.tcp_mm", tcp.as_slice())
}

/// The closest a positioner axis's line may pass to the tool's TCP with the arm at zero, m.
pub(crate) const POSITIONER_CLEARANCE: f64 = 1e-3;

/// Refuses a positioner axis whose line passes through the tool's TCP (`tcp`, flange frame, m)
/// within [`POSITIONER_CLEARANCE`], with the arm at zero axis angles and the carrier at the
/// middle of its travel: an axis through the tool turns the tool, not the part (the URDF's
/// positioner hanging from the arm's chain is refused the same way).
pub(super) fn check_positioner(robot: &Robot, tcp: &Vector3<f64>) -> Result<()> {
    let Some(axes) = robot.external() else {
        return Ok(());
    };
    let e = axes.stations(1)[0];
    let at = robot.frames_at(&Vector6::zeros(), e.as_slice()).point(tcp);
    for a in axes.axes().iter().skip(axes.carrier_len()) {
        let lever = at - a.point;
        let distance = (lever - a.direction.into_inner() * lever.dot(&a.direction)).norm();
        if distance < POSITIONER_CLEARANCE {
            return Err(invalid(
                &format!("external_axis ({})", a.name),
                format!(
                    "the positioner axis passes through the tool's TCP ({:.3} mm from it with the arm at zero and the carrier at the middle of its travel): a positioner turns the part, not the tool; give a point_mm on the positioner's own axis, away from the tool",
                    distance * 1e3
                ),
            ));
        }
    }
    Ok(())
}

pub(super) fn check_load(load: &RopeLoad) -> Result<()> {
    limits::check("loading.load_n", &[load.load], &limits::LOAD_N)?;
    check_points("loading.anchor_mm", std::slice::from_ref(&load.anchor))
}

pub(super) fn check_load_steps(steps: &[f64]) -> Result<()> {
    let field = "loading.steps_n";
    limits::check_count(field, steps.len(), 0, crate::setup::load_steps::MAX_STEPS)?;
    limits::check(field, steps, &limits::LOAD_N)?;
    match steps.windows(2).position(|w| w[1] <= w[0]) {
        Some(i) => Err(invalid(
            &format!("{field}[{}]", i + 2),
            format!(
                "{} after {}: expected rising load levels",
                steps[i + 1],
                steps[i]
            ),
        )),
        None => Ok(()),
    }
}

pub(super) fn check_noise(noise: &Noise) -> Result<()> {
    check_scaled(
        "noise.reading_sd_mm",
        &[noise.reading_variance.sqrt()],
        1e3,
        &limits::READING_SD_MM,
    )?;
    let levels = &noise.levels;
    limits::check_count("noise.level_multiples", levels.len(), 1, limits::MAX_LEVELS)?;
    limits::check("noise.level_multiples", levels, &limits::LEVEL_MULTIPLE)
}

pub(super) fn degrees(q: &Vector6<f64>) -> Vec<f64> {
    q.iter().map(|v| v.to_degrees()).collect()
}

/// Bounds may leave the robot's limits by this, rad: the rounding of degrees to radians.
pub(super) const BOUNDS_TOLERANCE: f64 = 1e-12;

pub(super) fn check_bounds(bounds: &JointBox, robot: &Robot) -> Result<()> {
    let sides = [("lower_deg", &bounds.lower), ("upper_deg", &bounds.upper)];
    for (side, q) in sides {
        limits::check(&format!("bounds.{side}"), &degrees(q), &limits::ANGLE_DEG)?;
    }
    if let Some(i) = (0..6).find(|&i| bounds.lower[i] >= bounds.upper[i]) {
        let (l, u) = (bounds.lower[i].to_degrees(), bounds.upper[i].to_degrees());
        return Err(invalid(
            &format!("bounds.lower_deg[{}]", i + 1),
            format!(
                "{} deg is not below bounds.upper_deg[{}] = {u:.2} deg",
                distinct(l, u, u),
                i + 1
            ),
        ));
    }
    let within = robot.limits().widened(BOUNDS_TOLERANCE);
    for (side, q) in sides {
        within.check(q, "the robot's limits", |a| {
            format!("bounds.{side}[{}]", a + 1)
        })?;
    }
    Ok(())
}

pub(super) fn check_test_postures(postures: &[Vector6<f64>], robot: &Robot) -> Result<()> {
    let n = postures.len();
    limits::check_count("test.postures_deg", n, 0, limits::MAX_TEST_POSTURES)?;
    for (i, q) in postures.iter().enumerate() {
        let field = format!("test.postures_deg[{}]", i + 1);
        limits::check(&field, &degrees(q), &limits::ANGLE_DEG)?;
        let axis = |a: usize| format!("{field}[{}]", a + 1);
        robot.limits().check(q, "the robot's limits", axis)?;
    }
    Ok(())
}
