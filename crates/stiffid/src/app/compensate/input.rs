//! A program input of the compensate job read and checked before anything is computed: its
//! output, options and settings, its text, and its Cartesian targets resolved as the controller
//! moves to them; the warnings about the input itself (its encoding, a G-code program's
//! unstated units and unplaced G53 rapids, an LS program's uncoupled axes, the points the
//! controller holds).

use super::{generate, in_input, output, Input};
use crate::app::{Warning, WarningKind};
use stiffid_core::io::Encoding;
use stiffid_core::{Error, Result, Setup};
use stiffid_machining::compensate::Options;
use stiffid_machining::program::Context;
use stiffid_machining::{self as machining, Language, Program};

/// The program of a program input, checked against its output and options, read and its
/// Cartesian targets resolved on `setup`'s controller (as the controller moves to them);
/// `None` for a path file.
///
/// # Errors
/// Those of [`output::check_output`], [`output::check_lean`], [`output::check_tool_axis`],
/// [`Settings::validate`], [`output::check_settings`],
/// [`generate::compensated::check`], [`machining::read_in`] (with the setup's pulses and tools) and
/// [`machining::resolve`] (the program's
/// as [`Error::Input`] naming its file).
pub(super) fn read_checked(
    setup: &Setup,
    input: &Input,
    options: &Options,
) -> Result<Option<Program>> {
    let Input::Program {
        name,
        text,
        data,
        language,
        chord_tolerance,
        output,
        settings,
        process,
        reading,
        ..
    } = input
    else {
        return Ok(None);
    };
    let (language, output) = (*language, *output);
    output::check_output(language, output).map_err(|e| in_input(name, e))?;
    output::check_lean(options, output)?;
    output::check_tool_axis(options, output)?;
    settings.validate()?;
    output::check_settings(language, output, settings)?;
    if let (Language::GCode, Language::Robot(d)) = (language, output) {
        generate::compensated::check(setup, d, settings.targets)?;
    }
    let machine = stiffid_machining::gcode::Machine::of(setup, Some(process));
    let context =
        (Context::of(setup).with_data(*data).with_machine(&machine)).with_reading(*reading);
    let program = read_program_in(name, text, language, *chord_tolerance, &context)?;
    // A Cartesian program's targets as the controller moves to them (a copy only then).
    match machining::resolve(&program, setup, None, options) {
        Ok(std::borrow::Cow::Owned(p)) => Ok(Some(p)),
        Ok(std::borrow::Cow::Borrowed(_)) => Ok(Some(program)),
        Err(e) => Err(in_input(name, e)),
    }
}

/// Reads a program file's text in `language` (G-code arcs split to `chord_tolerance`, m), its
/// errors placed in the file `name`.
///
/// # Errors
/// Those of [`machining::read`], as [`Error::Input`](stiffid_core::Error::Input).
pub fn read_program(
    name: &str,
    text: &str,
    language: Language,
    chord_tolerance: f64,
) -> Result<Program> {
    read_program_in(name, text, language, chord_tolerance, &Context::default())
}

/// [`read_program`] with what a setup says of the program in `context` (an INFORM job's pulses
/// and tool files, [`Context::of`]; KRL's `.dat`; a G-code program's controller, its work offsets,
/// start and home positions and tool lengths, [`stiffid_machining::gcode::Machine::of`]).
///
/// # Errors
/// Those of [`machining::read_in`], as [`Error::Input`](stiffid_core::Error::Input).
pub fn read_program_in(
    name: &str,
    text: &str,
    language: Language,
    chord_tolerance: f64,
    context: &Context,
) -> Result<Program> {
    machining::read_in(text, language, chord_tolerance, context).map_err(|e| in_input(name, e))
}

/// Refuses a setup without the tool's centre point.
pub(super) fn check_tcp(setup: &Setup) -> Result<()> {
    match setup.tcp_given() {
        true => Ok(()),
        false => Err(Error::InvalidField {
            field: "tool.tcp_mm".into(),
            message: format!("missing in setup {}: compensation moves the cutting tool's centre point, which the setup must give ([tool] tcp_mm); measuring point 1 is a measuring target, not the tool", setup.name()),
        }),
    }
}

/// The warning that the program's files (its `text`, a KRL program's `data`, read as Latin-1)
/// are not all UTF-8, naming the one that is not: the program `name`, or the `.dat` beside it
/// when the program alone is UTF-8 (both are read and written as Latin-1).
pub(super) fn encoding_warning(
    name: &str,
    encoding: Encoding,
    (text, data): (&str, Option<&str>),
) -> Option<Warning> {
    let utf8 = |t: &str| (encoding.encode(t)).is_ok_and(|b| std::str::from_utf8(&b).is_ok());
    let which = match data {
        Some(d) if utf8(text) && !utf8(d) => format!("the .dat beside {name}"),
        _ => name.to_string(),
    };
    (encoding == Encoding::Latin1).then(|| {
        Warning::new(
            WarningKind::Encoding,
            format!("{which} is not UTF-8 text: read as Latin-1 (ISO 8859-1, each byte one character), as controllers write ISO 8859-1 or Windows-1252 files; the compensated program is written in it, every byte not compensated as read"),
        )
    })
}

/// The warning that a G-code program states no units (`G20` or `G21`) before its first motion:
/// it is read in mm, the units a controller is in at its start being its own setting.
pub(super) fn unstated_units(program: &Program) -> Option<Warning> {
    let Program::GCode(g) = program else {
        return None;
    };
    g.unstated_units.map(|line| {
        Warning::new(
            WarningKind::Units,
            format!("the program states no units (G20 or G21) before its first motion, line {line}: read in mm, as LinuxCNC and grbl start; a controller set to inches (Haas setting 9, a FANUC parameter) runs it 25.4 times larger: write G21 (or G20) at its start"),
        )
    })
}

/// The warning that a G-code program moves a tool of known length without a tool length
/// offset (`G43`) in force: its coordinates are read as the spindle's gauge line's, the tip that
/// length below them.
pub(super) fn no_length_offset(program: &Program) -> Option<Warning> {
    let Program::GCode(g) = program else {
        return None;
    };
    g.no_length_offset.map(|(line, length)| {
        Warning::new(
            WarningKind::Plausibility,
            format!("line {line} moves the tool, whose length the process gives ({:.3} mm), with no tool length offset (G43) in force: its coordinates are read as the spindle's gauge line's, the tip {:.3} mm below them, as a controller with that tool table runs it; if the program's coordinates are the tip's (a machine whose work Z was touched off with the tool), leave length_mm out of the process", length * 1e3, length * 1e3),
        )
    })
}

/// The warning that a G-code program writes rotary words (`A0`) for an axis the cell lacks,
/// every one of them 0: read as no motion.
pub(super) fn zero_rotary(program: &Program) -> Option<Warning> {
    let Program::GCode(g) = program else {
        return None;
    };
    g.zero_rotary.map(|line| {
        Warning::new(
            WarningKind::LeftOut,
            format!("line {line} and after: rotary axis words (A, B, C), every one 0, for an axis the cell does not have: read as no motion (the axis stays at its zero, where the setup places the part) and written back as found"),
        )
    })
}

/// The warning that a G-code program's `G53` rapids were read without the setup's `G53` frame:
/// they make no point, and the robot goes from the point before each to the next in one move.
pub(super) fn unplaced_g53(program: &Program) -> Option<Warning> {
    let Program::GCode(g) = program else {
        return None;
    };
    let lines = &g.unplaced_g53;
    let shown: Vec<String> = lines.iter().take(5).map(u64::to_string).collect();
    let more = match lines.len() {
        n if n > 5 => format!(" and {} more", n - 5),
        _ => String::new(),
    };
    let (what, word) = match lines.len() {
        1 => ("1 G53 rapid".to_string(), "line"),
        n => (format!("{n} G53 rapids"), "lines"),
    };
    (!lines.is_empty()).then(|| {
        Warning::new(
            WarningKind::LeftOut,
            format!("{what} in machine coordinates, which the setup does not place (no [workpiece.offsets] G53), make no point ({word} {}{more}): the axes each names are unknown until the program gives them again, and the robot goes from the point before it to the next point in one move, without that retract; give the G53 frame to have them", shown.join(", ")),
        )
    })
}

/// The warning that the joint positions of a program whose controller measures axis 3 from the
/// horizontal (FANUC's LS: [`Descriptor::axis_3_from_horizontal`]) are read on a URDF robot whose
/// axes the setup does not couple (no `robot_axis_map`): a URDF's joint 3 turns relative to link 2.
///
/// [`Descriptor::axis_3_from_horizontal`]: stiffid_machining::program::Descriptor::axis_3_from_horizontal
pub(super) fn uncoupled_ls(setup: &Setup, program: &Program) -> Option<Warning> {
    let Program::Robot(p) = program else {
        return None;
    };
    let robot = setup.robot();
    let joint = p.targets.iter().find(|t| t.cartesian.is_none())?;
    let uncoupled = *robot.axis_map() == stiffid_core::robot::AxisMap::default();
    let horizontal = p.dialect.controller().descriptor().axis_3_from_horizontal;
    (horizontal && robot.urdf_source().is_some() && uncoupled).then(|| {
        Warning::new(
            WarningKind::Plausibility,
            format!("the LS program's joint positions (line {} the first) are read as the URDF robot's joint positions: a FANUC measures J3 from the horizontal (the J2/J3 interaction), a URDF's joint 3 from link 2, so on a FANUC each J3 is another posture unless the setup couples the axes (robot_axis_map, joint 3 = J2 + J3 for ROS-Industrial's FANUC URDFs)", joint.line),
        )
    })
}

/// The lines of a robot program's motions to points the controller holds (KRL's `XHOME`).
pub(super) fn held_lines(program: &Program) -> Vec<u64> {
    match program {
        Program::Robot(p) => (p.targets.iter())
            .filter(|t| t.is_held())
            .map(|t| t.line)
            .collect(),
        Program::GCode(_) => Vec::new(),
    }
}

/// Whether target `i` of `program` is a motion of the program's own file, not of a program of
/// the backup it calls (whose motions are on lines of their own file).
pub(super) fn own_motion(program: &Program, i: usize) -> bool {
    match program {
        Program::Robot(p) => p.called_in(i).is_none(),
        Program::GCode(_) => true,
    }
}

/// The programs of the backup a program calls that move, compensated, as the files to write
/// beside it: each under its own name (the stem of its file as given); a KRL module's `.dat`
/// (after its `.src`, of the same stem) as that file's data.
pub(super) fn called_files(
    called: &[(String, String)],
) -> Vec<stiffid_machining::program::generate::File> {
    let mut out: Vec<stiffid_machining::program::generate::File> = Vec::new();
    for (file, text) in called {
        let name = file.rsplit(['/', '\\']).next().unwrap_or(file);
        let (stem, extension) = name.rsplit_once('.').unwrap_or((name, ""));
        if let Some(last) = out.last_mut()
            && extension.eq_ignore_ascii_case("dat")
            && last.name.eq_ignore_ascii_case(stem)
            && last.data.is_none()
        {
            last.data = Some(text.clone());
            continue;
        }
        out.push(stiffid_machining::program::generate::File {
            name: stem.to_string(),
            text: text.clone(),
            data: None,
        });
    }
    out
}

/// The warning that the motions on `lines` go to the controller's home (KRL's `XHOME`, at the
/// setup's `[controller] home_deg`), which the program does not hold: not compensated.
pub(super) fn held_warning(lines: &[u64]) -> Option<Warning> {
    let shown: Vec<String> = lines.iter().map(u64::to_string).collect();
    (!lines.is_empty()).then(|| {
        Warning::new(
            WarningKind::LeftOut,
            format!("the motions to XHOME (lines {}) go to the controller's home position, which its $config.dat holds and the setup gives ([controller] home_deg): they are read at the home posture, and written as read, not compensated (no bound)", shown.join(", ")),
        )
    })
}

/// The warning that the motions the program's reader left as found (a motion to the home
/// position; with `--leave-refused`, the motions refused for what only the run decides) are not
/// compensated: each line and why, written back as read.
pub(super) fn left_warning(program: &Program) -> Option<Warning> {
    let Program::Robot(p) = program else {
        return None;
    };
    let listed: Vec<String> = (p.left.iter())
        .map(|l| format!("line {}: {}", l.line, l.why))
        .collect();
    (!listed.is_empty()).then(|| {
        Warning::new(
            WarningKind::LeftOut,
            format!("{} motion{} left as found, not compensated (no bound) and written back as read: {}", listed.len(), if listed.len() == 1 { "" } else { "s" }, listed.join("; ")),
        )
    })
}

/// The warning naming the positions the reader copied into the program from the controller's
/// backup (an LS position register read from `POSREG.VA`: the register left as it is, the motion
/// written to the program's copy where compensating moves it).
pub(super) fn copied_warning(program: &Program) -> Option<Warning> {
    let Program::Robot(p) = program else {
        return None;
    };
    (!p.copied.is_empty()).then(|| Warning::new(WarningKind::LeftOut, p.copied.join("; ")))
}

/// The warning naming what reading a robot program on its setup found (a frame taught in the
/// nominal cell, re-located to the part the calibration located or read as stated).
pub(super) fn notes_warning(program: &Program) -> Option<Warning> {
    let Program::Robot(p) = program else {
        return None;
    };
    (!p.notes.is_empty()).then(|| Warning::new(WarningKind::Calibrated, p.notes.join("; ")))
}
