//! What is placed: a G-code program cut under a process, or a path file's points; each as the
//! part frame carries it, and what cannot move with the part refused naming why.

use nalgebra::Isometry3;
use stiffid_core::common::choice::Choice;
use stiffid_core::observation::deflection::Frame;
use stiffid_core::{Error, Result, Setup};
use stiffid_machining::compensate::{PathPoint, Target};
use stiffid_machining::process::Process;
use stiffid_machining::program::{cartesian, Dialect};
use stiffid_machining::{Language, Program};

/// The work placed with the part.
#[derive(Debug, Clone, Copy)]
pub enum Work<'a> {
    /// A G-code program, its points in the part frame, or a robot program whose targets are all
    /// Cartesian ones in the part frame ([`stiffid_machining::program::cartesian`]), cut under
    /// `process`.
    Program {
        /// The program ([`stiffid_machining::read`]).
        program: &'a Program,
        /// The process that gives every point its wrench.
        process: &'a Process,
    },
    /// A path file's points ([`stiffid_machining::path`], [`read_path`]): each row's TCP pose
    /// (`x_mm..rz_deg`) in the part frame, its wrench in the tool frame (`tool`) or in the part
    /// frame (`base`: the part's own frame here, turning with it as the cut does).
    Path(&'a [PathPoint]),
}

/// Reads a path file's text (`name` for its errors) for placement on `setup`: the rows of
/// [`stiffid_machining::path::parse`] with `default_frame` for rows without a `frame`.
///
/// # Errors
/// [`Error::InvalidField`] (`path`) for a setup whose robot has external axes (before reading);
/// those of [`stiffid_machining::path::parse`], as [`Error::Input`] naming the file.
pub fn read_path(
    setup: &Setup,
    name: &str,
    text: &str,
    default_frame: Frame,
) -> Result<Vec<PathPoint>> {
    refuse_external(setup)?;
    stiffid_machining::path::parse(text, default_frame).map_err(|e| Error::Input {
        source_name: name.to_string(),
        error: Box::new(e),
    })
}

/// Reads a program file's text (`name` for its errors; G-code arcs split into chords of at
/// most `chord_tolerance`, m; a G-code program read on the controller `setup` and `process`'s
/// tool lengths describe, [`stiffid_machining::gcode::Machine::of`]) for placement on `setup`: its language (`check_language`), the
/// program ([`stiffid_machining::read`]), and what the part cannot carry (`Work::check`),
/// refused before any placement is tried.
///
/// # Errors
/// Those of `check_language` and `Work::check`; those of [`stiffid_machining::read`] and
/// `Work::check`'s naming a line ([`Error::Program`]: a tool that is not the setup's, a
/// frame that is not the part's) as [`Error::Input`] naming the file, as `compensate` names
/// them.
pub fn read_program(
    setup: &Setup,
    name: &str,
    text: &str,
    language: Language,
    (chord_tolerance, process): (f64, &Process),
) -> Result<Program> {
    read_program_with(
        setup,
        name,
        (text, None, &[]),
        language,
        (chord_tolerance, process),
    )
}

/// [`read_program`] with the data file beside the program (KRL's `.dat`: its points and frame
/// data), as the controller pairs them, and the files of the controller's backup given with it
/// (each its name and text: KRL the module's `.dat` and `$config.dat`, RAPID the task's other
/// modules, as `compensate` reads them, [`stiffid_machining::program::Context::backup`]).
///
/// # Errors
/// Those of [`read_program`].
pub fn read_program_with(
    setup: &Setup,
    name: &str,
    (text, data, backup): (&str, Option<&str>, &[(String, String)]),
    language: Language,
    (chord_tolerance, process): (f64, &Process),
) -> Result<Program> {
    check_language(language)?;
    let in_file = |e: Error| match e {
        e @ Error::Program { .. } => Error::Input {
            source_name: name.to_string(),
            error: Box::new(e),
        },
        e => e,
    };
    let machine = stiffid_machining::gcode::Machine::of(setup, Some(process));
    let mut context =
        (stiffid_machining::program::Context::of(setup).with_machine(&machine)).with_backup(backup);
    context.data = data;
    let program =
        stiffid_machining::read_in(text, language, chord_tolerance, &context).map_err(in_file)?;
    check_program(setup, &program).map_err(in_file)?;
    Ok(program)
}

/// Refuses a program the part cannot carry ([`Work::check`]).
fn check_program(setup: &Setup, program: &Program) -> Result<()> {
    check_language(program.language())?;
    let Program::Robot(p) = program else {
        return Ok(());
    };
    match p.targets.iter().find(|t| t.cartesian.is_none()) {
        Some(t) => Err(Error::InvalidField { field: "program".into(), message: format!("a {} program's targets are joint targets ({}, line {} the first), and axis angles do not move with the part: give its targets as Cartesian ones in the part frame ({}), or the program as G-code, or its TCP poses in the part frame as a path file", program.language().help(), joint_form(p.dialect), t.line, part_form(p.dialect)) }),
        None => cartesian::check_part(p, setup),
    }
}

impl Work<'_> {
    /// Refuses what the part cannot carry: a robot program with joint targets (axis angles stay
    /// where they are) or whose Cartesian targets are not for the setup's tool or not in the
    /// part frame ([`stiffid_machining::program::cartesian::check_part`]), a path file's
    /// axis-angle rows, a path file on a robot with external axes.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`program`, `path`) naming why; [`Error::Program`] naming the
    /// line of a target for another tool or in another frame; those of
    /// [`Setup::controller_robot`].
    pub(crate) fn check(&self, setup: &Setup) -> Result<()> {
        let refuse = |field: &str, message: String| {
            Err(Error::InvalidField {
                field: field.into(),
                message,
            })
        };
        match self {
            Work::Program { program, .. } => check_program(setup, program),
            Work::Path(points) => {
                refuse_external(setup)?;
                match points.iter().find(|p| matches!(p.target, Target::Posture(_))) {
                    Some(p) => refuse("path", format!("line {}: axis angles (q1_deg..q6_deg) do not move with the part: give each row's TCP pose in the part frame (x_mm, y_mm, z_mm, rx_deg, ry_deg, rz_deg)", p.line)),
                    None => Ok(()),
                }
            }
        }
    }
}

/// Refuses a program language whose targets cannot move with the part: Yaskawa INFORM's
/// (stiffid reads its pulse positions only); G-code and the languages with Cartesian targets
/// (KRL, RAPID, LS) pass, their targets checked once read ([`Work::check`]). A front end
/// checks it before reading the program.
///
/// # Errors
/// [`Error::InvalidField`] (`program`) naming the language, its joint targets and what to give.
pub(crate) fn check_language(language: Language) -> Result<()> {
    match language {
        Language::Robot(d) if d.controller().part_forms().is_none() => Err(Error::InvalidField {
            field: "program".into(),
            message: format!("a {} program's targets are joint targets ({}), and axis angles do not move with the part: give the program as G-code, or its TCP poses in the part frame as a path file", language.help(), joint_form(d)),
        }),
        _ => Ok(()),
    }
}

/// Where a dialect's Cartesian targets are in the part frame.
fn part_form(d: Dialect) -> &'static str {
    d.controller().part_forms().unwrap_or("none")
}

/// The points of a path file with the part at `base_from_part`: each pose and each `base`
/// wrench (the part frame's, module docs) carried into the robot base frame.
pub(super) fn placed(points: &[PathPoint], base_from_part: &Isometry3<f64>) -> Vec<PathPoint> {
    let turn = base_from_part.rotation;
    points
        .iter()
        .map(|p| {
            let mut p = p.clone();
            if let Target::Pose(pose) = p.target {
                p.target = Target::Pose(base_from_part * pose);
            }
            if p.frame == Frame::Base {
                let (f, m) = (p.wrench.fixed_rows::<3>(0), p.wrench.fixed_rows::<3>(3));
                let (f, m) = (turn * f.into_owned(), turn * m.into_owned());
                p.wrench = nalgebra::Vector6::new(f.x, f.y, f.z, m.x, m.y, m.z);
            }
            p
        })
        .collect()
}

fn joint_form(d: Dialect) -> &'static str {
    d.controller().joint_forms()
}

/// Refuses a path file on a robot with external axes (module docs of [`Work::Path`]).
fn refuse_external(setup: &Setup) -> Result<()> {
    match setup.robot().external() {
        Some(_) => Err(Error::InvalidField {
            field: "path".into(),
            message: format!("setup {} has external axes: a path file is placed on a robot without them (give the program as G-code)", setup.name()),
        }),
        None => Ok(()),
    }
}
