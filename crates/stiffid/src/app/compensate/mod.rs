//! The compensate job: the deflection of every point of a machining path under its process
//! wrench, and the compensated axis angles that cancel it ([`stiffid_machining::compensate`](mod@stiffid_machining::compensate), Zhang et al.
//! 2021, Eq. 4-6).
//!
//! The path comes from
//! - a path CSV ([`stiffid_machining::path`]: axis angles or TCP poses, each with its wrench),
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
mod failure;
pub(crate) mod feasibility;
mod free;
mod given;
mod input;
mod output;
pub mod ranking;
pub mod resolution;
pub mod scene;
mod segments;
pub use segments::{ProgramReport, Segment};
pub mod speed;
pub mod stream;
mod written;

use crate::app::compensate::document::{Names, Summary};
use crate::app::{Warning, WarningKind};
use failure::{in_input, Failure};
pub use given::Given;
use input::{
    called_files, check_tcp, copied_warning, encoding_warning, held_lines, held_warning,
    left_warning, no_length_offset, notes_warning, own_motion, read_checked, uncoupled_ls,
    unplaced_g53, unstated_units, zero_rotary,
};
pub use input::{read_program, read_program_in};
use stiffid_core::io::Encoding;
use stiffid_core::model::Parameter;
use stiffid_core::observation::deflection::Frame;
use stiffid_core::{Coordinates, Error, Result, Setup};
use stiffid_machining::compensate::{self, Compensated, Compliance, Options, PathPoint, CHUNK};
use stiffid_machining::dynamics::Dynamics;
use stiffid_machining::process::Process;
use stiffid_machining::program::generate::compensated::{gcode_controller, written_name};
use stiffid_machining::program::generate::{self, generate, Settings};
use stiffid_machining::program::rename::renamed;
use stiffid_machining::{self as machining, Language, Program};
use stiffid_machining::{cell, path};
use written::generated;

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
        /// The text of its data file, for a KRL `.src` whose `.dat` is beside it (same stem,
        /// same folder): its points and frame data are read from it, and its targets there
        /// written back into a compensated copy ([`ProgramReport::data`]).
        data: Option<&'t str>,
        /// Its language.
        language: Language,
        /// The process file's name.
        process_name: String,
        /// The process.
        process: Process,
        /// G-code arcs are split into chords of at most this sagitta, m.
        chord_tolerance: f64,
        /// The language of the compensated program: the program's own, or for G-code a robot
        /// program of the compensated targets ([`generate()`]).
        output: Language,
        /// The name of the file the compensated program is written to: a generated robot
        /// program is named after its stem (upper case), as the controllers call it.
        out_name: String,
        /// How a generated robot program is written.
        settings: Settings,
        /// The encoding its files were read in ([`stiffid_core::io::program_texts`]), which the
        /// compensated program is written in ([`ProgramReport::encoding`]).
        encoding: Encoding,
        /// How it is read beyond its own files: its controller backup's, and whether refused
        /// motions are left as found.
        reading: stiffid_machining::program::Reading<'t>,
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
    /// The names of the inputs and outputs the document states: the setup as the user named it,
    /// the stiffness file, the files the front end writes.
    pub names: Names,
}

/// The compensate job's report, which is its document (serialised through
/// [`document::Document`]; without the points: the sink receives them).
pub(crate) type Outcome = crate::app::Outcome<Report>;

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
    /// With [`stiffid_machining::compensate::FreeVariables::configuration`]: every configuration of the arm evaluated over the
    /// path, the one chosen ([`compensate::Configurations`]).
    pub configurations: Option<compensate::Configurations>,
    /// With a stiffness file whose `model_form` holds a recommended model other than its own:
    /// whether the two rank the path's points alike ([`ranking`]).
    pub model_ranking: Option<ranking::RankingDocument>,
    /// Points without a process force (plunges, rapid moves, blocks no operation covers).
    pub warnings: Vec<Warning>,
    /// The names of the inputs and outputs the document states ([`Request::names`]).
    pub names: Names,
    /// The document's points: the rows a front end that returns the document whole keeps as
    /// the sink receives them ([`stream::Rows`]); empty from [`run`], and where the front end
    /// streams them ([`document::Document::write_json`]).
    pub points: Vec<document::Row>,
}

impl Report {
    /// The document this report is written as (`stiffid compensate --json`, the report's
    /// `summary.json`, Python's `stiffid.compensate`'s `document`), to read: what the command's
    /// text and report print.
    pub fn document(&self) -> document::Document<'_> {
        document::Document::new(self)
    }
}

impl serde::Serialize for Report {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        self.document().serialize(s)
    }
}

/// Runs the compensate job; `sink(first, points, results, dynamics)` gets every chunk of points
/// (the 0-based index of its first point, the points, their results, their drilling surge and
/// milling frequencies: [`stiffid_machining::dynamics::program`] for a program with a mass model,
/// else empty values) in path order as it is computed.
///
/// # Errors
/// [`Error::InvalidField`] for options outside their limits ([`Options::validate`],
/// [`Settings::validate`]), a setup without `[tool] tcp_mm` (`tool.tcp_mm`), a generated robot
/// program's name, tool or file its controller does not take ([`generate()`]); errors about
/// the path as [`Error::Input`] naming the path or program file: those of
/// [`path::points`], [`compensate::stream`], [`machining::read`] and [`machining::compensate()`]
/// (a malformed program, a point outside the joint limits or whose compensation changes the
/// configuration, naming the line); and those of `sink`.
pub fn run<E, F>(request: Request<'_>, sink: F) -> std::result::Result<Outcome, E>
where
    E: From<Error>,
    F: FnMut(usize, &[PathPoint], &[Compensated], &[Dynamics]) -> std::result::Result<(), E>,
{
    Ok(Outcome {
        report: find(request, sink)?,
        document: crate::app::Itself,
    })
}

/// What [`run`] finds.
fn find<E, F>(request: Request<'_>, mut sink: F) -> std::result::Result<Report, E>
where
    E: From<Error>,
    F: FnMut(usize, &[PathPoint], &[Compensated], &[Dynamics]) -> std::result::Result<(), E>,
{
    let Request {
        setup,
        compliance,
        input,
        options,
        names,
    } = request;
    options.validate()?;
    check_tcp(setup)?;
    let read = read_checked(setup, &input, &options)?;
    let (options, speeds) = speed::prepare(setup, &input, read.as_ref(), options)?;
    let mut tally = Tally::new(setup, &options, speeds);
    tally.ranking = ranking::Ranking::new(setup.arm(), compliance.model_form.as_ref());
    let units = read.as_ref().and_then(unstated_units);
    let g53 = read.as_ref().and_then(unplaced_g53);
    let length = read.as_ref().and_then(no_length_offset);
    let rotary = read.as_ref().and_then(zero_rotary);
    let coupling = read.as_ref().and_then(|p| uncoupled_ls(setup, p));
    let mut outcome = {
        let mut add = |first: usize, p: &[PathPoint], r: &[Compensated], d: &[Dynamics]| {
            tally.add(setup, first, p, r, options.map);
            sink(first, p, r, d)
        };
        match (input, read) {
            (Input::Path { name, text, frame }, _) => {
                path_job(setup, &compliance, (name, text, frame), &options, &mut add)?
            }
            (input @ Input::Program { .. }, Some(program)) => {
                program_job(setup, &compliance, (input, program), &options, &mut add)?
            }
            (Input::Program { .. }, None) => unreachable!("read_checked reads every program"),
        }
    };
    outcome.warnings.extend(units);
    outcome.warnings.extend(g53);
    outcome.warnings.extend(length);
    outcome.warnings.extend(rotary);
    outcome.warnings.extend(coupling);
    Ok(finish(setup, (compliance, names), options, tally, outcome)?)
}

/// Whether the compensation moves a free variable (the tool's rotation, its lean, an external
/// axis).
fn frees(options: &Options) -> bool {
    let free = &options.free;
    free.tool_rotation().is_some() || free.lead_tilt().is_some() || free.frees_external()
}

/// What the job gathers point by point as they are computed: the summary, the speeds, the
/// values chosen (for the map), the two models' deflections (with a recommended model).
struct Tally<'a> {
    summary: Summary,
    speeds: speed::Tracker<'a>,
    chosen: Vec<compensate::ChosenValues>,
    ranking: Option<ranking::Ranking>,
}

impl<'a> Tally<'a> {
    fn new(setup: &Setup, options: &Options, speeds: speed::Tracker<'a>) -> Self {
        let mut summary = Summary::new(frees(options), options.level, setup.robot().external());
        summary.budget.limit = options.max_error;
        if options.free.lead_tilt().is_some() {
            summary = summary.with_lean();
        }
        Tally {
            summary,
            speeds,
            chosen: Vec::new(),
            ranking: None,
        }
    }

    /// The points from the 0-based `first` and their results; `map`: keep the values chosen.
    fn add(
        &mut self,
        setup: &Setup,
        first: usize,
        points: &[PathPoint],
        results: &[Compensated],
        map: bool,
    ) {
        for (k, (p, r)) in points.iter().zip(results).enumerate() {
            // The values the compensation chose (a free station or positioner), else the path's own.
            let e = match r.external.is_empty() {
                true => &p.external,
                false => &r.external,
            };
            self.summary.add(first + k, p.line, r, e);
            self.speeds.add(first + k, p, r);
            if let Some(ranking) = &mut self.ranking {
                ranking.add(setup.arm(), p.line, r);
            }
            if map {
                self.chosen
                    .push(compensate::ChosenValues::of(r, &p.external));
            }
        }
    }
}

/// What a path's or a program's job gives besides the points: the input's name, the program,
/// the warnings, the points to map, the configurations evaluated.
struct Computed {
    name: String,
    program: Option<ProgramReport>,
    warnings: Vec<Warning>,
    mapped: Option<Vec<PathPoint>>,
    configurations: Option<compensate::Configurations>,
}

impl Computed {
    fn named(name: String) -> Self {
        Computed {
            name,
            program: None,
            warnings: Vec::new(),
            mapped: None,
            configurations: None,
        }
    }
}

/// Gives `points` and their `results` (and dynamics, else none) to `add` in chunks of [`CHUNK`].
fn feed<E, A>(
    points: &[PathPoint],
    results: &[Compensated],
    dynamics: Option<&[Dynamics]>,
    add: &mut A,
) -> std::result::Result<(), E>
where
    A: FnMut(usize, &[PathPoint], &[Compensated], &[Dynamics]) -> std::result::Result<(), E>,
{
    for (k, (p, r)) in points.chunks(CHUNK).zip(results.chunks(CHUNK)).enumerate() {
        match dynamics {
            Some(d) => add(k * CHUNK, p, r, &d[k * CHUNK..k * CHUNK + p.len()])?,
            None => add(k * CHUNK, p, r, &vec![Dynamics::default(); p.len()])?,
        }
    }
    Ok(())
}

/// A path file's job: its points compensated in the configuration chosen, streamed, or with a
/// free station or positioner ([`on_track`]).
fn path_job<E, A>(
    setup: &Setup,
    compliance: &Compliance,
    (name, text, frame): (String, &str, Frame),
    options: &Options,
    add: &mut A,
) -> std::result::Result<Computed, E>
where
    E: From<Error>,
    A: FnMut(usize, &[PathPoint], &[Compensated], &[Dynamics]) -> std::result::Result<(), E>,
{
    let robot = setup.arm().robot();
    let placed = |text| -> Result<_> {
        let points = path::points(text, frame, robot.external())?;
        Ok(points.map(|p| p.and_then(|p| cell::on_carriage(robot, p))))
    };
    let all = || placed(text).and_then(Iterator::collect::<Result<Vec<PathPoint>>>);
    let mut out = Computed::named(name);
    if options.map {
        out.mapped = Some(all().map_err(|e| in_input(&out.name, e))?);
    }
    if options.free.configuration().is_some() {
        let points = all().map_err(|e| in_input(&out.name, e))?;
        let (results, c) =
            compensate::path_configurations(setup.arm(), compliance, &points, options)
                .map_err(|e| in_input(&out.name, e))?;
        feed(
            &points,
            &cell::path_to_cell(robot, &points, results),
            None,
            add,
        )?;
        if let Some(m) = out.mapped.as_mut() {
            *m = c.in_chosen(setup.arm(), m);
        }
        out.configurations = Some(c);
    } else if !options.free.frees_external() {
        let points = placed(text).map_err(|e| in_input(&out.name, e))?;
        let mut first = 0;
        compensate::stream(setup.arm(), compliance, points, options, |p, r| {
            let r = match robot.external() {
                None => std::borrow::Cow::Borrowed(r),
                Some(_) => std::borrow::Cow::Owned(cell::path_to_cell(robot, p, r.to_vec())),
            };
            add(first, p, &r, &vec![Dynamics::default(); p.len()]).map_err(Failure::Sink)?;
            first += p.len();
            Ok(())
        })
        .map_err(|f: Failure<E>| f.into_error(&out.name))?;
    } else {
        let points = path::points(text, frame, robot.external());
        let points: Result<Vec<PathPoint>> = points.and_then(Iterator::collect);
        let points = points.map_err(|e| in_input(&out.name, e))?;
        on_track(setup, compliance, &points, options, add)
            .map_err(|f: Failure<E>| f.into_error(&out.name))?;
    }
    Ok(out)
}

/// A program's job: every name and setting of the output checked, the program compensated, its
/// points' dynamics, the program written.
fn program_job<E, A>(
    setup: &Setup,
    compliance: &Compliance,
    (input, program): (Input<'_>, Program),
    options: &Options,
    add: &mut A,
) -> std::result::Result<Computed, E>
where
    E: From<Error>,
    A: FnMut(usize, &[PathPoint], &[Compensated], &[Dynamics]) -> std::result::Result<(), E>,
{
    let Input::Program {
        name,
        language,
        process_name,
        process,
        chord_tolerance,
        output,
        out_name,
        settings,
        encoding,
        text: source,
        data: source_data,
        ..
    } = input
    else {
        unreachable!("a program's input")
    };
    // Every name and setting of the output before the compensation, which can be long.
    let cell = setup.robot().external();
    let settings = written::with_setup(setup, settings);
    let written_name = written_name(&program, output, &out_name, (&settings, cell))?;
    // A G-code program is written for the controller's kinematics.
    let (controller, assumed) = match (&program, output) {
        (Program::GCode(_), Language::GCode) => gcode_controller(setup)?,
        _ => (setup.robot(), None),
    };
    let at = (setup.arm(), setup.workpiece(), compliance);
    let compensated = machining::compensate_for(controller, at, &program, &process, options)
        .map_err(|e| in_input(&name, e))?;
    output::check_runs(compensated.configurations.as_ref(), output)?;
    let rounded = resolution::check(setup, (&program, output), &compensated.results)?;
    let mut out = Computed::named(name);
    out.mapped = options.map.then(|| match &compensated.configurations {
        Some(c) => c.in_chosen(setup.arm(), &compensated.points),
        None => compensated.points.clone(),
    });
    out.configurations = compensated.configurations.clone();
    let (dynamics, warnings) = program_dynamics(setup, compliance, &process, &compensated, add)?;
    out.warnings = warnings;
    out.warnings.extend(assumed.into_iter().chain(rounded));
    let mut data = compensated.data.as_ref().map(|d| match &written_name {
        Some(to) => stiffid_machining::program::rename::renamed_data(d, to),
        None => d.clone(),
    });
    let (text, subprograms) = match (output, &program) {
        (Language::Robot(d), Program::GCode(g)) => {
            let how = (written_name.unwrap_or_default(), settings, chord_tolerance);
            let written = generated(setup, d, &compensated, g, (how, options.level));
            let (main, subprograms, warnings) = written.map_err(|e| in_input(&out.name, e))?;
            out.warnings.extend(warnings);
            data = main.data;
            (main.text, subprograms)
        }
        (Language::Robot(d), _) => {
            let text = match &written_name {
                Some(to) => renamed(&compensated.program, d, to),
                None => compensated.program.clone(),
            };
            let held = held_lines(&program);
            out.warnings.extend(held_warning(&held));
            out.warnings.extend(left_warning(&program));
            out.warnings.extend(notes_warning(&program));
            out.warnings.extend(copied_warning(&program));
            let own = |i: usize| own_motion(&program, i);
            let lines: Vec<(u64, f64)> = (compensated.points.iter())
                .zip(&compensated.results)
                .enumerate()
                .filter(|(i, (p, _))| !held.contains(&p.line) && own(*i))
                .map(|(_, (p, r))| (p.line, r.budget.bound))
                .collect();
            let lines = certify::moved(source, &text, &lines);
            (
                certify::at_lines(d, &text, &lines, options.level),
                called_files(&compensated.called),
            )
        }
        _ => (compensated.program.clone(), Vec::new()),
    };
    let report = ProgramReport {
        language,
        output,
        process: process_name,
        segments: segments::segments(&compensated, &process),
        dynamics,
        text,
        subprograms,
        data,
        encoding,
    };
    report.check_encoding(&out_name)?;
    out.warnings
        .extend(encoding_warning(&out.name, encoding, (source, source_data)));
    out.program = Some(report);
    Ok(out)
}

/// A compensated program's points given to `add` with their drilling surge and milling
/// frequencies (with a mass model), each operation's dynamics and the warnings (points without
/// a force, no mass model, chatter).
fn program_dynamics<E, A>(
    setup: &Setup,
    compliance: &Compliance,
    process: &Process,
    compensated: &machining::Report,
    add: &mut A,
) -> std::result::Result<(Vec<dynamics::OperationDynamics>, Vec<Warning>), E>
where
    A: FnMut(usize, &[PathPoint], &[Compensated], &[Dynamics]) -> std::result::Result<(), E>,
{
    let c = compensated;
    let (masses, mass_warning) = stiffid_core::observation::dynamics::mass_model(setup.arm());
    let point_dynamics = match &masses {
        Some(m) => stiffid_machining::dynamics::program(
            setup.arm(),
            m,
            compliance,
            process,
            &c.results,
            &c.operations,
        ),
        None => vec![Dynamics::default(); c.points.len()],
    };
    feed(&c.points, &c.results, Some(&point_dynamics), add)?;
    let mut warnings: Vec<Warning> = (c.warnings.iter())
        .map(|w| Warning::new(WarningKind::NoForce, w.clone()))
        .collect();
    warnings.extend(mass_warning);
    // Without masses no point has dynamics: the document's list is empty (its docs).
    let (operations, chatter) = match &masses {
        Some(_) => dynamics::operations(process, &c.points, &c.operations, &point_dynamics),
        None => (Vec::new(), Vec::new()),
    };
    warnings.extend(chatter);
    Ok((operations, warnings))
}

/// The report, its inputs and outputs named by `names`: the largest error refused above
/// `--max-error-mm`, the map of the free variable, the warnings of the configurations, the
/// speeds, the solver's stops and the compliance's region.
///
/// # Errors
/// Those of [`budget::Worst::refuse_above`] and [`compensate::map`].
fn finish(
    setup: &Setup,
    (compliance, names): (Compliance, Names),
    options: Options,
    tally: Tally<'_>,
    outcome: Computed,
) -> Result<Report> {
    let Tally {
        summary,
        speeds,
        chosen,
        ranking,
    } = tally;
    if let Some(max_error) = options.max_error {
        summary.budget.refuse_above(max_error, options.level)?;
    }
    let map = map_of(setup, &compliance, &options, &outcome, &chosen)?;
    let Computed {
        name,
        program,
        mut warnings,
        configurations,
        ..
    } = outcome;
    if let Some(c) = &configurations {
        (c.warnings.iter())
            .for_each(|w| warnings.push(Warning::new(WarningKind::Configuration, w.clone())));
    }
    warnings.extend(speeds.warning());
    warnings.extend(summary.stop_warning(options.max_iterations));
    warnings.extend(summary.region_warnings(&compliance.region));
    let (model_ranking, disagree) = ranking.map(ranking::Ranking::finish).unzip();
    warnings.extend(disagree.flatten());
    Ok(Report {
        input: name,
        springs: setup.springs(),
        feasibility: feasibility::Feasibility::new(&options, summary.removed),
        speed_limits: speeds.document(),
        refine: frees(&options).then_some(options.refine),
        free: options.free,
        parameters: setup.model().parameters(),
        prediction_level: compliance.prediction.as_ref().map(|_| options.level),
        compliance,
        summary,
        program,
        map,
        configurations,
        model_ranking,
        warnings,
        names,
        points: Vec::new(),
    })
}

/// With [`Options::map`]: the map of the free variable over the points kept, in the
/// configuration chosen, with the values chosen.
///
/// # Errors
/// Those of [`compensate::map`], placed in the input.
fn map_of(
    setup: &Setup,
    compliance: &Compliance,
    options: &Options,
    outcome: &Computed,
    chosen: &[compensate::ChosenValues],
) -> Result<Option<compensate::Map>> {
    let Some(points) = &outcome.mapped else {
        return Ok(None);
    };
    let mut in_chosen = options.clone();
    in_chosen.q0 = (outcome.configurations.as_ref())
        .and_then(compensate::Configurations::start)
        .unwrap_or(options.q0);
    in_chosen.free = in_chosen
        .free
        .keeping(|f| !matches!(f, compensate::Free::Configuration(_)));
    // A program's wrenches hold the tool's weight (machining::compensate).
    let weighted = outcome.program.is_some()
        && stiffid_machining::weight::tool_load(setup.arm(), compliance).is_some();
    let at = (&in_chosen, setup.cell());
    let map = compensate::map(setup.arm(), compliance, points, at, (chosen, weighted));
    map.map(Some).map_err(|e| in_input(&outcome.name, e))
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
