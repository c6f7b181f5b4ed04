//! What a compensated program may be written as: the output language a program takes, and
//! a lean, a tool axis' rotation or runs' configurations G-code cannot carry.

use super::configurations::name;
#[cfg(doc)]
use stiffid_core::JobOption;
use stiffid_core::{Error, Result};
use stiffid_machining::compensate::{Configurations, Options, Run};
use stiffid_machining::program::generate::Settings;
use stiffid_machining::Language;

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

/// Refuses the settings of a generated robot program where none is generated: the targets, the
/// moves per file and the largest TCP speed for a robot program written back (it keeps its own
/// targets and speeds, in one file), these and the name length for a program written as G-code.
/// A setting at its default changes nothing and passes.
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::Targets`], [`JobOption::MovesPerFile`],
/// [`JobOption::MaxTcpSpeedMmS`], [`JobOption::NameLength`]).
pub(super) fn check_settings(
    language: Language,
    output: Language,
    settings: &Settings,
) -> Result<()> {
    let default = Settings::default();
    let given = [
        (
            settings.targets != default.targets,
            stiffid_core::JobOption::Targets,
        ),
        (
            settings.moves_per_file != default.moves_per_file,
            stiffid_core::JobOption::MovesPerFile,
        ),
        (
            settings.max_tcp_speed != default.max_tcp_speed,
            stiffid_core::JobOption::MaxTcpSpeedMmS,
        ),
        (
            settings.name_length.is_some(),
            stiffid_core::JobOption::NameLength,
        ),
    ];
    use stiffid_core::JobOption::{MaxTcpSpeedMmS, MovesPerFile, NameLength, Targets};
    let (unused, why): (&[stiffid_core::JobOption], _) = match (language, output) {
        (Language::GCode, Language::Robot(_)) => return Ok(()),
        (Language::Robot(_), _) => (
            &[Targets, MovesPerFile, MaxTcpSpeedMmS],
            "only for a G-code program written as a robot program: a robot program is written back with its own targets and speeds, in one file",
        ),
        (_, Language::GCode) => (
            &[Targets, MovesPerFile, MaxTcpSpeedMmS, NameLength],
            "only for a G-code program written as a robot program (--out X.ls, .src, .mod or .jbi; Python output=): G-code carries positions, its own feeds and no program name",
        ),
    };
    match given.iter().find(|(g, o)| *g && unused.contains(o)) {
        Some((_, option)) => Err(Error::InvalidOption {
            option: *option,
            message: why.into(),
        }),
        None => Ok(()),
    }
}

/// Refuses a free lead and tilt for a program written as G-code: its blocks carry positions
/// only, so the leaned postures would be lost.
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::LeadTilt`]).
pub(super) fn check_lean(options: &Options, output: Language) -> Result<()> {
    match (options.free.lead_tilt(), output) {
        (Some(_), Language::GCode) => Err(Error::InvalidOption {
            option: stiffid_core::JobOption::LeadTilt,
            message: "a program written as G-code carries the tool's positions only (a 3-axis program has no words for its axis), so the leaned postures would be lost: write it as a robot program (--out X.ls, .src, .mod or .jbi; Python output=), whose targets carry them".into(),
        }),
        _ => Ok(()),
    }
}

/// Refuses a free tool axis for a program written as G-code: its blocks carry positions only,
/// so the rotation chosen about the tool's axis would not reach the controller (it would run the
/// program's own posture).
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::ToolRotationRange`]).
pub(super) fn check_tool_axis(options: &Options, output: Language) -> Result<()> {
    match (&options.free.tool_rotation(), output) {
        (Some(_), Language::GCode) => Err(Error::InvalidOption {
            option: stiffid_core::JobOption::ToolRotationRange,
            message: "a program written as G-code carries the tool's positions only (a 3-axis program has no word for the rotation about the tool's axis), so the rotation chosen would be lost: write it as a robot program (--out X.ls, .src, .mod or .jbi; Python output=), whose targets carry it".into(),
        }),
        _ => Ok(()),
    }
}

/// Refuses a program written as G-code whose runs ([`stiffid_machining::compensate::Scope::Run`])
/// were compensated in different configurations: its blocks carry positions only, so the
/// controller would hold the first run's configuration throughout.
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::ConfigurationScope`]) naming the first run whose
/// configuration is not the first run's, its lines and both configurations.
pub(super) fn check_runs(configurations: Option<&Configurations>, output: Language) -> Result<()> {
    let runs = configurations.map_or(&[][..], |c| c.runs.as_slice());
    let (Language::GCode, Some(first)) = (output, runs.first()) else {
        return Ok(());
    };
    let named = |r: &Run| name(&r.branches[r.chosen].configuration);
    let Some((k, run)) = (runs.iter().enumerate()).find(|(_, r)| named(r) != named(first)) else {
        return Ok(());
    };
    Err(Error::InvalidOption {
        option: stiffid_core::JobOption::ConfigurationScope,
        message: format!(
            "run: run {} (lines {} to {}) is compensated in {}, run 1 in {}; a G-code program cannot name a configuration, so the controller would keep one throughout: write a robot program (--out X.src, .mod or .ls; Python output=), whose joint moves carry each run's configuration, or keep one configuration per program",
            k + 1,
            run.first_line,
            run.last_line,
            named(run),
            named(first)
        ),
    })
}
