//! Built-in robot presets, embedded in the library. Each file cites its source.

use super::{file, Robot};
use crate::{robot::builtin, Result};

/// `(name, robot TOML)` of every preset.
const PRESETS: &builtin::Table = &[
    (
        "comau-smart5-nj165-3.0",
        include_str!("../../presets/comau-smart5-nj165-3.0.toml"),
    ),
    (
        "fanuc-r2000ic-165f",
        include_str!("../../presets/fanuc-r2000ic-165f.toml"),
    ),
    (
        "kuka-kr210-robond",
        include_str!("../../presets/kuka-kr210-robond.toml"),
    ),
];

/// The preset names, in listing order.
pub fn names() -> impl Iterator<Item = &'static str> {
    builtin::names(PRESETS)
}

/// The robot TOML text of a preset.
///
/// # Errors
/// [`Error::Unknown`](crate::Error::Unknown) if no preset has this name.
pub fn text(name: &str) -> Result<&'static str> {
    builtin::text(PRESETS, "robot preset", name)
}

/// The robot of a preset.
///
/// # Errors
/// [`Error::Unknown`](crate::Error::Unknown) if no preset has this name.
///
/// # Examples
/// Forward kinematics and the Jacobian of the flange origin at a posture (axis angles, rad):
/// ```
/// use nalgebra::{Vector3, Vector6};
/// use stiffid_core::{robot::presets, Coordinates};
/// let robot = presets::get("comau-smart5-nj165-3.0")?;
/// let q = Vector6::new(0.0, 0.0, -90.0, 0.0, 30.0, 0.0).map(f64::to_radians);
/// assert!(robot.limits().contains(&q));
/// let frames = robot.frames(&q); // base frame, m
/// let j = frames.jacobian(&Vector3::zeros(), Coordinates::Axis); // rows [v; omega]
/// assert_eq!(j.shape(), (6, 6));
/// assert!(frames.flange.translation.vector.norm() > 1.0);
/// # Ok::<(), stiffid_core::Error>(())
/// ```
pub fn get(name: &str) -> Result<Robot> {
    file::parse(text(name)?, &format!("preset {name}"))
}
