//! `stiffid.place`: where to clamp the part so that a G-code program's error bound is least
//! ([`stiffid::app::place`]), as `stiffid place` does.

use crate::documents::to_python;
use crate::error::{self, raise};
use crate::setup::Setup;
use pyo3::prelude::*;
use pyo3::types::{PyAny, PyDict};
use std::path::PathBuf;
use stiffid::app::place::Effort;
use stiffid::app::place::{self as job, Region, Request, Work};
use stiffid::internal::machining::compensate::Aggregate;
use stiffid::internal::machining::process::file;
use stiffid::internal::machining::Language;
use stiffid::internal::observation::deflection::Frame;

/// The placement of the part that minimises the error bound of the G-code ``program`` (cut with
/// the process file ``process``; a robot program's controller backup ``backup``, a path or a
/// list of files or folders, as ``compensate`` reads it), or of the path CSV ``path`` (each row's TCP pose in the part
/// frame, a wrench in ``frame`` ``"base"``, the part frame, or ``"tool"`` where the row gives
/// none; not with ``program``), on the setup file ``setup`` (a ``.toml`` path with its
/// ``[workpiece] base_from_part``, the part's own placement) with the stiffness ``stiffness``
/// (numbers per parameter or a stiffness file, as ``compensate``): the part frame's origin
/// within ``region_mm`` ``(x0, x1, y0, y1)`` of the robot base frame, turned about the base z axis
/// within ``rotation_deg`` from its own; ``free``, a list of the texts of ``stiffid place
/// --free``, also moves its height (``"z"``: its own +-100 mm, ``"z=LO..HI"``: mm from its own)
/// and tilts it about the base x and y axes (``"tilt"``: within +-10 deg, ``"tilt=-T..T"``).
/// Every point must be reachable from ``q0_deg`` without a change of
/// configuration, every axis ``margin_deg`` from its joint limits, the TCP Jacobian's condition
/// number at most ``max_condition`` and, with a ``[cell]``, clear of the floor, the obstacles
/// and itself. It minimises the path's largest bound (``objective="max"``) or their sum
/// (``"sum"``) at ``level``, by a grid (``grid`` values per coordinate), ``samples`` random
/// placements (``seed``) and ``starts`` local searches: the same ``seed``, the same placement.
/// Returns the document of ``stiffid place --json`` (``placed``, ``own``, ``reach_only``: each
/// with ``xyz_mm``, ``rpy_deg``, ``peak_bound_mm``, ``mean_bound_mm``, ``worst_line``,
/// ``min_limit_margin_deg``, ``max_condition``, ``min_clearance_mm``; ``gain_vs_own_pct``,
/// ``gain_vs_reach_only_pct``, ``evaluations``) and ``setup_text``: the setup file's text
/// with the chosen ``[workpiece]``, as ``stiffid place --out`` writes it.
#[pyfunction]
#[pyo3(signature = (setup, stiffness, *, program=None, process=None, backup=None, path=None, frame="base", region_mm, rotation_deg=(-180.0, 180.0), free=None, objective="max", margin_deg=5.0, max_condition=1000.0, seed=1, grid=5, samples=32, starts=3, chord_tolerance_mm=0.01, level=0.95, force_tolerance_pct=20.0, q0_deg=None, **retired))]
#[allow(clippy::too_many_arguments)]
pub fn place<'py>(
    py: Python<'py>,
    setup: PathBuf,
    stiffness: &Bound<'py, PyAny>,
    program: Option<PathBuf>,
    process: Option<PathBuf>,
    backup: Option<&Bound<'py, PyAny>>,
    path: Option<PathBuf>,
    frame: &str,
    region_mm: [f64; 4],
    rotation_deg: (f64, f64),
    free: Option<&Bound<'py, PyAny>>,
    objective: &str,
    #[pyo3(from_py_with = crate::count::number)] margin_deg: f64,
    #[pyo3(from_py_with = crate::count::number)] max_condition: f64,
    #[pyo3(from_py_with = crate::count::seed_of)] seed: u64,
    #[pyo3(from_py_with = crate::count::whole)] grid: i64,
    #[pyo3(from_py_with = crate::count::whole)] samples: i64,
    #[pyo3(from_py_with = crate::count::whole)] starts: i64,
    #[pyo3(from_py_with = crate::count::number)] chord_tolerance_mm: f64,
    #[pyo3(from_py_with = crate::count::number)] level: f64,
    #[pyo3(from_py_with = crate::count::number)] force_tolerance_pct: f64,
    q0_deg: Option<&Bound<'py, PyAny>>,
    retired: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    refuse_retired(retired)?;
    let free = free_texts(free)?;
    let setup_text = error::read(&setup)?;
    let s = Setup::from_file(py, setup, Vec::new())?;
    let s = &s.inner;
    let compliance = crate::stiffness::compliance(s, stiffness, None, "stiffness")?;
    let mut options = crate::compensate::options(py, s, q0_deg)?;
    options.level = level;
    options.force_tolerance = force_tolerance_pct / 100.0;
    let (read, parsed, points, files);
    let work = match (&program, &process, &path) {
        (Some(_), Some(_), None) if frame.parse::<Frame>().map_err(raise)? != Frame::Base => {
            return Err(error::value(
                "frame: only with path= (the frame of a path CSV's wrenches): a program's wrench is its process file's, where the tool cuts",
            ))
        }
        (Some(program), Some(process_path), None) => {
            let name = program.display().to_string();
            let language = Language::of_file(&name).map_err(raise)?;
            // A KRL program's .dat beside it, read with it as compensate does.
            let (text, data, _) = error::read_program(program)?;
            files = match backup {
                Some(b) => error::read_backup(&crate::compensate::backup_paths(b)?, &name)?,
                None => Vec::new(),
            };
            let tolerance = chord_tolerance_mm * 1e-3;
            let process_name = process_path.display().to_string();
            parsed = file::parse(&error::read(process_path)?, &process_name).map_err(raise)?;
            let how = (tolerance, &parsed);
            let files = (text.as_str(), data.as_deref(), files.as_slice());
            read = job::read_program_with(s, &name, files, language, how).map_err(raise)?;
            Work::Program {
                program: &read,
                process: &parsed,
            }
        }
        (None, None, Some(_)) if backup.is_some() => {
            return Err(error::value("backup: only with program= and process="))
        }
        (None, None, Some(p)) => {
            let frame = frame.parse::<Frame>().map_err(raise)?;
            let text = error::read(p)?;
            points = job::read_path(s, &p.display().to_string(), &text, frame).map_err(raise)?;
            Work::Path(&points)
        }
        _ => {
            return Err(error::value(
                "expected program= and process= (a G-code program and its process file), or path= (a path CSV), not both",
            ))
        }
    };
    let own = s.workpiece().copied();
    let region = Region::from_mm_deg(
        region_mm,
        [rotation_deg.0, rotation_deg.1],
        &free,
        own.map_or(0.0, |o| o.translation.vector.z),
    )
    .map_err(raise)?;
    let request = Request {
        setup: s,
        setup_text: &setup_text,
        compliance: &compliance,
        work,
        options: &options,
        region,
        objective: objective.parse::<Aggregate>().map_err(raise)?,
        margin: margin_deg.to_radians(),
        max_condition,
        effort: Effort {
            grid: crate::count::count("grid", grid)?,
            samples: crate::count::count("samples", samples)?,
            starts: crate::count::count("starts", starts)?,
            seed,
        },
    };
    let outcome = py.detach(|| job::run(&request)).map_err(raise)?;
    crate::documents::warn(py, &outcome.warnings)?;
    let out = to_python(py, outcome.written(), &[])?;
    out.set_item("setup_text", &outcome.setup_text)?;
    Ok(out)
}

/// `free=`: a list of the texts of `stiffid place --free` (`"z=-50..150"`, `"tilt"`).
fn free_texts(free: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<String>> {
    let Some(free) = free else {
        return Ok(Vec::new());
    };
    let expected = "free: expected a list of str, the texts of `stiffid place --free`: [\"z\", \"tilt\"] (the height +-100 mm and the tilt +-10 deg), [\"z=-50..150\"] (mm from the part's own height), [\"tilt=-5..5\"] (deg)";
    if free.is_instance_of::<pyo3::types::PyString>()
        || free.is_instance_of::<pyo3::types::PyBool>()
    {
        return Err(error::value(expected));
    }
    free.extract::<Vec<String>>()
        .map_err(|_| error::value(expected))
}

/// Refuses `z_mm=` and `tilt_deg=`, which `free=` replaced, saying how to write them; any
/// other keyword as Python would.
fn refuse_retired(retired: Option<&Bound<'_, PyDict>>) -> PyResult<()> {
    let Some(key) = retired.and_then(|r| r.keys().into_iter().next()) else {
        return Ok(());
    };
    let key: String = key.extract()?;
    let how = match key.as_str() {
        "z_mm" => "free=[\"z=LO..HI\"] (the height's range, mm from the part's own)",
        "tilt_deg" => "free=[\"tilt=-T..T\"] (deg)",
        _ => {
            return Err(pyo3::exceptions::PyTypeError::new_err(format!(
                "place() got an unexpected keyword argument '{key}'"
            )))
        }
    };
    Err(error::value(format!("{key}: removed; write {how}")))
}
