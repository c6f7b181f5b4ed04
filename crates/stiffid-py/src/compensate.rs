//! `stiffid.compensate`: deflection compensation of a machining path, over
//! [`stiffid::internal::machining::compensate`] (Zhang et al. 2021, Eq. 4-6, with the loaded pose solved by Newton
//! steps; the free tool axis after Caro et al., ICRA 2013, and Xiong et al., RCIM 2019).

use crate::arrays;
use crate::documents::{to_python, warn};
use crate::error::{self, raise};
use crate::setup::Setup;
use nalgebra::Vector6;
use pyo3::prelude::*;
use pyo3::types::{PyAny, PyDict};
use std::path::{Path, PathBuf};
use stiffid::app::compensate::document::{Names, DYNAMICS};
use stiffid::app::compensate::stream::{chunk_values, Rows};
use stiffid::app::compensate::{self as job, Given, Input, Request};
use stiffid::internal::io::Encoding;
use stiffid::internal::machining::compensate::{
    free, Aggregate, Compensated, FreeOption, Freedom, MapVariable, Objective, Options, PathPoint,
    Variable,
};
use stiffid::internal::machining::dynamics::Dynamics;
use stiffid::internal::machining::process::file;
use stiffid::internal::machining::program::generate::{date, Settings, Targets};
use stiffid::internal::machining::Language;
use stiffid::internal::observation::deflection::Frame;

/// Compensates a machining path with the stiffness ``stiffness`` of every parameter of the setup's
/// model: one number per parameter (the six drives, Nm/rad, then the virtual springs, Nm/rad or
/// N/mm) or the path of a stiffness JSON file as ``stiffid identify --out`` writes it (its
/// covariance, when present, gives the standard deviations); the same job as ``stiffid
/// compensate``. The path is either the CSV file ``path`` (the format of
/// ``stiffid compensate --path``: axis angles ``q1_deg..q6_deg`` or a TCP pose ``x_mm..rz_deg``
/// per line, and the wrench ``fx_n..mz_nm`` at the TCP, in ``frame`` ``"base"`` or ``"tool"``
/// unless the file says), or the machining program ``program`` (G-code, KUKA KRL ``.src``, ABB
/// RAPID ``.mod``, FANUC LS ``.ls``; G-code arcs split to ``chord_tolerance_mm``, its part frame
/// the setup's ``[workpiece]``) with the process file ``process`` that gives each point its
/// cutting force. Inverse kinematics starts at ``q0_deg`` (shape ``(6,)``, deg; default the
/// setup's first test posture). ``free`` lists the free variables, each moved from the path's
/// own value at every point (the texts of ``compensate --free``, or dicts
/// ``{"variable": "station", "range": 500, "step": 10}``): ``"tool-rotation=-R..R/STEP"`` (the
/// rotation about tool z, deg, default ``-90..90/2``), ``"station=-R..R/STEP"`` (a track's
/// station, mm, step default 10), ``"positioner=-R..R/STEP"`` (the positioner's last axis, deg,
/// step default 5), ``"tilt=-R..R/STEP"`` (a two-axis positioner's first axis), an external
/// axis by its name in the cell file, ``"lead-tilt=-CONE..CONE/STEP"`` (the tool axis leaned
/// within a cone, deg, step default 2; a program's cone, without a range, its process file's;
/// ``lead_deg`` and ``tilt_deg`` (``(n,)``) hold the lean chosen), ``"configuration"`` (the
/// arm's configuration, up to 8; ``"configuration=run"``: one per run, the ``document``'s
/// ``configurations``). They are chosen jointly to the least ``minimise`` (``"bound"``, the
/// default: the error bound the document reports; ``"deflection"``; ``"surge"``: the
/// breakthrough surge at the drilling exits of a program, the tool rotation alone, the robot
/// giving its masses), summed along the path (``objective="sum"``) or at its worst point
/// (``"max"``), no point worse than at the path's own values; each step is also the most a
/// variable changes between points. A moved posture keeps ``margin_deg`` (0 to 90, default 5)
/// from the joint limits, a TCP Jacobian condition number of at most ``max_condition``
/// (default 1000) and, with the setup's ``[cell]``, clear of the floor, the obstacles and
/// itself (the ``document``'s ``feasibility`` counts the states each check removed);
/// ``refine=L`` (0 to 4) refines the grid ``L`` times around the line chosen on it, each level
/// halving every step (the ``document``'s ``refine``). ``minimise``, ``objective``,
/// ``margin_deg``, ``max_condition`` and ``refine`` without ``free`` are refused
/// (``ValueError``), as are the keywords ``free`` replaced, with how to write them. Every
/// point's error budget at ``level``: ``bound_mm`` (``(n,)``) and its parts ``bound_left_mm``,
/// ``bound_compensation_mm``, ``bound_calibration_mm``, ``bound_force_mm`` (the force model's
/// relative error ``force_tolerance_pct``) and ``bound_model_form_mm`` (``(n,)``, ``nan``
/// where absent); ``max_error_mm`` refuses (``ValueError``) a path whose bound exceeds it
/// anywhere, naming its worst points and what dominates their bound.
/// ``map=True`` (or ``"rotation"``) adds ``map``:
/// the free variable's map, every point at every rotation about tool z of the free tool axis'
/// grid (else 5 deg steps within +-90 deg): ``line`` (``(n,)``), ``tool_rotation_deg``
/// (``(g,)``), ``chosen_deg`` (``(n,)``: the rotation chosen), ``bound_mm``, ``deflection_mm``,
/// ``condition`` and ``limit_distance_deg`` (``(n, g)``, ``nan`` where the turned pose is not
/// reached) and, with a cell floor or obstacles, ``collision_distance_mm`` (``(n, g)``);
/// ``map="track"`` maps the track station instead (the free station's grid, else 50 mm steps
/// within +-1000 mm): ``station_offset_mm`` (``(g,)``) and ``chosen_mm`` (``(n,)``) for the
/// rotation's two, ``nan`` beyond the travel (as ``--map track``).
/// ``figures=True`` adds ``figures``: the figures of ``compensate --report`` as SVG documents
/// (str) keyed by name, byte for byte its ``figures/<name>.svg``: ``deflection`` (the TCP
/// deflection along the path before and after, with its band), ``path`` (the path over the
/// robot, side and top views), for a program ``force`` and ``segments``, with ``map=True``
/// ``map``.
/// Returns a dict of arrays with one row per path point, in path order: ``line`` (the file's line
/// numbers, ``int64``), ``q_deg`` and ``q_compensated_deg`` (``(n, 6)``, deg), ``deflection_mm``
/// and ``deflection_mrad`` (``(n, 3)``, base frame, the TCP under the wrench), ``force_n``
/// (``(n, 3)``, base frame), ``residual_um`` and ``residual_urad`` (``(n,)``), ``iterations``
/// (``(n,)``, ``int64``: the Newton steps of the compensation), ``tool_rotation_deg`` (``(n,)``)
/// and, with a covariance, ``deflection_std_mm`` (``(n, 3)``); with a stiffness file that holds
/// held-out residuals (``identify(..., cross_validate=True)``), the deflection's prediction
/// intervals at ``level`` (0.5 to 0.999), ``deflection_lower_mm`` and ``deflection_upper_mm``
/// (``(n, 3)``, base frame; ``-inf``/``inf`` for an unbounded end); ``document``: the document of
/// ``stiffid compensate --json`` (its ``program`` with the segments' force and deflection before
/// and after, for a program); with a program, ``program``: the compensated program's text, in
/// the program's own language or, for G-code with ``output="krl"``, ``"rapid"``, ``"ls"`` or
/// ``"inform"``, a robot program of the compensated targets (``targets="cartesian"``, the
/// default when ``None``: the compensated poses with their configuration, cutting moves linear; ``"joint"``:
/// axis angles; an INFORM job: axis angles in pulses, the setup's ``[controller]
/// pulses_per_deg``, with a warning when ``targets="cartesian"`` is given), named
/// ``program_name`` (default the program file's stem, upper case), its feeds refused above
/// ``max_tcp_speed_mm_s``, split into sub-programs of at most ``moves_per_file`` moves
/// (``subprograms``: their names and texts, in call order), names within ``name_length``
/// (default the controller's: KRL 24, RAPID 32, LS 8), as ``stiffid compensate`` does. A KRL
/// ``.src`` is read with the ``.dat`` beside it (same folder and stem, as the controller pairs
/// them) and ``data`` is that ``.dat`` compensated (``None`` without one); a KRL program written
/// from G-code has its points in ``data``, its ``.dat`` (``DEFDAT``, ``DECL E6POS XP1=..``), to be
/// written beside it, and each sub-program's in ``subprogram_data`` (name: text). Points
/// without a process force are warned about (``UserWarning``) as the command does.
/// ``backup=`` (a path or a list: files of the controller's backup, or folders whose files of the
/// program's language are read) gives what a robot program declares elsewhere (KUKA the
/// module's ``.dat`` and ``$config.dat``; ABB the task's modules); ``leave_refused=True`` leaves
/// as found the motions refused for what only the run decides, each named in a warning.
#[pyfunction]
#[pyo3(signature = (setup, path=None, stiffness=None, *, program=None, process=None, output=None, chord_tolerance_mm=0.01, backup=None, leave_refused=false, frame="base", q0_deg=None, free=None, minimise=None, program_name=None, targets=None, max_tcp_speed_mm_s=2000.0, name_length=None, moves_per_file=10000, level=0.95, max_error_mm=None, force_tolerance_pct=20.0, objective=None, map=None, margin_deg=None, max_condition=None, refine=None, figures=false, **retired))]
#[allow(clippy::too_many_arguments)]
pub fn compensate<'py>(
    py: Python<'py>,
    setup: &Setup,
    path: Option<PathBuf>,
    stiffness: Option<&Bound<'py, PyAny>>,
    program: Option<PathBuf>,
    process: Option<PathBuf>,
    output: Option<&str>,
    #[pyo3(from_py_with = crate::count::number)] chord_tolerance_mm: f64,
    backup: Option<&Bound<'py, PyAny>>,
    leave_refused: bool,
    frame: &str,
    q0_deg: Option<&Bound<'py, PyAny>>,
    free: Option<&Bound<'py, PyAny>>,
    minimise: Option<&str>,
    program_name: Option<String>,
    targets: Option<&str>,
    #[pyo3(from_py_with = crate::count::number)] max_tcp_speed_mm_s: f64,
    #[pyo3(from_py_with = crate::count::optional_whole)] name_length: Option<i64>,
    #[pyo3(from_py_with = crate::count::whole)] moves_per_file: i64,
    #[pyo3(from_py_with = crate::count::number)] level: f64,
    max_error_mm: Option<&Bound<'_, PyAny>>,
    #[pyo3(from_py_with = crate::count::number)] force_tolerance_pct: f64,
    objective: Option<&str>,
    map: Option<&Bound<'py, PyAny>>,
    margin_deg: Option<&Bound<'_, PyAny>>,
    max_condition: Option<&Bound<'_, PyAny>>,
    #[pyo3(from_py_with = crate::count::optional_whole)] refine: Option<i64>,
    figures: bool,
    retired: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let max_error_mm = crate::count::real("max_error_mm", max_error_mm)?;
    let margin_deg = crate::count::real("margin_deg", margin_deg)?;
    let max_condition = crate::count::real("max_condition", max_condition)?;
    refuse_retired(retired)?;
    let name_length = crate::count::optional("name_length", name_length)?;
    let moves_per_file = crate::count::count("moves_per_file", moves_per_file)?;
    let s = &setup.inner;
    let stiffness = stiffness.ok_or_else(|| {
        let positional = match &path {
            Some(p) if p.extension().is_some_and(|e| e.eq_ignore_ascii_case("json")) => format!(" (the second positional argument is path, and {} was given there: pass the stiffness by keyword, stiffness=...)", p.display()),
            _ => String::new(),
        };
        error::value(format!("stiffness: missing: give stiffness=, one stiffness per parameter of the setup's model or a stiffness file{positional}"))
    })?;
    let compliance = crate::stiffness::compliance(s, stiffness, None, "stiffness")?;
    let frame = frame.parse::<Frame>().map_err(raise)?;
    let gates = (level, max_error_mm, force_tolerance_pct, map);
    let freedom = (free, minimise, objective, margin_deg, max_condition, refine);
    let options = job_options(py, s, q0_deg, gates, freedom)?;
    let (name, file_path) = match (&path, &program) {
        (Some(p), None) | (None, Some(p)) => (p.display().to_string(), p.clone()),
        _ => {
            return Err(error::value(
                "expected path= (a path CSV) or program= (a machining program), not both",
            ))
        }
    };
    // A KRL program's .dat beside it, read with it (its compensated copy is ``data``).
    let (text, data, encoding) = match &process {
        None => (error::read(&file_path)?, None, Encoding::Utf8),
        Some(_) => error::read_program(&file_path)?,
    };
    let how = (output, program_name, chord_tolerance_mm);
    let settings = (targets, max_tcp_speed_mm_s, name_length, moves_per_file);
    let texts = (
        name.as_str(),
        (text.as_str(), data.as_deref()),
        frame,
        encoding,
    );
    let mut input = input_of(texts, (&program, &process), how, settings)?;
    let backup = backup_files(backup, &input, &name)?;
    read_with(&mut input, &backup, leave_refused)?;
    let names = names_of(setup, stiffness);
    let request = Request {
        setup: s,
        compliance,
        input,
        options,
        names,
    };
    let mut points: Vec<PathPoint> = Vec::new();
    let mut results: Vec<Compensated> = Vec::new();
    let mut rows = Rows::default();
    let mut dynamics: Vec<Vec<Option<f64>>> = Vec::new();
    let at = (stiffid::app::compensate::document::header().iter())
        .position(|h| h == DYNAMICS[0])
        .unwrap_or(0);
    let outcome = py
        .detach(|| {
            job::run(
                request,
                |first, p: &[PathPoint], r: &[Compensated], d: &[Dynamics]| {
                    for v in chunk_values(first, p, r, d) {
                        dynamics.push(v[at..at + DYNAMICS.len()].to_vec());
                        rows.push(&v);
                    }
                    points.extend_from_slice(p);
                    results.extend_from_slice(r);
                    Ok::<(), stiffid::Error>(())
                },
            )
        })
        .map_err(raise)?;
    let mut report = outcome.report;
    warn(py, &report.warnings)?;
    let out = table(py, &results, &points)?;
    for (k, name) in DYNAMICS.iter().enumerate() {
        let column = dynamics.iter().map(|v| v[k].unwrap_or(f64::NAN));
        out.set_item(*name, arrays::vec1(py, column))?;
    }
    // The job's report, its document, gets the rows the sink received.
    report.points = rows.into_points();
    out.set_item("document", to_python(py, &report, &[])?)?;
    if figures {
        let sample = stiffid_figures::compensate::sample(&report);
        let drawings = stiffid_figures::compensate::figures(s, &sample, &report);
        out.set_item("figures", crate::figures::svgs(py, &drawings)?)?;
    }
    if let Some(p) = &report.program {
        program_items(py, &out, p)?;
    }
    if let Some(m) = &report.map {
        out.set_item("map", map_dict(py, m)?)?;
    }
    Ok(out)
}

/// The job's options: where inverse kinematics starts, the levels and gates, the map, the
/// free variables (the arguments of [`compensate`]).
#[allow(clippy::type_complexity)]
fn job_options<'py>(
    py: Python<'py>,
    s: &stiffid::Setup,
    q0_deg: Option<&Bound<'py, PyAny>>,
    (level, max_error_mm, force_tolerance_pct, map): (
        f64,
        Option<f64>,
        f64,
        Option<&Bound<'py, PyAny>>,
    ),
    (free, minimise, objective, margin_deg, max_condition, refine): (
        Option<&Bound<'py, PyAny>>,
        Option<&str>,
        Option<&str>,
        Option<f64>,
        Option<f64>,
        Option<i64>,
    ),
) -> PyResult<Options> {
    let map = match map_over(map)? {
        (true, over) => Some(over),
        (false, _) => None,
    };
    let given = Given {
        q0: q0(py, s, q0_deg)?,
        level,
        max_error_mm,
        force_tolerance_pct,
        map,
        freedom: Freedom {
            free: free_variables(free)?,
            minimise: minimise
                .map(str::parse::<Objective>)
                .transpose()
                .map_err(raise)?,
            objective: objective
                .map(str::parse::<Aggregate>)
                .transpose()
                .map_err(raise)?,
            margin_deg,
            max_condition,
            refine: crate::count::optional("refine", refine)?,
        },
    };
    given.options(s).map_err(raise)
}

/// A compensated program's items: `program`, its text, `encoding` (`utf-8`, or `latin-1` for
/// a program read as Latin-1: each text is then the characters of its file's bytes, which
/// `text.encode("latin-1")` gives back, a UTF-8 byte order mark's three included), `subprograms`,
/// `data` (a KRL program's compensated `.dat`, or `None`) and `subprogram_data` (each KRL
/// sub-program's `.dat` by its name; empty in another language).
fn program_items(
    py: Python<'_>,
    out: &Bound<'_, PyDict>,
    p: &stiffid::app::compensate::ProgramReport,
) -> PyResult<()> {
    let text = |t: &str| file_text(t, p.encoding);
    out.set_item("program", text(&p.text)?)?;
    out.set_item("encoding", p.encoding.name())?;
    let subprograms = PyDict::new(py);
    for f in &p.subprograms {
        subprograms.set_item(&f.name, text(&f.text)?)?;
    }
    out.set_item("subprograms", subprograms)?;
    out.set_item("data", p.data.as_deref().map(text).transpose()?)?;
    let subprogram_data = PyDict::new(py);
    for f in &p.subprograms {
        if let Some(data) = &f.data {
            subprogram_data.set_item(&f.name, text(data)?)?;
        }
    }
    out.set_item("subprogram_data", subprogram_data)?;
    Ok(())
}

/// A program file's text as Python gets it: in `encoding`'s bytes ([`Encoding::encode`]), each
/// byte one character for a Latin-1 file (the text `text.encode("latin-1")` writes byte for
/// byte), the text itself for a UTF-8 one.
fn file_text(text: &str, encoding: Encoding) -> PyResult<String> {
    match encoding {
        Encoding::Utf8 => Ok(text.to_string()),
        Encoding::Latin1 => (encoding.encode(text))
            .map(|bytes| bytes.into_iter().map(char::from).collect())
            .map_err(pyo3::exceptions::PyValueError::new_err),
    }
}

/// The names the document states: the setup as given, the stiffness file (or `arrays`).
fn names_of(setup: &Setup, stiffness: &Bound<'_, PyAny>) -> Names {
    Names {
        setup: setup.given.clone(),
        stiffness: stiffness
            .extract::<PathBuf>()
            .map_or("arrays".into(), |p| p.display().to_string()),
        out: String::new(),
        program_out: String::new(),
    }
}

/// The files of the controller's backup `backup=` gives with the program `input` (named `name`).
fn backup_files(
    backup: Option<&Bound<'_, PyAny>>,
    input: &Input,
    name: &str,
) -> PyResult<Vec<(String, String)>> {
    match (backup, input) {
        (None, _) => Ok(Vec::new()),
        (Some(b), Input::Program { .. }) => error::read_backup(&backup_paths(b)?, name),
        (Some(_), _) => Err(error::value("backup: only with program= and process=")),
    }
}

/// The program `input` read with the backup's files `backup` and `leave_refused`.
fn read_with<'t>(
    input: &mut Input<'t>,
    backup: &'t [(String, String)],
    leave_refused: bool,
) -> PyResult<()> {
    match input {
        Input::Program { reading, .. } => {
            *reading = stiffid::internal::machining::program::Reading {
                backup,
                leave_refused,
            };
            Ok(())
        }
        _ if leave_refused => Err(error::value(
            "leave_refused: only with program= and process=",
        )),
        _ => Ok(()),
    }
}

/// The paths `backup=` gives: one path (a file or a folder), or a list of them.
pub(crate) fn backup_paths(backup: &Bound<'_, PyAny>) -> PyResult<Vec<PathBuf>> {
    match backup.extract::<PathBuf>() {
        Ok(one) => Ok(vec![one]),
        Err(_) => backup.extract::<Vec<PathBuf>>().map_err(|_| {
            error::value("backup: expected a path (a file or a folder of the controller's backup) or a list of paths")
        }),
    }
}

/// The path (`program` and `process` `None`) or the program to compensate, named `name`, and
/// how its output is written.
#[allow(clippy::type_complexity)]
fn input_of<'t>(
    (name, (text, data), frame, encoding): (&str, (&'t str, Option<&'t str>), Frame, Encoding),
    (program, process): (&Option<PathBuf>, &Option<PathBuf>),
    (output, program_name, chord_tolerance_mm): (Option<&str>, Option<String>, f64),
    (targets, max_tcp_speed_mm_s, name_length, moves_per_file): (
        Option<&str>,
        f64,
        Option<usize>,
        usize,
    ),
) -> PyResult<Input<'t>> {
    let input = match (program, process) {
        (None, None) => {
            // The program's options, given (their defaults are the signature's): a path CSV is
            // compensated point by point and writes no program.
            let given = [
                ("output", output.is_some()),
                ("program_name", program_name.is_some()),
                ("targets", targets.is_some()),
                ("name_length", name_length.is_some()),
                ("chord_tolerance_mm", chord_tolerance_mm != 0.01),
                ("moves_per_file", moves_per_file != 10_000),
            ];
            if let Some((key, _)) = given.iter().find(|(_, given)| *given) {
                return Err(error::value(format!(
                    "{key}: only with program= (a path is compensated point by point and writes no program)"
                )));
            }
            Input::Path {
                name: name.to_string(),
                text,
                frame,
            }
        }
        (Some(_), Some(_)) if frame != Frame::Base => {
            return Err(error::value(
                "frame: only with path= (the frame of a path CSV's wrenches): a program's wrench is its process file's, where the tool cuts",
            ))
        }
        (Some(_), Some(process)) => {
            let language = Language::of_file(name).map_err(raise)?;
            let process_name = process.display().to_string();
            let parsed = file::parse(&error::read(process)?, &process_name).map_err(raise)?;
            let stem = program_name.unwrap_or_else(|| {
                Path::new(name)
                    .file_stem()
                    .map_or(String::new(), |s| s.to_string_lossy().into_owned())
            });
            let (output, out_name) =
                Language::output(language, None, output, &stem).map_err(raise)?;
            let settings = Settings {
                targets: (targets.map(str::parse::<Targets>).transpose())
                    .map_err(raise)?
                    .unwrap_or_default(),
                targets_asked: targets.is_some(),
                max_tcp_speed: max_tcp_speed_mm_s * 1e-3,
                name_length,
                moves_per_file,
                date_s: source_date()?,
                ..Settings::default()
            };
            Input::Program {
                encoding,
                reading: Default::default(),
                name: name.to_string(),
                text,
                data,
                language,
                process_name,
                process: parsed,
                chord_tolerance: chord_tolerance_mm * 1e-3,
                output,
                out_name,
                settings,
            }
        }
        (None, Some(_)) => return Err(error::value("process: only with program=")),
        (Some(_), None) => return Err(error::value("program: needs process= (the process file)")),
    };
    Ok(input)
}

/// The dict of the free variable's map `m` (module docs of [`compensate`]).
fn map_dict<'py>(
    py: Python<'py>,
    m: &stiffid::internal::machining::compensate::Map,
) -> PyResult<Bound<'py, PyDict>> {
    let map = PyDict::new(py);
    let matrix = |x: &nalgebra::DMatrix<f64>, scale: f64| {
        let a = numpy::ndarray::Array2::from_shape_fn((x.nrows(), x.ncols()), |(i, k)| {
            x[(i, k)] * scale
        });
        numpy::IntoPyArray::into_pyarray(a, py)
    };
    map.set_item("line", arrays::integers(py, m.lines.iter().copied()))?;
    let deg = |v: &[f64]| arrays::vec1(py, v.iter().map(|a| a.to_degrees()));
    let mm = |v: &[f64]| arrays::vec1(py, v.iter().map(|a| a * 1e3));
    match m.variable {
        MapVariable::Rotation => {
            map.set_item("tool_rotation_deg", deg(&m.angles))?;
            map.set_item("chosen_deg", deg(&m.chosen))?;
        }
        MapVariable::Track => {
            map.set_item("station_offset_mm", mm(&m.stations))?;
            map.set_item("chosen_mm", mm(&m.chosen))?;
        }
    }
    if let Some(c) = &m.collision_distance {
        map.set_item("collision_distance_mm", matrix(c, 1e3))?;
    }
    map.set_item("bound_mm", matrix(&m.bound, 1e3))?;
    map.set_item("deflection_mm", matrix(&m.deflection, 1e3))?;
    map.set_item("condition", matrix(&m.condition, 1.0))?;
    map.set_item(
        "limit_distance_deg",
        matrix(&m.limit_distance, 1.0f64.to_degrees()),
    )?;
    Ok(map)
}

/// `map=`: `None` or `False` (no map), `True` or `"rotation"` (the rotation's), `"track"` (the
/// station's).
fn map_over(map: Option<&Bound<'_, PyAny>>) -> PyResult<(bool, MapVariable)> {
    let Some(map) = map else {
        return Ok((false, MapVariable::Rotation));
    };
    if let Ok(on) = map.extract::<bool>() {
        return Ok((on, MapVariable::Rotation));
    }
    let name: String = map
        .extract()
        .map_err(|_| error::value("map: expected True, False, \"rotation\" or \"track\""))?;
    Ok((true, name.parse::<MapVariable>().map_err(raise)?))
}

/// The compensation's options from the arguments: the setup's, inverse kinematics started at
/// `q0_deg` when given.
pub(crate) fn options(
    py: Python<'_>,
    s: &stiffid::Setup,
    q0_deg: Option<&Bound<'_, PyAny>>,
) -> PyResult<Options> {
    let mut options = Options::for_setup(s);
    if let Some(q0) = q0(py, s, q0_deg)? {
        options.q0 = q0;
    }
    Ok(options)
}

/// `q0_deg=`: where inverse kinematics starts, axis angles within the joint limits (rad), with
/// the warning of a posture that looks like radians; `None` when not given.
fn q0(
    py: Python<'_>,
    s: &stiffid::Setup,
    q0_deg: Option<&Bound<'_, PyAny>>,
) -> PyResult<Option<Vector6<f64>>> {
    let Some(q) = q0_deg else {
        return Ok(None);
    };
    let r = s.robot();
    let within = (r.limits(), "the joint limits");
    let q0 = arrays::postures(q, "q0_deg", within, 1)?.0[0];
    let warning = stiffid::internal::setup::plausibility::radians_in_option("q0_deg", &q0);
    warn(py, &Vec::from_iter(warning))?;
    Ok(Some(q0))
}

/// `free=`: a list of the texts of `compensate --free` (`"tool-rotation=-90..90/5"`) or of dicts
/// (`{"variable": "station", "range": 500, "step": 10}`, `range` and `step` optional).
fn free_variables(free: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<FreeOption>> {
    let Some(free) = free else {
        return Ok(Vec::new());
    };
    let expected = "free: expected a list of str (\"tool-rotation=-90..90/5\") or of dicts ({\"variable\": ..., \"range\": ..., \"step\": ...})";
    if free.is_instance_of::<pyo3::types::PyString>() || free.is_instance_of::<PyDict>() {
        return Err(error::value(expected));
    }
    let items: Vec<Bound<'_, PyAny>> = free.extract().map_err(|_| error::value(expected))?;
    items
        .iter()
        .map(|item| free_variable(item, expected))
        .collect()
}

/// One item of `free=`.
fn free_variable(item: &Bound<'_, PyAny>, expected: &str) -> PyResult<FreeOption> {
    if let Ok(text) = item.extract::<String>() {
        return FreeOption::parse(&text).map_err(raise);
    }
    let dict = item.cast::<PyDict>().map_err(|_| error::value(expected))?;
    for key in dict.keys() {
        let key: String = key.extract().map_err(|_| error::value(expected))?;
        if !["variable", "range", "step", "unit", "per"].contains(&key.as_str()) {
            return Err(error::value(format!(
                "free: `{key}`: expected the keys variable, range, step, unit and per"
            )));
        }
    }
    let number = |key: &str| -> PyResult<Option<f64>> {
        match dict.get_item(key)? {
            None => Ok(None),
            Some(v) if v.is_instance_of::<pyo3::types::PyBool>() => {
                Err(error::value(format!("free: {key}: expected a number")))
            }
            Some(v) => v
                .extract::<f64>()
                .map(Some)
                .map_err(|_| error::value(format!("free: {key}: expected a number"))),
        }
    };
    let variable: String = dict
        .get_item("variable")?
        .ok_or_else(|| error::value("free: a dict needs its variable"))?
        .extract()
        .map_err(|_| error::value("free: variable: expected a str"))?;
    let text = |key: &str| -> PyResult<Option<String>> {
        match dict.get_item(key)? {
            Some(v) if !v.is_none() => v
                .extract::<String>()
                .map(Some)
                .map_err(|_| error::value(format!("free: {key}: expected a str"))),
            _ => Ok(None),
        }
    };
    // A document's `free` entry as it is: `per` the configuration's, `unit` the variable's.
    let option = match text("per")? {
        Some(per) if variable == "configuration" => {
            FreeOption::parse(&format!("configuration={per}"))
        }
        Some(_) => return Err(error::value("free: per: only for the configuration")),
        None => FreeOption::from_parts(&variable, number("range")?, number("step")?),
    }
    .map_err(raise)?;
    let own = match &option.variable {
        Variable::Axis(_) => None,
        Variable::Configuration(_) => Some(""),
        v => Some(v.limits().unit),
    };
    match (text("unit")?, own) {
        (Some(u), Some(own)) if u != own => Err(error::value(format!(
            "free: unit {u}: {variable} is in {}",
            if own.is_empty() { "no unit" } else { own }
        ))),
        _ => Ok(option),
    }
}

/// Refuses a keyword that `free=` or `minimise=` replaced, saying how to write it.
fn refuse_retired(retired: Option<&Bound<'_, PyDict>>) -> PyResult<()> {
    let Some(key) = retired.and_then(|r| r.keys().into_iter().next()) else {
        return Ok(());
    };
    let key: String = key.extract()?;
    let Some((option, value)) = free::retired(&key.replace('_', "-")) else {
        return Err(pyo3::exceptions::PyTypeError::new_err(format!(
            "compensate() got an unexpected keyword argument '{key}'"
        )));
    };
    let how = match option {
        "free" => format!("free=[\"{value}\"]"),
        _ => format!("{option}=\"{value}\""),
    };
    Err(error::value(format!("{key}: removed; write {how}")))
}

/// The per-point results as arrays (see [`compensate`]).
fn table<'py>(
    py: Python<'py>,
    results: &[Compensated],
    points: &[PathPoint],
) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    let column = |f: &dyn Fn(&Compensated) -> f64| arrays::vec1(py, results.iter().map(f));
    let part = |f: &dyn Fn(&Compensated) -> Vector6<f64>, from: usize, scale: f64| {
        let rows: Vec<[f64; 3]> = results
            .iter()
            .map(|c| std::array::from_fn(|i| f(c)[from + i] * scale))
            .collect();
        arrays::table(py, &rows)
    };
    let lines = points.iter().map(|p| p.line);
    out.set_item("line", arrays::integers(py, lines))?;
    let q: Vec<_> = results.iter().map(|c| c.q).collect();
    let qc: Vec<_> = results.iter().map(|c| c.q_compensated).collect();
    out.set_item("q_deg", arrays::degrees(py, &q))?;
    out.set_item("q_compensated_deg", arrays::degrees(py, &qc))?;
    out.set_item("deflection_mm", part(&|c| c.deflection, 0, 1e3))?;
    out.set_item("deflection_mrad", part(&|c| c.deflection, 3, 1e3))?;
    out.set_item("force_n", part(&|c| c.wrench, 0, 1.0))?;
    out.set_item("residual_um", column(&|c| c.residual_position * 1e6))?;
    out.set_item("residual_urad", column(&|c| c.residual_rotation * 1e6))?;
    let iterations = results.iter().map(|c| c.iterations as u64);
    out.set_item("iterations", arrays::integers(py, iterations))?;
    out.set_item(
        "tool_rotation_deg",
        column(&|c| c.tool_rotation.to_degrees()),
    )?;
    out.set_item("lead_deg", column(&|c| c.lead.to_degrees()))?;
    out.set_item("tilt_deg", column(&|c| c.tilt.to_degrees()))?;
    let bound = |c: &Compensated| c.budget.bound * 1e3;
    out.set_item("bound_mm", column(&bound))?;
    let names = stiffid::internal::machining::compensate::budget::PARTS;
    for (k, name) in names.iter().enumerate() {
        let part = move |c: &Compensated| c.budget.parts()[k].map_or(f64::NAN, |v| v * 1e3);
        out.set_item(format!("bound_{name}_mm"), column(&part))?;
    }
    if results.iter().all(|c| c.deflection_std.is_some()) {
        let std = |c: &Compensated| c.deflection_std.unwrap_or_default();
        out.set_item("deflection_std_mm", part(&std, 0, 1e3))?;
    }
    if results.iter().all(|c| c.deflection_interval.is_some()) {
        for (end, key) in ["deflection_lower_mm", "deflection_upper_mm"]
            .iter()
            .enumerate()
        {
            let rows: Vec<[f64; 3]> = results
                .iter()
                .map(|c| {
                    c.deflection_interval
                        .unwrap_or_default()
                        .map(|i| i[end] * 1e3)
                })
                .collect();
            out.set_item(*key, arrays::table(py, &rows))?;
        }
    }
    Ok(out)
}

/// The date of generated programs: `SOURCE_DATE_EPOCH`'s when the environment sets it, else 0.
fn source_date() -> PyResult<i64> {
    match std::env::var(date::VARIABLE) {
        Err(_) => Ok(0),
        Ok(text) => date::epoch(&text).map_err(raise),
    }
}
