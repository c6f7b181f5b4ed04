//! A compensated program's output checked and written: its name and settings before the
//! compensation ([`written_name`]), a G-code program written as a new robot program
//! ([`generated`]) in the controller's kinematics and frames.

use super::certify;
use crate::app::{Warning, WarningKind};
use stiffid_core::robot::ExternalAxes;
use stiffid_core::{Error, Result, Setup};
use stiffid_machining::program::generate::arcs::{self, Circular, Form};
use stiffid_machining::program::generate::{
    self, generate_with, moves, Plan, Settings, Target, Tool,
};
use stiffid_machining::program::Dialect;
use stiffid_machining::{self as machining, Language, Program};

/// A compensated G-code program written as a new robot program in `dialect`
/// ([`write_robot_program`]), each target's bound at `level` in a comment: the main program
/// (with a KRL program's `.dat`), its sub-programs, the warnings.
///
/// # Errors
/// Those of [`write_robot_program`].
pub(super) fn generated(
    setup: &Setup,
    dialect: Dialect,
    compensated: &machining::Report,
    gcode: &stiffid_machining::gcode::GCode,
    ((name, settings, chord_tolerance), level): ((String, Settings, f64), f64),
) -> Result<(generate::File, Vec<generate::File>, Vec<Warning>)> {
    let how = (name.as_str(), &settings, chord_tolerance);
    let (written, (circular, form), home) =
        write_robot_program(setup, dialect, compensated, gcode, how)?;
    let arcs = circular.warnings.len();
    let feeds = written.warnings.len() - arcs;
    let mut warnings: Vec<Warning> = (written.warnings.into_iter().enumerate())
        .map(|(i, w)| match i < feeds {
            true => Warning::new(WarningKind::Feed, w),
            false => Warning::new(WarningKind::LeftOut, w),
        })
        .collect();
    warnings.extend((written.left_out.into_iter()).map(|w| Warning::new(WarningKind::LeftOut, w)));
    if settings.targets_asked
        && generate::written_targets(dialect, settings.targets) != settings.targets
    {
        warnings.push(Warning::new(WarningKind::LeftOut, format!(
            "targets = {}: {} programs are written with joint targets (the compensated axis angles in pulses; stiffid reads no rectangular position back), which hold in any kinematics; the controller interpolates the axes between them",
            settings.targets.name(),
            dialect.controller().key().to_ascii_uppercase()
        )));
    }
    let bounds: Vec<f64> = compensated.results.iter().map(|r| r.budget.bound).collect();
    let path = arcs::motion_bounds(&circular, &bounds, form.unwrap_or(Form::ViaEnd));
    // The home posture's moves carry no bound: they are not compensated.
    let bounds: Vec<Option<f64>> = (home.then_some(None).into_iter())
        .chain(path.into_iter().map(Some))
        .chain(home.then_some(None))
        .collect();
    let texts: Vec<String> = written.files.iter().map(|f| f.text.clone()).collect();
    let texts = certify::generated(dialect, &texts, &bounds, level);
    let mut files =
        (written.files.into_iter().zip(texts)).map(|(f, text)| generate::File { text, ..f });
    let main = files.next().unwrap_or_else(|| generate::File {
        name,
        text: String::new(),
        data: None,
    });
    Ok((main, files.collect(), warnings))
}

/// The name of the program written, checked before anything is computed: for a G-code program
/// written as a robot program, the stem of `out_name` in upper case ([`generate::check_plan`]:
/// every name, setting and count of the program of its points); for a robot program written back
/// under another name, that stem (upper case for LS, as written for KRL;
/// [`generate::check_name`]), which its declaration takes ([`renamed`]); `None` otherwise (a
/// RAPID module, G-code written as G-code, no output file).
///
/// # Errors
/// [`Error::InvalidField`] (`out`) for a KRL program to be written into a `.dat` (a `DEF` belongs
/// in the `.src`); those of [`generate::check_plan`] and [`generate::check_name`].
pub(super) fn written_name(
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
            generate::check_plan(dialect, &name, settings, g.points.len())?;
            if let Some(generator) = dialect.controller().generator() {
                generator.check_settings(settings)?;
            }
            generate::check_cell(dialect, settings.targets, cell)?;
            Ok(Some(name))
        }
        Program::Robot(_) if stem.is_empty() => Ok(None),
        Program::Robot(_) => {
            let Some(name) = controller.program_name(stem) else {
                return Ok(None);
            };
            let longest = (settings.name_length).unwrap_or(generate::max_name_length(dialect));
            generate::check_name(dialect, &name, longest)?;
            Ok(Some(name))
        }
    }
}

/// The robot program of a compensated G-code path ([`generate`]) named `name`
/// ([`written_name`]), written with `settings`, cutting points approximated within the chord
/// tolerance (m). Its Cartesian targets are the forward kinematics of the compensated axis angles
/// in the controller's kinematics ([`Setup::controller_robot`]), with the configuration that makes
/// its inverse kinematics return them.
///
/// # Errors
/// Those of [`Setup::controller_robot`], [`moves`] and [`generate`].
fn write_robot_program(
    setup: &Setup,
    dialect: Dialect,
    compensated: &machining::Report,
    gcode: &stiffid_machining::gcode::GCode,
    (name, settings, chord_tolerance): (&str, &Settings, f64),
) -> Result<(generate::Written, (Circular, Option<Form>), bool)> {
    use rayon::prelude::*;
    let points = &gcode.points;
    let moves = moves(points, settings.max_tcp_speed)?;
    let tool = setup.tool();
    // Joint targets are exact in any kinematics; Cartesian ones are the controller's.
    let controller = match generate::written_targets(dialect, settings.targets) {
        generate::Targets::Joint => setup.robot(),
        generate::Targets::Cartesian => cell_controller(setup)?,
    };
    let targets: Vec<Target> = (compensated.results.par_iter())
        .zip(&compensated.points)
        .map(|(r, p)| {
            let e = super::circles::values(r, p);
            // The pose in the tool's axes ([tool] tcp_rpy_deg), as the program's tool states them.
            let mut t = Target::at(controller, &tool.tcp, &r.q_compensated, e);
            t.pose.rotation *= tool.rotation;
            t
        })
        .collect();
    let check = (&tool.tcp, compensated, cell_controller(setup));
    let (mut targets, mut moves, circular, form) = super::circles::circular(
        (dialect, settings),
        &gcode.arcs(),
        (targets, moves),
        check,
        chord_tolerance,
    );
    let mut lines: Vec<Option<u64>> = (circular.index.iter())
        .map(|&i| Some(points[i].line))
        .collect();
    let home = super::home::add(setup, controller, (&mut targets, &mut moves, &mut lines));
    let before = generate::place(&gcode.process, &lines);
    let comments_before = generate::place_comments(&gcode.comments, &lines);
    let process = generate::Process {
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
    let mut written = generate_with(&plan, &process)?;
    written.warnings.extend(circular.warnings.iter().cloned());
    Ok((written, (circular, form), home))
}

/// The setup's tool and part frame as its controller holds them by number
/// ([`generate::numbered`]).
fn numbers(setup: &Setup, dialect: Dialect) -> generate::numbered::Numbers {
    let c = setup.workcell().controller();
    let part = (setup.program_world()).inv_mul(&setup.workpiece().copied().unwrap_or_default());
    let highest = dialect.controller().descriptor().frame_numbers;
    let tool = &program_tool(setup).frame;
    generate::numbered::Numbers::of((&c.tools, &c.bases), tool, &part, highest)
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

/// The controller's kinematics for a G-code program written back as G-code
/// ([`Setup::controller_robot`]): on a cell with external axes, the controller moves the arm on
/// its carriage and the part on its positioner by its own model of them, so its robot must
/// declare them ([`cell_controller`]); the G-code's positions are then the controller's forward
/// kinematics of the compensated axes at its own external axes, in the part frame of `[workpiece]
/// base_from_part`. When the controller's model of them is not the setup's (a nominal controller
/// beside a calibrated cell), a warning states that model and frame, which the controller must
/// hold.
///
/// # Errors
/// Those of [`cell_controller`], its message saying what a G-code controller of the cell needs.
pub(super) fn gcode_controller(setup: &Setup) -> Result<(&stiffid_core::Robot, Option<Warning>)> {
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
fn cell_controller(setup: &Setup) -> Result<&stiffid_core::Robot> {
    let controller = setup.controller_robot()?;
    let roles = |r: &stiffid_core::Robot| -> Vec<_> {
        (r.external().map_or(&[][..], |a| a.axes()).iter())
            .map(|a| (a.role, a.kind))
            .collect()
    };
    if roles(controller) != roles(setup.robot()) {
        let names = |r: &stiffid_core::Robot| match r.external().filter(|a| !a.is_empty()) {
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
pub(super) fn program_tool(setup: &Setup) -> Tool {
    let adapter = setup.workcell().controller().adapter;
    Tool {
        frame: adapter * setup.tool().frame(),
        payload: setup
            .payload()
            .map(|p| (p.mass, adapter.transform_point(&p.centre.into()).coords)),
    }
}
