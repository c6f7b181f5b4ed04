//! `stiffid robots`: the built-in robot presets.

use crate::output;
use anyhow::Result;
use stiffid::internal::robot::presets;

/// Prints every preset: name, robot, source.
pub fn run() -> Result<()> {
    let mut text = String::new();
    for name in presets::names() {
        let robot = presets::get(name)?;
        text += &format!("{name}\n  {}\n  source: {}\n", robot.name(), robot.source());
    }
    output::print(&text)
}
