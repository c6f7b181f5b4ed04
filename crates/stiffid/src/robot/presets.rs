//! Built-in robot presets, embedded in the library. Each file cites its source.

use super::{file, Robot};
use crate::{builtin, Result};

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
pub fn get(name: &str) -> Result<Robot> {
    file::parse(text(name)?, &format!("preset {name}"))
}
