//! `stiffid compensate`: arguments to a request of [`stiffid::app::compensate`], the rows of its
//! CSV and JSON document ([`stiffid::app::compensate::document`]) written as the job computes them,
//! then the compensated program, the text or JSON, and the report.

mod files;
mod text;

use crate::commands::common::choice;
use crate::commands::common::{Common, Stiffness};
use crate::load;
use crate::output::{self, print, write_stdout_with, OutFile, Writer};
use crate::progress::Bars;
use crate::report::{self, compensation};
use anyhow::{anyhow, bail, Result};
use files::{check_subprogram_files, write_subprograms};
use std::io::Write;
use std::path::PathBuf;
use stiffid::app::compensate::document::{
    csv_line, external_header, external_values, header, Names, GENERATOR,
};
use stiffid::app::compensate::stream::{chunk_values, Points};
use stiffid::app::compensate::{self as job, Given, Input, Report, Request};
use stiffid::internal::io::Encoding;
use stiffid::internal::machining::compensate::{
    Aggregate, Compensated, FreeOption, Freedom, MapVariable, Objective, Options, PathPoint,
};
use stiffid::internal::machining::dynamics::Dynamics;
use stiffid::internal::machining::process::file;
use stiffid::internal::machining::program;
use stiffid::internal::machining::program::generate::{date, Settings, Targets};
use stiffid::internal::machining::Language;
use stiffid::internal::observation::deflection::Frame;
use stiffid::internal::robot::ExternalAxes;
use stiffid::{Error, Progress, Setup};
use text::human;

/// Arguments of `stiffid compensate`.
#[derive(clap::Args)]
#[command(group(clap::ArgGroup::new("input").required(true).args(["path", "program"])))]
pub struct Args {
    #[command(flatten)]
    common: Common,
    #[command(flatten)]
    stiffness: Stiffness,
    /// Path CSV: q1_deg..q6_deg or x_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg, then fx_n,fy_n,fz_n
    /// [,mx_nm,my_nm,mz_nm] [,frame], and a cell's external axes e1_mm, e2_deg, ... (at most
    /// 1 000 000 rows).
    #[arg(long)]
    path: Option<PathBuf>,
    /// A machining program instead of a path CSV: G-code (.nc .ngc .gcode .tap .cnc .g; the
    /// part frame from the setup's [workpiece]), KUKA KRL (.src .dat), ABB RAPID (.mod .modx
    /// .prg), FANUC LS (.ls) joint or Cartesian targets, or Yaskawa INFORM (.jbi) joint targets.
    /// Needs --process.
    #[arg(long, requires = "process")]
    program: Option<PathBuf>,
    /// With --program: the process file (TOML) that gives every point its cutting force.
    #[arg(long, requires = "program")]
    process: Option<PathBuf>,
    /// With --program: G-code arcs are split into chords of at most this sagitta, mm
    /// (1e-6 <= value <= 10).
    #[arg(long, default_value_t = 0.01, requires = "program")]
    chord_tolerance_mm: f64,
    /// With a robot --program: files of the controller's backup that hold what the program
    /// declares elsewhere, or folders whose files of the program's language are read (KUKA the
    /// module's .dat and $config.dat; ABB the task's modules, .mod and .sys).
    #[arg(long, num_args = 1.., value_name = "PATH", requires = "program")]
    backup: Vec<PathBuf>,
    /// With a robot --program: leave as found the motions refused for what only the run decides
    /// (a frame that depends on the path, a point assigned at run time), not compensated and
    /// each named in a warning, instead of refusing the program.
    #[arg(long, requires = "program")]
    leave_refused: bool,
    /// With --path: the CSV written, one row per path point, units in the header. With
    /// --program: the compensated program, in the program's own language, or for G-code a robot
    /// program of the compensated targets (.src KRL, .mod RAPID, .ls FANUC LS, .jbi Yaskawa
    /// INFORM in pulses: the setup's [controller] pulses_per_deg) named after the file (its stem,
    /// upper case), with its sub-programs beside it when it is split; a KRL program (read or
    /// written) with its .dat beside it (the same stem). Never one of the inputs.
    #[arg(long)]
    out: PathBuf,
    /// With a G-code --program written as a robot program: Cartesian targets (the compensated
    /// poses with their configuration, cutting moves linear) or joint targets (the compensated
    /// axis angles, reached by axis-interpolated moves in KRL and RAPID and linear ones in LS and
    /// INFORM; an INFORM job always, with a warning when cartesian is given). Default: cartesian.
    #[arg(long, value_parser = choice::<Targets>(), requires = "program")]
    targets: Option<Targets>,
    /// With a G-code --program written as a robot program: the robot's largest TCP speed, mm/s
    /// (0 < value <= 10000); a faster feed is refused.
    #[arg(long, default_value_t = 2000.0, requires = "program")]
    max_tcp_speed_mm_s: f64,
    /// With a G-code --program written as a robot program: the longest program name the
    /// controller takes (8 to 64; default KRL 24, RAPID 32, LS 8 as on R-30iA, longer on later
    /// FANUC controllers).
    #[arg(long, requires = "program")]
    name_length: Option<usize>,
    /// With a G-code --program written as a robot program: the most moves in one program file
    /// (100 to 1000000); a longer program is split into sub-programs its main program calls.
    #[arg(long, default_value_t = 10_000, requires = "program")]
    moves_per_file: usize,
    /// With --program: also the CSV of every path point (the columns of --path's --out).
    #[arg(long, requires = "program")]
    csv: Option<PathBuf>,
    /// Also write a report into this directory (created; must be missing, empty or hold an
    /// earlier compensation report).
    #[arg(long)]
    report: Option<PathBuf>,
    /// Where inverse kinematics starts for the first pose, axis angles q1..q6, deg; default the
    /// setup's first test posture, else the middle of its bounds.
    #[arg(long, allow_hyphen_values = true)]
    q0_deg: Option<String>,
    /// With --path: the frame of the wrench in rows without a `frame` column value (a program's
    /// wrench is its process file's, where the tool cuts).
    #[arg(long, value_parser = choice::<Frame>(), default_value = "base")]
    frame: Frame,
    /// A free variable, moved from the path's or the program's own value at every point
    /// (repeatable, one of each): `tool-rotation=-R..R/STEP` (the rotation about tool z, deg;
    /// default -90..90/2), `station=-R..R/STEP` (a track's station, mm, step default 10),
    /// `positioner=-R..R/STEP` (the positioner's last axis, the table's turn, deg, step default 5),
    /// `tilt=-R..R/STEP` (a two-axis positioner's first axis), an external axis by its name in
    /// the cell file (the carrier's first: the station), `lead-tilt=-CONE..CONE/STEP` (the tool
    /// axis leaned within a cone, deg, step default 2; a program's cone, without a range, is its
    /// process file's; written as a robot program), `configuration` (the arm's configuration, up
    /// to 8, one per program; `configuration=run`: one per run between rapid or joint moves).
    /// The step is the grid's spacing and the most the variable changes between consecutive
    /// points; the variables are chosen jointly by one dynamic programme, every moved posture
    /// feasible (--margin-deg, --max-condition, the cell's collisions), and no point's --minimise
    /// worse than at the path's own values.
    #[arg(long, value_name = "VARIABLE=-R..R/STEP")]
    free: Vec<String>,
    /// With --free: what a point costs: the error bound the document reports (`bound_mm`, the
    /// default), the TCP deflection, or the breakthrough surge at every drilling exit of a
    /// program (tool-rotation alone; the robot must give its masses).
    #[arg(long, value_parser = choice::<Objective>())]
    minimise: Option<Objective>,
    /// With --free: how the points' costs add up along the path: their sum (the default), or the
    /// worst point's (ties broken by the sum).
    #[arg(long, value_parser = choice::<Aggregate>())]
    objective: Option<Aggregate>,
    /// With --free: every moved posture keeps at least this distance to the joint limits, deg (0
    /// to 90; default 5); the path's own posture stays as it is.
    #[arg(long)]
    margin_deg: Option<f64>,
    /// With --free: a moved posture's TCP Jacobian condition number stays at most this (finite,
    /// >= 1; default 1000): away from singularities.
    #[arg(long)]
    max_condition: Option<f64>,
    /// With --free (not configuration alone): refine the grid this many times around the line
    /// chosen on it (0 to 4): each level halves every free variable's step and chooses again
    /// within +-1 previous step of the previous line; the steps given stay the largest change
    /// between points.
    #[arg(long)]
    refine: Option<usize>,
    /// Refuse (a failed gate: exit 1, nothing written) a path or program whose error bound (`bound_mm`, at
    /// --level) exceeds this anywhere, mm (> 0), naming its worst points and what dominates
    /// their bound.
    #[arg(long)]
    max_error_mm: Option<f64>,
    /// With --report: also the map of a free variable: `rotation` (the default: the rotation
    /// about tool z, on the --free tool-rotation grid, else 5 deg steps within +-90 deg) or `track`
    /// (the track station, on the --free station grid, else 50 mm steps within +-1000 mm):
    /// every point's error bound, deflection, condition number, distance to the joint limits and,
    /// with a [cell] floor or obstacles, to them, at every value, every other free variable at
    /// the value chosen at the point, with the value chosen (map.csv and the figure map).
    #[arg(long, requires = "report", num_args = 0..=1, default_missing_value = "rotation", value_parser = choice::<MapVariable>())]
    map: Option<MapVariable>,
    /// The process force model's relative error in the error budget, percent (0 to 100): the
    /// bound's force part is this share of the deflection.
    #[arg(long, default_value_t = 20.0)]
    force_tolerance_pct: f64,
    /// The level of the error bound (`bound_mm`) and of the deflection's prediction intervals
    /// (0.5 to 0.999; the CSV's `d*_lower_mm`, `d*_upper_mm`, when the stiffness file holds the
    /// held-out residuals of its identification, `identify --cross-validate`).
    #[arg(long, default_value_t = 0.95)]
    level: f64,
}

/// A failure of the run: the library's, or writing.
enum Failure {
    Library(Error),
    Output(anyhow::Error),
}

impl From<Error> for Failure {
    fn from(e: Error) -> Self {
        Failure::Library(e)
    }
}

/// Where the rows go as they come: the CSV, and the document's points (for `--json` and the
/// report).
struct Sinks<'s> {
    csv: Writer,
    cell: Option<&'s ExternalAxes>,
    rows: Option<Points<Writer>>,
}

impl Sinks<'_> {
    fn write(
        &mut self,
        first: usize,
        points: &[PathPoint],
        results: &[Compensated],
        dynamics: &[Dynamics],
    ) -> Result<()> {
        for (v, r) in chunk_values(first, points, results, dynamics).zip(results) {
            let e = external_values(self.cell, r);
            writeln!(self.csv, "{}", csv_line(&[&v[..], &e[..]].concat()))?;
            if let Some(rows) = self.rows.as_mut() {
                rows.push(&v)?;
            }
        }
        Ok(())
    }
}

/// Parses the arguments, runs the job with the rows written as they come, then writes the
/// program, the report, and the text or JSON.
pub fn run(args: &Args) -> Result<()> {
    let setup = args.common.load_setup()?;
    let compliance = args.stiffness.load(&setup)?;
    let options = options(args, &setup)?;
    let (name, input_path) = match (&args.path, &args.program) {
        (Some(p), _) | (None, Some(p)) => (p.display().to_string(), p.clone()),
        (None, None) => bail!("expected --path or --program"),
    };
    // A KRL program's .dat beside it: read with it, and written compensated beside --out.
    let (text, data, encoding) = match &args.process {
        None => (load::read(&input_path)?, None, Encoding::Utf8),
        Some(_) => load::read_program(&input_path)?,
    };
    let backup = load::read_backup(&args.backup, &name)?;
    let input = input(args, name.clone(), (&text, data.as_deref()), encoding)?;
    let input = with_reading(input, &backup, args.leave_refused);
    let out = OutFile::prepare(&args.out, "--out")?;
    // A program whose language keeps data beside it (KRL's .dat) has it written there too.
    let data_out =
        (program::data_out(&args.out).map(|p| OutFile::prepare(&p, "--out"))).transpose()?;
    let csv_out = args
        .csv
        .as_deref()
        .map(|p| OutFile::prepare(p, "--csv"))
        .transpose()?;
    let report_dir = args
        .report
        .as_deref()
        .map(|dir| report::open(dir, "--report", None, GENERATOR, &compensation::holds))
        .transpose()?;
    let mut csv = csv_out.as_ref().unwrap_or(&out).writer()?;
    let cell = setup.robot().external();
    let columns = [header(), external_header(cell)].concat();
    writeln!(csv, "{}", columns.join(","))?;
    let rows = (args.common.json || report_dir.is_some())
        .then(|| out.writer().map(Points::new))
        .transpose()?;
    let mut sinks = Sinks { csv, cell, rows };
    let request = Request {
        setup: &setup,
        compliance,
        input,
        options,
        names: names(args),
    };
    // The points are counted as they come (a program's are known only once its arcs are split).
    let bars = Bars::new(false);
    bars.begin("points compensated", 0);
    let outcome = match job::run(request, |first, p, r, d| {
        bars.advance(first + p.len());
        sinks.write(first, p, r, d).map_err(Failure::Output)
    }) {
        Ok(outcome) => outcome,
        Err(Failure::Output(e)) => return Err(e),
        Err(Failure::Library(e)) => return Err(e.into()),
    };
    bars.end();
    let report = outcome.report;
    output::warnings(&report.warnings);
    let Sinks { mut csv, rows, .. } = sinks;
    csv.sync()?;
    if let (Some(o), Some(d)) = (
        &data_out,
        report.program.as_ref().and_then(|p| p.data.as_ref()),
    ) {
        o.write(&report.program.as_ref().map_or(Vec::new(), |p| p.bytes(d)))?;
    }
    finish(args, &setup, &report, csv, rows, &out, report_dir)?;
    Ok(())
}

/// The program input `input` read with the backup's files `backup` and `leave_refused`.
fn with_reading<'t>(
    mut input: Input<'t>,
    backup: &'t [(String, String)],
    leave_refused: bool,
) -> Input<'t> {
    if let Input::Program { reading, .. } = &mut input {
        *reading = stiffid::internal::machining::program::Reading {
            backup,
            leave_refused,
        };
    }
    input
}

/// Why a wrench frame other than the default is refused with a program.
pub(crate) const FRAME_WITHOUT_PATH: &str = "only with --path (the frame of a path CSV's wrenches): a program's wrench is its process file's, where the tool cuts";

/// The request's input from the arguments and the input file's text.
fn input<'t>(
    args: &Args,
    name: String,
    (text, data): (&'t str, Option<&'t str>),
    encoding: Encoding,
) -> Result<Input<'t>> {
    let Some(process) = &args.process else {
        return Ok(Input::Path {
            name,
            text,
            frame: args.frame,
        });
    };
    if args.frame != Frame::Base {
        bail!("--frame: {FRAME_WITHOUT_PATH}");
    }
    let language = Language::of_file(&name).map_err(|e| anyhow!("--program {e}"))?;
    let out = args.out.display().to_string();
    let (output, out_name) =
        Language::output(language, Some(&out), None, "").map_err(|e| anyhow!("--out {e}"))?;
    if let (Language::GCode, Language::Robot(_)) = (language, output) {
        check_subprogram_files(&args.out)?;
    }
    let process_name = process.display().to_string();
    let parsed = file::parse(&load::read(process)?, &process_name)?;
    Ok(Input::Program {
        encoding,
        reading: Default::default(),
        name,
        text,
        data,
        language,
        process_name,
        process: parsed,
        chord_tolerance: args.chord_tolerance_mm * 1e-3,
        output,
        out_name,
        settings: Settings {
            targets: args.targets.unwrap_or_default(),
            targets_asked: args.targets.is_some(),
            max_tcp_speed: args.max_tcp_speed_mm_s * 1e-3,
            name_length: args.name_length,
            moves_per_file: args.moves_per_file,
            date_s: source_date()?,
            ..Settings::default()
        },
    })
}

/// The date of generated programs: `SOURCE_DATE_EPOCH`'s when the environment sets it, else 0.
fn source_date() -> Result<i64> {
    match std::env::var(date::VARIABLE) {
        Err(_) => Ok(0),
        Ok(text) => Ok(date::epoch(&text)?),
    }
}

fn names(args: &Args) -> Names {
    let shown = |p: &Option<PathBuf>| {
        p.as_ref()
            .map_or(String::new(), |p| p.display().to_string())
    };
    let out = args.out.display().to_string();
    match args.program {
        None => Names {
            setup: args.common.setup.clone(),
            stiffness: args.stiffness.stiffness.display().to_string(),
            out,
            program_out: String::new(),
        },
        Some(_) => Names {
            setup: args.common.setup.clone(),
            stiffness: args.stiffness.stiffness.display().to_string(),
            out: shown(&args.csv),
            program_out: out,
        },
    }
}

/// Writes the program (with --program), the report, the CSV, then the text or JSON.
#[allow(clippy::too_many_arguments)]
fn finish(
    args: &Args,
    setup: &Setup,
    report: &Report,
    csv: Writer,
    rows: Option<Points<Writer>>,
    out: &OutFile,
    report_dir: Option<output::ReportDir>,
) -> Result<()> {
    let typed = report.document();
    let mut rows = rows.map(Points::into_inner);
    if let Some(rows) = rows.as_mut() {
        rows.sync()?;
    }
    if let Some(p) = &report.program {
        out.write(&p.bytes(&p.text))?;
        let parts = write_subprograms(&args.out, p)?;
        // A generated program's earlier split: its parts not written again go at the commit.
        if p.language == Language::GCode && p.output != Language::GCode {
            output::staged::parts(out.target().to_path_buf(), parts);
        }
    }
    // The document without its points, which the library writes from the rows stored.
    let rows_path = rows.as_ref().map(|r| r.path().to_path_buf());
    let json = |w: &mut dyn Write| match &rows_path {
        Some(p) => typed
            .write_json(std::fs::File::open(p)?, w)
            .map_err(std::io::Error::from),
        None => Ok(()),
    };
    if let Some(dir) = report_dir {
        let view = compensation::View {
            report,
            csv: csv.path(),
            summary: &json,
            document: &typed,
        };
        compensation::write(dir, setup, &view)?;
    }
    if report.program.is_none() || args.csv.is_some() {
        csv.finish()?;
    }
    match (args.common.json, &rows_path) {
        (true, Some(_)) => write_stdout_with(&json),
        _ => print(&human(args, setup, report, &typed)),
    }
}

fn options(args: &Args, setup: &Setup) -> Result<Options> {
    stiffid::internal::model::prediction::check_level("--level", args.level)?;
    let q0 = match &args.q0_deg {
        Some(text) => Some(load::posture(text, "--q0-deg", setup.robot())?.1),
        None => None,
    };
    let free = args
        .free
        .iter()
        .map(|f| FreeOption::parse(f.as_str()))
        .collect::<stiffid::Result<Vec<_>>>()?;
    let given = Given {
        q0,
        level: args.level,
        max_error_mm: args.max_error_mm,
        force_tolerance_pct: args.force_tolerance_pct,
        map: args.map,
        freedom: Freedom {
            free,
            minimise: args.minimise,
            objective: args.objective,
            margin_deg: args.margin_deg,
            max_condition: args.max_condition,
            refine: args.refine,
        },
    };
    Ok(given.options(setup)?)
}
