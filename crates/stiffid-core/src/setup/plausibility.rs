//! Plausibility warnings: values that pass every range check but look like a unit slip (a robot
//! file or tool points in metres where millimetres are meant, a URDF scaled down, angles in
//! radians under `_deg` names). Each warning ([`WarningKind::Plausibility`]) names the likely
//! cause; nothing is refused. The command line prints them when it loads a setup or reads postures,
//! Python raises them as `UserWarning`s, and the identify job reports the radians warning of its
//! data (`stiffid::app::identify`).

use super::Setup;
use crate::common::warning::{Warning, WarningKind};
use crate::robot::Bodies;
use crate::Robot;
use nalgebra::Vector6;

/// Below this reach (m) at the middle of the bounds, the robot's lengths look like a unit slip.
pub(crate) const MIN_REACH_M: f64 = 0.1;

/// Above this reach (m), the robot's lengths look like millimetres read as metres.
pub(crate) const MAX_REACH_M: f64 = 20.0;

/// Below this distance (m) from the flange, every tool point looks like metres read as mm.
pub(crate) const MIN_TOOL_M: f64 = 1e-3;

/// The warnings of `setup` (module docs), each one sentence naming the field and the likely
/// cause, and the setup file's notes ([`Setup::notes`]: an old field and what it meant); empty
/// when nothing looks wrong.
pub fn warnings(setup: &Setup) -> Vec<Warning> {
    let mut out: Vec<Warning> = meshes(setup.robot()).into_iter().collect();
    out.extend(setup.notes().iter().cloned());
    let bounds = setup.bounds();
    let frames = setup.robot().frames(&((bounds.lower + bounds.upper) / 2.0));
    let reach = (frames.flange.translation.vector - frames.joints[0].translation.vector)
        .norm()
        .max(frames.flange.translation.vector.norm());
    if reach < MIN_REACH_M {
        out.push(plausibility(format!(
            "robot '{}' reaches only {:.3} mm from its base at the middle of the bounds: a robot TOML in metres (its lengths are mm) or a URDF scaled down?",
            setup.robot().name(),
            reach * 1e3
        )));
    } else if reach > MAX_REACH_M {
        out.push(plausibility(format!(
            "robot '{}' reaches {:.1} m from its base: lengths in mm read as metres (a URDF's lengths are m)?",
            setup.robot().name(),
            reach
        )));
    }
    let tool = setup.tool();
    let farthest = tool
        .measuring_points
        .iter()
        .chain([&tool.loading_point])
        .map(|p| p.norm())
        .fold(0.0, f64::max);
    let measuring = (tool.measuring_points.iter())
        .map(|p| p.norm())
        .fold(0.0, f64::max);
    if farthest < MIN_TOOL_M {
        out.push(plausibility(format!(
            "every tool point (loading_point_mm, measuring_points_mm) lies within {:.4} mm of the flange: given in metres instead of mm?",
            farthest * 1e3
        )));
    } else if measuring < MIN_TOOL_M {
        out.push(plausibility(format!(
            "every measuring point (measuring_points_mm) lies within {:.4} mm of the flange, the loading point {:.1} mm from it: the measuring points given in metres instead of mm?",
            measuring * 1e3,
            tool.loading_point.norm() * 1e3
        )));
    }
    out
}

/// The warning for a URDF robot whose collision meshes were not found ([`Bodies::Missing`]):
/// everything but the cell's body checks goes on ([`Setup::check_bodies`]). `None` otherwise.
pub fn meshes(robot: &Robot) -> Option<Warning> {
    let Bodies::Missing(why) = robot.bodies() else {
        return None;
    };
    Some(Warning::new(
        WarningKind::Meshes,
        format!(
            "{why}: the robot is loaded for kinematics and identification without its collision \
             meshes; the cell's body checks need them (--package-path DIR, Python: package_paths)"
        ),
    ))
}

/// The warning for postures (axis angles, rad, as read from `_deg` columns) whose every angle lies
/// within +-2 pi degrees as read (a turn, in radians): angles in radians under `_deg` names.
/// `None` for fewer than three postures, all-zero postures, or anything else.
pub fn radians_as_degrees<'a>(
    postures: impl IntoIterator<Item = &'a Vector6<f64>>,
) -> Option<Warning> {
    let (mut count, mut largest) = (0usize, 0.0f64);
    for q in postures {
        count += 1;
        largest = largest.max(q.amax());
    }
    let limit = std::f64::consts::TAU.to_radians() * (1.0 + 1e-9);
    (count >= 3 && largest > 0.0 && largest <= limit).then(|| {
        plausibility(format!(
            "every axis angle of the {count} postures lies within +-{:.3} deg: angles in radians under _deg names?",
            largest.to_degrees()
        ))
    })
}

/// The warning for one posture given as an option (`option`, e.g. `--q-deg`; axis angles, rad, as
/// read from degrees) whose every angle lies within +-2 pi degrees as read and one of them is not a
/// whole number of degrees (`-1.571`): radians given as degrees. `None` otherwise (an all-zero
/// posture, or small whole degrees such as `0,5,-5,0,0,0`).
pub fn radians_in_option(option: &str, q: &Vector6<f64>) -> Option<Warning> {
    let deg = q.map(f64::to_degrees);
    let limit = std::f64::consts::TAU * (1.0 + 1e-9);
    let fractional = deg.iter().any(|d| (d - d.round()).abs() > 1e-6);
    (deg.amax() <= limit && fractional).then(|| {
        plausibility(format!(
            "{option}: every axis angle lies within +-{:.3} deg: radians given as degrees?",
            deg.amax()
        ))
    })
}

fn plausibility(message: String) -> Warning {
    Warning::new(WarningKind::Plausibility, message)
}
