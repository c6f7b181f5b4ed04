//! The compensate job: the deflection of every point of a machining path under its process
//! wrench, and the compensated axis angles that cancel it ([`crate::compensate`], Zhang et al.
//! 2021, Eq. 4-6).
//!
//! The path comes from
//! - a path CSV ([`crate::path`]: axis angles or TCP poses, each with its wrench),
//!   compensated as it is read, [`CHUNK`] points at a time, in bounded memory whatever its
//!   length ([`compensate::stream`]); or
//! - a machining program (G-code, KUKA KRL, ABB RAPID, FANUC LS) and a process file: the wrench of
//!   every point from the process, the program written back in its own format with the
//!   compensated targets ([`crate`]).
//!
//! Either way the front end's `sink` gets every point's result in path order, chunk by chunk, as
//! it is computed (to write the CSV rows as they come), and the report holds the summary
//! ([`Summary`]: the largest and mean values, a sample of the points and the ten largest
//! deflections) and, for a program, the compensated program and each segment's force and
//! deflection before and after.

pub mod budget;
pub mod certify;
mod columns;
pub mod configurations;
pub mod document;
pub mod dynamics;
pub mod feasibility;
mod free;
mod input;
mod output;
pub mod scene;
pub mod speed;
pub mod stream;

use crate::app::compensate::document::Summary;
use crate::compensate::{self, Compensated, Compliance, Options, PathPoint, CHUNK};
use crate::dynamics::Dynamics;
use crate::process::Process;
use crate::program::generate::{self, generate, moves, Plan, Settings, Target, Tool};
use crate::program::rename::renamed;
use crate::program::Dialect;
use crate::{self as machining, Language, Program};
use crate::{cell, path};
use input::read_checked;
pub use input::read_program;
use stiffid_core::app::{Warning, WarningKind};
use stiffid_core::model::Parameter;
use stiffid_core::observation::deflection::Frame;
use stiffid_core::robot::ExternalAxes;
use stiffid_core::{Coordinates, Error, Result, Setup};

/// The path to compensate.
pub enum Input<'t> {
    /// A path CSV's text, named `name` (a file's name) in the report and in errors; `frame` is the
    /// wrench's frame in rows without a `frame` value.
    Path {
        /// The file's name.
        name: String,
        /// Its text.
        text: &'t str,
        /// The default frame of the wrenches.
        frame: Frame,
    },
    /// A machining program and the process that cuts it.
    Program {
        /// The program file's name.
        name: String,
        /// Its text.
        text: &'t str,
        /// Its language.
        language: Language,
        /// The process file's name.
        process_name: String,
        /// The process.
        process: Process,
        /// G-code arcs are split into chords of at most this sagitta, m.
        chord_tolerance: f64,
        /// The language of the compensated program: the program's own, or for G-code a robot
        /// program of the compensated targets ([`generate`]).
        output: Language,
        /// The name of the file the compensated program is written to: a generated robot
        /// program is named after its stem (upper case), as the controllers call it.
        out_name: String,
        /// How a generated robot program is written.
        settings: Settings,
    },
}

/// What to compensate and how.
pub struct Request<'a> {
    /// The setup: robot, TCP, springs, joint limits, `[workpiece]` for G-code.
    pub setup: &'a Setup,
    /// The joint compliance (and its covariance, for the standard deviations).
    pub compliance: Compliance,
    /// The path.
    pub input: Input<'a>,
    /// Where inverse kinematics starts, its options, the free tool axis.
    pub options: Options,
}

/// A compensated program.
#[derive(Debug, Clone, PartialEq)]
pub struct ProgramReport {
    /// Its language.
    pub language: Language,
    /// The language of the compensated program.
    pub output: Language,
    /// The process file's name.
    pub process: String,
    /// The program, compensated, in its own format (robot programs with the compensated axis
    /// angles and every other byte as read, G-code with the compensated positions), or a G-code
    /// path as a new robot program of the compensated targets (its main program when it is
    /// split).
    pub text: String,
    /// A generated program's sub-programs, in call order (empty unless it is split): each
    /// written to a file of its name next to the main program's.
    pub subprograms: Vec<generate::File>,
    /// Each segment's force and deflection, in program order.
    pub segments: Vec<Segment>,
    /// Each operation's drilling surge or milling frequencies ([`dynamics::operations`]); empty
    /// without a mass model.
    pub dynamics: Vec<dynamics::OperationDynamics>,
}

/// The points of one program line (a G-code block's arc points, a robot program's target).
#[derive(Debug, Clone, PartialEq)]
pub struct Segment {
    /// The program line, 1-based.
    pub line: u64,
    /// The name of the operation that cuts there; `None` for a rapid move or a block no
    /// operation covers.
    pub operation: Option<String>,
    /// Path points of the segment.
    pub points: usize,
    /// The largest process force on the tool, N.
    pub force: f64,
    /// The largest TCP deflection, uncompensated, m.
    pub deflection_before: f64,
    /// The largest TCP deflection left after compensation (the residual), m.
    pub deflection_after: f64,
    /// With a compliance covariance: the largest standard deviation of the deflection's length,
    /// m.
    pub deflection_std: Option<f64>,
}

/// What the compensate job found.
#[derive(Debug, Clone)]
pub struct Report {
    /// The path's (or program's) name.
    pub input: String,
    /// Where the springs sit.
    pub springs: Coordinates,
    /// The parameters of the setup's model (drives first), in the order of `compliance`.
    pub parameters: Vec<Parameter>,
    /// The compliance used.
    pub compliance: Compliance,
    /// The level of the deflection's prediction intervals, when the compliance carries a
    /// prediction calibration ([`stiffid_core::model::prediction`]).
    pub prediction_level: Option<f64>,
    /// The free variables and what they minimise ([`Options::free`]).
    pub free: compensate::FreeVariables,
    /// With a free variable: the feasibility checks of its moved postures and the states each
    /// removed.
    pub feasibility: Option<feasibility::Feasibility>,
    /// The axes' speed limits at the program's feed: whether checked, each axis's highest
    /// share of its largest speed at the path's own values and at those chosen.
    pub speed_limits: speed::SpeedLimits,
    /// With a free variable: the levels of its grid's refinement ([`Options::refine`]).
    pub refine: Option<usize>,
    /// The largest and mean values along the path, a sample, the ten largest deflections.
    pub summary: Summary,
    /// With a program: the compensated program and its segments.
    pub program: Option<ProgramReport>,
    /// With [`Options::map`]: the map of the free variable with the rotations chosen
    /// ([`compensate::Map`]).
    pub map: Option<compensate::Map>,
    /// With [`super::FreeVariables::configuration`]: every configuration of the arm evaluated over the
    /// path, the one chosen ([`compensate::Configurations`]).
    pub configurations: Option<compensate::Configurations>,
    /// Points without a process force (plunges, rapid moves, blocks no operation covers).
    pub warnings: Vec<Warning>,
}

/// Runs the compensate job; `sink(first, points, results, dynamics)` gets every chunk of points
/// (the 0-based index of its first point, the points, their results, their drilling surge and
/// milling frequencies: [`crate::dynamics::program`] for a program with a mass model,
/// else empty values) in path order as it is computed.
///
/// # Errors
/// [`Error::InvalidField`] for options outside their limits ([`Options::validate`],
/// [`Settings::validate`]), a setup without `[tool] tcp_mm` (`tool.tcp_mm`), a generated robot
/// program's name, tool or file its controller does not take ([`generate`]); errors about
/// the path as [`Error::Input`] naming the path or program file: those of
/// [`path::points`], [`compensate::stream`], [`machining::read`] and [`machining::compensate`]
/// (a malformed program, a point outside the joint limits or whose compensation changes the
/// configuration, naming the line); and those of `sink`.
pub fn run<E, F>(request: Request<'_>, mut sink: F) -> std::result::Result<Report, E>
where
    E: From<Error>,
    F: FnMut(usize, &[PathPoint], &[Compensated], &[Dynamics]) -> std::result::Result<(), E>,
{
    let Request {
        setup,
        compliance,
        input,
        options,
    } = request;
    options.validate()?;
    if !setup.tcp_given() {
        return Err(Error::InvalidField {
            field: "tool.tcp_mm".into(),
            message: format!("missing in setup {}: compensation moves the cutting tool's centre point, which the setup must give ([tool] tcp_mm); measuring point 1 is a measuring target, not the tool", setup.name()),
        }
        .into());
    }
    let read = read_checked(setup, &input, &options)?;
    let (options, mut speeds) = speed::prepare(setup, &input, read.as_ref(), options)?;
    let external = options.free.frees_external();
    let free = options.free.tool_rotation.is_some() || options.free.lead_tilt.is_some() || external;
    let axes = setup.robot().external();
    let mut summary = Summary::new(free, options.level, axes);
    summary.budget.limit = options.max_error;
    if options.free.lead_tilt.is_some() {
        summary = summary.with_lean();
    }
    let mut chosen: Vec<compensate::ChosenValues> = Vec::new();
    let mut add = |first: usize, points: &[PathPoint], results: &[Compensated], d: &[Dynamics]| {
        for (k, (p, r)) in points.iter().zip(results).enumerate() {
            // The values the compensation chose (a free station or positioner), else the path's own.
            let e = match r.external.is_empty() {
                true => &p.external,
                false => &r.external,
            };
            summary.add(first + k, p.line, r, e);
            speeds.add(first + k, p, r);
            if options.map {
                chosen.push(compensate::ChosenValues::of(r, &p.external));
            }
        }
        sink(first, points, results, d)
    };
    let mut mapped: Option<Vec<PathPoint>> = None;
    let mut chosen_configurations: Option<compensate::Configurations> = None;
    let (name, program, warnings) = match input {
        Input::Path { name, text, frame } => {
            let robot = setup.arm().robot();
            let placed = |text| -> Result<_> {
                let points = path::points(text, frame, robot.external())?;
                Ok(points.map(|p| p.and_then(|p| cell::on_carriage(robot, p))))
            };
            if options.map {
                let points = placed(text).map_err(|e| in_input(&name, e))?;
                let points: Result<Vec<PathPoint>> = points.collect();
                mapped = Some(points.map_err(|e| in_input(&name, e))?);
            }
            if options.free.configuration.is_some() {
                let points = placed(text).map_err(|e| in_input(&name, e))?;
                let points: Result<Vec<PathPoint>> = points.collect();
                let points = points.map_err(|e| in_input(&name, e))?;
                let (results, c) =
                    compensate::path_configurations(setup.arm(), &compliance, &points, &options)
                        .map_err(|e| in_input(&name, e))?;
                let results = cell::path_to_cell(robot, &points, results);
                for (k, (p, r)) in points.chunks(CHUNK).zip(results.chunks(CHUNK)).enumerate() {
                    add(k * CHUNK, p, r, &vec![Dynamics::default(); p.len()])?;
                }
                if let Some(m) = mapped.as_mut() {
                    *m = c.in_chosen(setup.arm(), m);
                }
                chosen_configurations = Some(c);
            } else if !external {
                let points = placed(text).map_err(|e| in_input(&name, e))?;
                let mut first = 0;
                compensate::stream(setup.arm(), &compliance, points, &options, |p, r| {
                    let r = match robot.external() {
                        None => std::borrow::Cow::Borrowed(r),
                        Some(_) => {
                            std::borrow::Cow::Owned(cell::path_to_cell(robot, p, r.to_vec()))
                        }
                    };
                    add(first, p, &r, &vec![Dynamics::default(); p.len()])
                        .map_err(Failure::Sink)?;
                    first += p.len();
                    Ok(())
                })
                .map_err(|f: Failure<E>| f.into_error(&name))?;
            } else {
                let points = path::points(text, frame, robot.external());
                let points: Result<Vec<PathPoint>> = points.and_then(Iterator::collect);
                let points = points.map_err(|e| in_input(&name, e))?;
                on_track(setup, &compliance, &points, &options, &mut add)
                    .map_err(|f: Failure<E>| f.into_error(&name))?;
            }
            (name, None, Vec::new())
        }
        Input::Program {
            name,
            language,
            process_name,
            process,
            chord_tolerance,
            output,
            out_name,
            settings,
            ..
        } => {
            let Some(program) = read else {
                unreachable!("read_checked reads every program")
            };
            // Every name and setting of the output before the compensation, which can be long.
            let written_name = written_name(
                &program,
                output,
                &out_name,
                (&settings, setup.robot().external()),
            )?;
            // A G-code program is written for the controller's kinematics.
            let controller = match (&program, output) {
                (Program::GCode(_), Language::GCode) => setup.controller_robot()?,
                _ => setup.robot(),
            };
            let at = (setup.arm(), setup.workpiece(), &compliance);
            let compensated =
                machining::compensate_for(controller, at, &program, &process, &options)
                    .map_err(|e| in_input(&name, e))?;
            output::check_runs(compensated.configurations.as_ref(), output)?;
            if options.map {
                mapped = Some(match &compensated.configurations {
                    Some(c) => c.in_chosen(setup.arm(), &compensated.points),
                    None => compensated.points.clone(),
                });
            }
            chosen_configurations = compensated.configurations.clone();
            let (masses, mass_warning) =
                stiffid_core::observation::dynamics::mass_model(setup.arm());
            let point_dynamics = match &masses {
                Some(m) => crate::dynamics::program(
                    setup.arm(),
                    m,
                    &compliance,
                    &process,
                    &compensated.results,
                    &compensated.operations,
                ),
                None => vec![Dynamics::default(); compensated.points.len()],
            };
            for (k, ((p, r), d)) in compensated
                .points
                .chunks(CHUNK)
                .zip(compensated.results.chunks(CHUNK))
                .zip(point_dynamics.chunks(CHUNK))
                .enumerate()
            {
                add(k * CHUNK, p, r, d)?;
            }
            let mut warnings: Vec<Warning> = compensated
                .warnings
                .iter()
                .map(|w| Warning::new(WarningKind::NoForce, w.clone()))
                .collect();
            warnings.extend(mass_warning);
            // Without masses no point has dynamics: the document's list is empty (its docs).
            let (operation_dynamics, chatter) = match &masses {
                Some(_) => dynamics::operations(
                    &process,
                    &compensated.points,
                    &compensated.operations,
                    &point_dynamics,
                ),
                None => (Vec::new(), Vec::new()),
            };
            warnings.extend(chatter);
            let (text, subprograms) = match (output, &program) {
                (Language::Robot(d), Program::GCode(g)) => {
                    let written = write_robot_program(
                        setup,
                        d,
                        &compensated,
                        &g.points,
                        (
                            &written_name.unwrap_or_default(),
                            &settings,
                            chord_tolerance,
                        ),
                    )
                    .map_err(|e| in_input(&name, e))?;
                    warnings.extend(
                        written
                            .warnings
                            .into_iter()
                            .map(|w| Warning::new(WarningKind::Feed, w)),
                    );
                    let bounds: Vec<f64> =
                        compensated.results.iter().map(|r| r.budget.bound).collect();
                    let texts: Vec<String> = written.files.iter().map(|f| f.text.clone()).collect();
                    let texts = certify::generated(d, &texts, &bounds, options.level);
                    let mut files = (written.files.into_iter().zip(texts))
                        .map(|(f, text)| generate::File { text, ..f });
                    let main = files.next().map(|f| f.text).unwrap_or_default();
                    (main, files.collect())
                }
                (Language::Robot(d), _) => {
                    let text = match &written_name {
                        Some(to) => renamed(&compensated.program, d, to),
                        None => compensated.program.clone(),
                    };
                    let lines: Vec<(u64, f64)> = (compensated.points.iter())
                        .zip(&compensated.results)
                        .map(|(p, r)| (p.line, r.budget.bound))
                        .collect();
                    let text = certify::at_lines(d, &text, &lines, options.level);
                    (text, Vec::new())
                }
                _ => (compensated.program.clone(), Vec::new()),
            };
            let report = ProgramReport {
                language,
                output,
                process: process_name,
                segments: segments(&compensated, &process),
                dynamics: operation_dynamics,
                text,
                subprograms,
            };
            (name, Some(report), warnings)
        }
    };
    if let Some(max_error) = options.max_error {
        summary.budget.refuse_above(max_error, options.level)?;
    }
    let map = match &mapped {
        Some(points) => {
            let mut in_chosen = options.clone();
            in_chosen.q0 = (chosen_configurations.as_ref())
                .and_then(compensate::Configurations::start)
                .unwrap_or(options.q0);
            in_chosen.free.configuration = None;
            // A program's wrenches hold the tool's weight (machining::compensate).
            let weighted =
                program.is_some() && crate::weight::tool_load(setup.arm(), &compliance).is_some();
            let at = (&in_chosen, setup.cell());
            let map = compensate::map(setup.arm(), &compliance, points, at, (&chosen, weighted));
            Some(map.map_err(|e| in_input(&name, e))?)
        }
        None => None,
    };
    let mut warnings = warnings;
    if let Some(c) = &chosen_configurations {
        (c.warnings.iter())
            .for_each(|w| warnings.push(Warning::new(WarningKind::Configuration, w.clone())));
    }
    warnings.extend(speeds.warning());
    warnings.extend(summary.stop_warning(options.max_iterations));
    warnings.extend(summary.region_warnings(&compliance.region));
    Ok(Report {
        input: name,
        springs: setup.springs(),
        free: options.free,
        feasibility: feasibility::Feasibility::new(&options, summary.removed),
        speed_limits: speeds.document(),
        refine: free.then_some(options.refine),
        parameters: setup.model().parameters(),
        prediction_level: compliance.prediction.as_ref().map(|_| options.level),
        compliance,
        summary,
        program,
        map,
        configurations: chosen_configurations,
        warnings,
    })
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
fn written_name(
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
    points: &[crate::gcode::Point],
    (name, settings, chord_tolerance): (&str, &Settings, f64),
) -> Result<generate::Written> {
    use rayon::prelude::*;
    let moves = moves(points, settings.max_tcp_speed)?;
    let tool = setup.tool();
    // Joint targets are exact in any kinematics; Cartesian ones are the controller's.
    let controller = match settings.targets {
        generate::Targets::Joint => setup.robot(),
        generate::Targets::Cartesian => cell_controller(setup)?,
    };
    let targets: Vec<Target> = (compensated.results.par_iter())
        .zip(&compensated.points)
        .map(|(r, p)| {
            // The values the compensation chose (a free station), else the program's.
            let e = match r.external.is_empty() {
                true => p.external.as_slice(),
                false => r.external.as_slice(),
            };
            Target::at(controller, &tool.tcp, &r.q_compensated, e)
        })
        .collect();
    let plan = Plan {
        dialect,
        name,
        targets: &targets,
        moves: &moves,
        tool: program_tool(setup),
        work: setup.workpiece().copied().unwrap_or_default(),
        external: setup.robot().external(),
        world: setup.workcell().controller().world,
        approximation: chord_tolerance,
        settings: *settings,
    };
    generate(&plan)
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
/// `[robot_flange]` adapter included): the setup's TCP, mass and centre of mass.
fn program_tool(setup: &Setup) -> Tool {
    let adapter = setup.workcell().controller().adapter;
    Tool {
        frame: adapter * nalgebra::Translation3::from(setup.tool().tcp),
        payload: setup
            .payload()
            .map(|p| (p.mass, adapter.transform_point(&p.centre.into()).coords)),
    }
}

/// A path file's `points` (cell frame) of a robot on a track compensated with the station or
/// the positioner free ([`compensate::path_on_track`]), given to `add` in chunks of [`CHUNK`] in
/// the cell frame.
fn on_track<E, F>(
    setup: &Setup,
    compliance: &Compliance,
    points: &[PathPoint],
    options: &Options,
    add: &mut F,
) -> std::result::Result<(), Failure<E>>
where
    F: FnMut(usize, &[PathPoint], &[Compensated], &[Dynamics]) -> std::result::Result<(), E>,
{
    let robot = setup.arm().robot();
    let results = compensate::path_on_track(setup.arm(), compliance, points, options)?;
    let results = cell::path_to_cell(robot, points, results);
    for (k, (p, r)) in points.chunks(CHUNK).zip(results.chunks(CHUNK)).enumerate() {
        add(k * CHUNK, p, r, &vec![Dynamics::default(); p.len()]).map_err(Failure::Sink)?;
    }
    Ok(())
}

/// A failure of the streamed path: the library's, or the sink's.
enum Failure<E> {
    Library(Error),
    Sink(E),
}

impl<E> From<Error> for Failure<E> {
    fn from(e: Error) -> Self {
        Failure::Library(e)
    }
}

impl<E: From<Error>> Failure<E> {
    fn into_error(self, name: &str) -> E {
        match self {
            Failure::Library(e) => in_input(name, e).into(),
            Failure::Sink(e) => e,
        }
    }
}

/// `error` placed in the input `name`; an option's error (the free tool axis' grid, the program's
/// name) as it is.
fn in_input(name: &str, error: Error) -> Error {
    match error {
        e @ Error::InvalidOption { .. } => e,
        e => Error::Input {
            source_name: name.to_string(),
            error: Box::new(e),
        },
    }
}

/// The segments of a compensated program: its points grouped by line, in order.
fn segments(c: &machining::Report, process: &Process) -> Vec<Segment> {
    let mut out: Vec<Segment> = Vec::new();
    for ((p, r), op) in c.points.iter().zip(&c.results).zip(&c.operations) {
        let force = r.wrench.fixed_rows::<3>(0).norm();
        let before = r.deflection.fixed_rows::<3>(0).norm();
        let std = r.translation_norm_std;
        match out.last_mut() {
            Some(s) if s.line == p.line => {
                s.points += 1;
                s.force = s.force.max(force);
                s.deflection_before = s.deflection_before.max(before);
                s.deflection_after = s.deflection_after.max(r.residual_position);
                s.deflection_std = s.deflection_std.zip(std).map(|(a, b)| a.max(b));
            }
            _ => out.push(Segment {
                line: p.line,
                operation: op.map(|i| process.operations[i].name.clone()),
                points: 1,
                force,
                deflection_before: before,
                deflection_after: r.residual_position,
                deflection_std: std,
            }),
        }
    }
    out
}
