//! What a compensated program may be written as: the output language a program takes, and
//! a lean G-code cannot carry.

use crate::machining::compensate::Options;
use crate::machining::Language;
#[cfg(doc)]
use crate::JobOption;
use crate::{Error, Result};

/// Refuses an output language a program cannot be written in: a robot program stays in its own.
pub(super) fn check_output(language: Language, output: Language) -> Result<()> {
    match (language, output) {
        (a, b) if a == b => Ok(()),
        (Language::GCode, Language::Robot(_)) => Ok(()),
        _ => Err(Error::InvalidField {
            field: "out".into(),
            message: format!(
                "a program in {} is written back in its own language, not as {}",
                language.name(),
                output.name()
            ),
        }),
    }
}

/// Refuses a free lead and tilt for a program written as G-code: its blocks carry positions
/// only, so the leaned postures would be lost.
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::FreeLeadTilt`]).
pub(super) fn check_lean(options: &Options, output: Language) -> Result<()> {
    match (options.free_lead_tilt, output) {
        (Some(_), Language::GCode) => Err(Error::InvalidOption {
            option: crate::JobOption::FreeLeadTilt,
            message: "a program written as G-code carries the tool's positions only (a 3-axis program has no words for its axis), so the leaned postures would be lost: write it as a robot program (--out X.ls, .src or .mod; Python output=), whose targets carry them".into(),
        }),
        _ => Ok(()),
    }
}
