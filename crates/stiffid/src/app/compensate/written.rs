//! A compensated G-code program written as a new robot program in the controller's kinematics
//! and frames ([`stiffid_machining::program::generate::compensated`]), each target's bound in a
//! comment ([`generated`]), and the settings it is written with ([`with_setup`]).

use super::certify;
use crate::app::Warning;
use stiffid_core::{Result, Setup};
use stiffid_machining::program::generate::compensated::{robot_program, Generated};
use stiffid_machining::program::generate::{self, Settings};
use stiffid_machining::program::Dialect;

/// A compensated G-code program written as a new robot program in `dialect`
/// ([`robot_program`]), each target's bound at `level` in a comment: the main program (with a
/// KRL program's `.dat`), its sub-programs, the warnings.
///
/// # Errors
/// Those of [`robot_program`].
pub(super) fn generated(
    setup: &Setup,
    dialect: Dialect,
    compensated: &stiffid_machining::Report,
    gcode: &stiffid_machining::gcode::GCode,
    ((name, settings, chord_tolerance), level): ((String, Settings, f64), f64),
) -> Result<(generate::File, Vec<generate::File>, Vec<Warning>)> {
    let how = (name.as_str(), &settings, chord_tolerance);
    let Generated {
        files,
        bounds,
        warnings,
    } = robot_program(setup, dialect, compensated, gcode, how)?;
    let texts: Vec<String> = files.iter().map(|f| f.text.clone()).collect();
    let texts = certify::generated(dialect, &texts, &bounds, level);
    let mut files = (files.into_iter().zip(texts)).map(|(f, text)| generate::File { text, ..f });
    let main = files.next().unwrap_or_else(|| generate::File {
        name,
        text: String::new(),
        data: None,
    });
    Ok((main, files.collect(), warnings))
}

/// `settings` with the setup's rapid speeds (`[controller] rapid_speed_mm_s`,
/// `rapid_joint_pct`), where it gives them.
pub(super) fn with_setup(setup: &Setup, settings: Settings) -> Settings {
    let program = &setup.workcell().controller().program;
    Settings {
        rapid_speed: program.rapid_speed.unwrap_or(settings.rapid_speed),
        rapid_joint_pct: program.rapid_joint_pct.unwrap_or(settings.rapid_joint_pct),
        ..settings
    }
}
