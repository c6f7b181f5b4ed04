//! `stiffid robots`: the built-in robot presets.

use anyhow::Result;
use stiffid::robot::presets;

/// Prints every preset: name, robot, source.
pub fn run() -> Result<()> {
    for name in presets::names() {
        let robot = presets::get(name)?;
        println!("{name}\n  {}\n  source: {}", robot.name, robot.source);
    }
    Ok(())
}
