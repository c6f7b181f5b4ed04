//! A compensated G-code program written as a new robot program, the compensate job's step
//! ([`robot_program`]): the program's name and settings checked before the compensation
//! ([`written_name`], [`check`]), its targets in the controller's kinematics and frames
//! (`cell_controller`, [`gcode_controller`]), its arcs as circular moves (`circles`), the
//! home posture before and after (`home`) and the bound of each motion written.

mod circles;
mod home;

use super::{
    after_points, arcs, check_name, check_plan, max_name_length, numbered, place, place_comments,
};
use super::{generate_with, moves, written_targets, File, Plan, Process, Settings, Target};
use super::{Targets, Tool};
use crate::gcode::GCode;
use crate::program::Dialect;
use crate::{Language, Program, Report};
use stiffid_core::common::warning::{Warning, WarningKind};
use stiffid_core::robot::ExternalAxes;
use stiffid_core::{Error, Result, Robot, Setup};

/// A compensated G-code program written as a robot program ([`robot_program`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Generated {
    /// The files: the main program first (with a KRL program's `.dat`), then its sub-programs
    /// in call order.
    pub files: Vec<File>,
    /// The bound of each motion written, m, in the order of the program's motions (`None` for
    /// the home posture's moves, which are not compensated).
    pub bounds: Vec<Option<f64>>,
    /// What the user should know: feeds not stated exactly, arcs written as chords, process
    /// words left as comments, Cartesian targets asked for where the language writes joint
    /// targets.
    pub warnings: Vec<Warning>,
}

/// Refuses, before any compensation, a G-code program written as a robot program of `dialect`
/// with `targets` that cannot state the setup's tool (`check_payload`) or lacks the
/// controller's encoder pulses (`check_pulses`).
///
/// # Errors
/// Those of `check_payload` and `check_pulses`.
pub fn check(setup: &Setup, dialect: Dialect, targets: Targets) -> Result<()> {
    super::check_payload(dialect, targets, &program_tool(setup))?;
    super::check_pulses(dialect, setup.workcell().controller().pulses.as_ref())
}

/// A compensated G-code program written as a new robot program in `dialect` named `name`
/// ([`written_name`]), written with `settings`, cutting points approximated within the chord
/// tolerance (m): its files, each motion's bound and the warnings. Its Cartesian targets are the
/// forward kinematics of the compensated axis angles in the controller's kinematics
/// ([`Setup::controller_robot`]), with the configuration that makes its inverse kinematics
/// return them.
///
/// # Errors
/// Those of [`Setup::controller_robot`], [`moves`] and [`generate_with`].
pub fn robot_program(
    setup: &Setup,
    dialect: Dialect,
    compensated: &Report,
    gcode: &GCode,
    (name, settings, chord_tolerance): (&str, &Settings, f64),
) -> Result<Generated> {
    use rayon::prelude::*;
    let points = &gcode.points;
    let moves = moves(points, settings.max_tcp_speed)?;
    let tool = setup.tool();
    // Joint targets are exact in any kinematics; Cartesian ones are the controller's.
    let controller = match written_targets(dialect, settings.targets) {
        Targets::Joint => setup.robot(),
        Targets::Cartesian => cell_controller(setup)?,
    };
    let targets: Vec<Target> = (compensated.results.par_iter())
        .zip(&compensated.points)
        .map(|(r, p)| {
            let e = circles::values(r, p);
            // The pose in the tool's axes ([tool] tcp_rpy_deg), as the program's tool states them.
            let mut t = Target::at(controller, &tool.tcp, &r.q_compensated, e);
            t.pose.rotation *= tool.rotation;
            t
        })
        .collect();
    let check = (&tool.tcp, compensated, cell_controller(setup));
    let (mut targets, mut moves, circular, form) = circles::circular(
        (dialect, settings),
        &gcode.arcs(),
        (targets, moves),
        check,
        chord_tolerance,
    );
    let mut lines: Vec<Option<u64>> = (circular.index.iter())
        .map(|&i| Some(points[i].line))
        .collect();
    let mut points: Vec<Option<usize>> = circular.index.iter().map(|&i| Some(i)).collect();
    let home = home::add(setup, controller, (&mut targets, &mut moves, &mut lines));
    if home {
        points.insert(0, None);
        points.push(None);
    }
    let mut before = place(&gcode.process, &lines);
    after_points(&gcode.process, &points, &mut before);
    let comments_before = place_comments(&gcode.comments, &lines);
    let process = Process {
        words: &gcode.process,
        before: &before,
        io: Some(&setup.workcell().controller().program.io),
        comments: &gcode.comments,
        comments_before: &comments_before,
    };
    let plan = Plan {
        dialect,
        name,
        targets: &targets,
        moves: &moves,
        tool: program_tool(setup),
        work: setup.workpiece().copied().unwrap_or_default(),
        external: setup.robot().external(),
        world: setup.program_world(),
        approximation: chord_tolerance,
        numbers: numbers(setup, dialect),
        pulses: setup.workcell().controller().pulses.as_ref(),
        settings: *settings,
    };
    let written = generate_with(&plan, &process)?;
    let mut warnings: Vec<Warning> = (written.warnings.into_iter())
        .map(|w| Warning::new(WarningKind::Feed, w))
        .collect();
    let left_out = circular.warnings.iter().cloned().chain(written.left_out);
    warnings.extend(left_out.map(|w| Warning::new(WarningKind::LeftOut, w)));
    warnings.extend(targets_warning(dialect, settings));
    let bounds: Vec<f64> = compensated.results.iter().map(|r| r.budget.bound).collect();
    let path = arcs::motion_bounds(&circular, &bounds, form.unwrap_or(arcs::Form::ViaEnd));
    // The home posture's moves carry no bound: they are not compensated.
    let bounds: Vec<Option<f64>> = (home.then_some(None).into_iter())
        .chain(path.into_iter().map(Some))
        .chain(home.then_some(None))
        .collect();
    Ok(Generated {
        files: written.files,
        bounds,
        warnings,
    })
}

/// The warning that `settings` asked for Cartesian targets a `dialect` program writes as joint
/// targets.
fn targets_warning(dialect: Dialect, settings: &Settings) -> Option<Warning> {
    (settings.targets_asked && written_targets(dialect, settings.targets) != settings.targets)
        .then(|| Warning::new(WarningKind::LeftOut, format!(
            "targets = {}: {} programs are written with joint targets (the compensated axis angles in pulses; stiffid reads no rectangular position back), which hold in any kinematics; the controller interpolates the axes between them",
            settings.targets.name(),
            dialect.controller().key().to_ascii_uppercase()
        )))
}

/// The setup's tool and part frame as its controller holds them by number ([`numbered`]).
fn numbers(setup: &Setup, dialect: Dialect) -> numbered::Numbers {
    let c = setup.workcell().controller();
    let part = (setup.program_world()).inv_mul(&setup.workpiece().copied().unwrap_or_default());
    let highest = dialect.controller().descriptor().frame_numbers;
    let tool = &program_tool(setup).frame;
    numbered::Numbers::of((&c.tools, &c.bases), tool, &part, highest)
}

/// The name of the program written, checked before anything is computed: for a G-code program
/// written as a robot program, the stem of `out_name` in upper case (`check_plan`: every
/// name, setting and count of the program of its points); for a robot program written back
/// under another name, that stem (upper case for LS, as written for KRL; [`check_name`]),
/// which its declaration takes ([`crate::program::rename`]); `None` otherwise (a RAPID module,
/// G-code written as G-code, no output file).
///
/// # Errors
/// [`Error::InvalidField`] (`out`) for a KRL program to be written into a `.dat` (a `DEF` belongs
/// in the `.src`); those of `check_plan`, [`check_name`] and `check_cell`.
pub fn written_name(
    program: &Program,
    output: Language,
    out_name: &str,
    (settings, cell): (&Settings, Option<&ExternalAxes>),
) -> Result<Option<String>> {
    let path = std::path::Path::new(out_name);
    let extension = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("");
    let Language::Robot(dialect) = output else {
        return Ok(None);
    };
    let controller = dialect.controller();
    if let Some(why) = controller.refuses_output(&extension.to_ascii_lowercase()) {
        return Err(Error::InvalidField {
            field: "out".into(),
            message: format!("{out_name}: {why}"),
        });
    }
    match program {
        Program::GCode(g) => {
            let name = stem.to_ascii_uppercase();
            check_plan(dialect, &name, settings, g.points.len())?;
            if let Some(generator) = dialect.controller().generator() {
                generator.check_settings(settings)?;
            }
            super::check_cell(dialect, settings.targets, cell)?;
            Ok(Some(name))
        }
        Program::Robot(_) if stem.is_empty() => Ok(None),
        Program::Robot(_) => {
            let Some(name) = controller.program_name(stem) else {
                return Ok(None);
            };
            let longest = (settings.name_length).unwrap_or(max_name_length(dialect));
            check_name(dialect, &name, longest)?;
            Ok(Some(name))
        }
    }
}

/// The controller's kinematics for a G-code program written back as G-code
/// ([`Setup::controller_robot`]): on a cell with external axes, the controller moves the arm on
/// its carriage and the part on its positioner by its own model of them, so its robot must
/// declare them (`cell_controller`); the G-code's positions are then the controller's forward
/// kinematics of the compensated axes at its own external axes, in the part frame of `[workpiece]
/// base_from_part`. When the controller's model of them is not the setup's (a nominal controller
/// beside a calibrated cell), a warning states that model and frame, which the controller must
/// hold.
///
/// # Errors
/// Those of `cell_controller`, its message saying what a G-code controller of the cell needs.
pub fn gcode_controller(setup: &Setup) -> Result<(&Robot, Option<Warning>)> {
    let controller = cell_controller(setup).map_err(|e| match e {
        Error::InvalidField { field, message } => Error::InvalidField {
            field,
            message: format!("{message}; G-code written back on this cell would otherwise place the part by the setup's own (calibrated) external axes, which the controller does not run; or say kinematics = \"calibrated\" for a controller loaded with the calibrated cell, or write the program as a robot program (its joint targets hold in any kinematics)"),
        },
        e => e,
    })?;
    let cell = (setup.robot().external()).filter(|a| !a.is_empty());
    let own = controller.external() != setup.robot().external();
    let warning = match (own, cell) {
        (true, Some(axes)) => Some(Warning::new(WarningKind::Calibrated, format!(
            "G-code on a cell with external axes ({}) is written for a controller that moves them by the model of its robot '{}' (kinematics = \"nominal\"), not the setup's '{}', with the part frame at [workpiece] base_from_part: the controller's external axes and part frame must be those",
            (axes.axes().iter().map(|a| a.name.as_str())).collect::<Vec<_>>().join(", "),
            controller.name(),
            setup.robot().name()
        ))),
        _ => None,
    };
    Ok((controller, warning))
}

/// The controller's kinematics ([`Setup::controller_robot`]) for Cartesian targets, which on a
/// cell with external axes must model the cell's: the controller moves the arm on its carriage
/// (and the part on its positioner) by its own model of them.
///
/// # Errors
/// Those of [`Setup::controller_robot`]; [`Error::InvalidField`] (`controller.robot`) for a
/// controller's robot without the cell's external axes (another count or role).
fn cell_controller(setup: &Setup) -> Result<&Robot> {
    let controller = setup.controller_robot()?;
    let roles = |r: &Robot| -> Vec<_> {
        (r.external().map_or(&[][..], |a| a.axes()).iter())
            .map(|a| (a.role, a.kind))
            .collect()
    };
    if roles(controller) != roles(setup.robot()) {
        let names = |r: &Robot| match r.external().filter(|a| !a.is_empty()) {
            Some(a) => (a.axes().iter().map(|a| a.name.as_str()))
                .collect::<Vec<_>>()
                .join(", "),
            None => "none".into(),
        };
        return Err(Error::InvalidField {
            field: "controller.robot".into(),
            message: format!(
                "the controller's robot '{}' has the external axes {} and the setup's robot '{}' has {}: the controller moves the arm by its own model of the cell's external axes, so its robot file must declare them ([[external_axis]])",
                controller.name(),
                names(controller),
                setup.robot().name(),
                names(setup.robot())
            ),
        });
    }
    Ok(controller)
}

/// The tool a generated program states, from the controller's flange (the setup's
/// `[robot_flange]` adapter included): the setup's TCP and tool axes (`tcp_mm`, `tcp_rpy_deg`),
/// mass and centre of mass.
fn program_tool(setup: &Setup) -> Tool {
    let adapter = setup.workcell().controller().adapter;
    Tool {
        frame: adapter * setup.tool().frame(),
        payload: setup
            .payload()
            .map(|p| (p.mass, adapter.transform_point(&p.centre.into()).coords)),
    }
}
