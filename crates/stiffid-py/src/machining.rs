//! `stiffid.process_force` and `stiffid.read_program`: the process forces of a process file
//! ([`stiffid::app::force`]) and the path of a machining program
//! ([`stiffid::app::compensate::read_program`]), as the command reads them.

use crate::arrays;
use crate::documents::to_python;
use crate::error::{self, raise};
use nalgebra::Vector6;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;
use stiffid::app::{compensate, force};
use stiffid::internal::machining::gcode::{Machine, Motion};
use stiffid::internal::machining::process::file;
use stiffid::internal::machining::program::speed::Speed;
use stiffid::internal::machining::program::{Context, JointProgram};
use stiffid::internal::machining::{Language, Program};

/// The mean cutting force of every operation of the process file ``process`` (TOML, the format
/// of ``stiffid force --process``), over one revolution, in the feed frame ``[feed, normal,
/// axial]`` (Altintas's linear edge-force model for milling, a specific-energy model for
/// drilling); with ``peak_resolution_deg`` (0.01 to 10) also the milling peak over a revolution
/// on a grid of spindle angles that far apart. Returns the document of ``stiffid force --json``:
/// ``kind`` (``"force"``), ``process``, ``peak_resolution_deg`` and ``operations``, each with
/// ``name``, ``kind``, ``mean_force_n``, ``mean_moment_nm`` and, when asked, ``peak_force_n``.
#[pyfunction]
#[pyo3(signature = (process, *, peak_resolution_deg=None))]
pub fn process_force<'py>(
    py: Python<'py>,
    process: PathBuf,
    peak_resolution_deg: Option<&Bound<'_, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let peak_resolution_deg = crate::count::real("peak_resolution_deg", peak_resolution_deg)?;
    let name = process.display().to_string();
    let parsed = file::parse(&error::read(&process)?, &name).map_err(raise)?;
    let request = force::Request {
        name,
        process: &parsed,
        peak_resolution_deg,
    };
    let outcome = force::run(&request).map_err(raise)?;
    to_python(py, outcome.written(), &[])
}

/// The path of the machining program ``program`` as ``stiffid compensate --program`` reads it:
/// G-code (``.nc .ngc .gcode .tap .cnc .g``; arcs split into chords of at most
/// ``chord_tolerance_mm`` sagitta), KUKA KRL (``.src .dat``), ABB RAPID (``.mod .modx .prg``) or
/// FANUC LS (``.ls``) joint targets, or a Yaskawa INFORM job (``.jbi``; its pulses per degree
/// from ``setup``'s ``[controller] pulses_per_deg``, or the job's ``'stiffid:`` comment, and its
/// tool files checked against ``setup``'s tool). Returns a dict: ``language`` (``"gcode"``,
/// ``"krl"``, ``"rapid"``, ``"ls"`` or ``"inform"``), ``line`` (``(n,)``, ``int64``: each point's line); for G-code
/// ``position_mm`` (``(n, 3)``, part frame), ``rapid`` (``(n,)`` bool: a ``G0`` move),
/// ``tool_number`` and ``operation`` (lists, ``None`` where none is in force); for a robot
/// program ``q_deg`` (``(n, 6)``, the joint targets' axis angles; ``NaN`` for a Cartesian
/// target, whose axis angles need the setup: ``compensate`` resolves them). Both carry the external
/// axes: ``external_axes`` (their names as the program gives them: KRL ``E1``, RAPID
/// ``eax_a``, a G-code header's letters ``U``..``C``, in the cell's order for G-code) and
/// ``external`` (``(n, k)``, each point's or target's values as written, mm for a linear axis
/// and deg for a rotary one; ``NaN`` where a robot target gives none, RAPID ``9E9`` or a KRL
/// member left out); ``k = 0`` for a program without external axes. Both carry ``feed_mm_s``
/// (``(n,)``: the TCP speed of the move to each point, a G-code feed move's ``F`` in force, a
/// robot program's programmed path speed of a linear motion; ``NaN`` elsewhere); a robot
/// program also ``joint`` (``(n,)`` bool: a joint motion, which the controller times),
/// ``time_s`` (``(n,)``: the move's time where the program gives it, RAPID ``\\T``, LS ``sec``;
/// ``NaN`` elsewhere) and ``speed_not_read`` (a list: why a linear motion's speed is not read, a
/// variable or a register; ``None`` where it is). A G-code program is read on the controller
/// ``setup`` (a ``Setup``: its ``[workpiece]`` work offsets, start and ``G28``/``G30``
/// positions and tool orientation) and ``process`` (a process file: its tools' ``length_mm``
/// for ``G43``) describe, as ``compensate`` reads it: the positions are the tool tip's in the
/// ``G54`` part frame.
#[pyfunction]
#[pyo3(signature = (program, *, chord_tolerance_mm=0.01, setup=None, process=None))]
pub fn read_program<'py>(
    py: Python<'py>,
    program: PathBuf,
    #[pyo3(from_py_with = crate::count::number)] chord_tolerance_mm: f64,
    setup: Option<PyRef<'py, crate::setup::Setup>>,
    process: Option<PathBuf>,
) -> PyResult<Bound<'py, PyDict>> {
    let name = program.display().to_string();
    let language = Language::of_file(&name).map_err(raise)?;
    // A KRL program's .dat beside it, read with it as compensate does.
    let (text, data, _) = error::read_program(&program)?;
    let process = match process {
        Some(p) => {
            let text = error::read(&p)?;
            Some(file::parse(&text, &p.display().to_string()).map_err(raise)?)
        }
        None => None,
    };
    let machine = match &setup {
        Some(s) => Machine::of(&s.inner, process.as_ref()),
        None => Machine {
            tool_lengths: process
                .as_ref()
                .map(|p| p.tool_lengths())
                .unwrap_or_default(),
            ..Default::default()
        },
    };
    let context = match &setup {
        Some(s) => Context::of(&s.inner),
        None => Context::default(),
    }
    .with_machine(&machine)
    .with_data(data.as_deref());
    let tolerance = chord_tolerance_mm * 1e-3;
    let read =
        compensate::read_program_in(&name, &text, language, tolerance, &context).map_err(raise)?;
    let out = PyDict::new(py);
    out.set_item("language", language.name())?;
    match &read {
        Program::GCode(g) => {
            out.set_item(
                "line",
                arrays::integers(py, g.points.iter().map(|p| p.line)),
            )?;
            let positions: Vec<_> = g.points.iter().map(|p| p.position).collect();
            out.set_item("position_mm", arrays::millimetres(py, &positions))?;
            let rapid: Vec<bool> = g.points.iter().map(|p| p.motion == Motion::Rapid).collect();
            out.set_item("rapid", numpy::PyArray1::from_vec(py, rapid))?;
            let tools: Vec<Option<u32>> = g.points.iter().map(|p| p.tool_number).collect();
            out.set_item("tool_number", tools)?;
            let ops: Vec<Option<String>> = g
                .points
                .iter()
                .map(|p| p.operation.as_deref().map(String::from))
                .collect();
            out.set_item("operation", ops)?;
            let feeds = g.points.iter().map(|p| match p.motion {
                Motion::Feed => p.feed.map_or(f64::NAN, |f| f * 1e3),
                Motion::Rapid => f64::NAN,
            });
            out.set_item("feed_mm_s", numpy::PyArray1::from_vec(py, feeds.collect()))?;
            let axes: Vec<String> = g.external.0.iter().map(char::to_string).collect();
            let values = arrays::grid(py, g.points.len(), axes.len(), |i, k| {
                g.points[i].external[k]
            });
            out.set_item("external", values)?;
            out.set_item("external_axes", axes)?;
        }
        Program::Robot(r) => {
            out.set_item(
                "line",
                arrays::integers(py, r.targets.iter().map(|t| t.line)),
            )?;
            let q: Vec<Vector6<f64>> = r
                .targets
                .iter()
                .map(|t| Vector6::from(t.q_deg).map(f64::to_radians))
                .collect();
            out.set_item("q_deg", arrays::degrees(py, &q))?;
            let values = arrays::grid(py, r.targets.len(), r.axes.len(), |i, k| {
                r.targets[i].external[k].unwrap_or(f64::NAN)
            });
            out.set_item("external", values)?;
            out.set_item("external_axes", r.axes.clone())?;
            speeds(py, &out, r)?;
        }
    }
    Ok(out)
}

/// A robot program's speeds into `out` (module docs of
/// [`stiffid::internal::machining::program::speed`]): `joint`, `feed_mm_s`, `time_s`, `speed_not_read`.
fn speeds(py: Python<'_>, out: &Bound<'_, PyDict>, r: &JointProgram) -> PyResult<()> {
    let of = |f: fn(&Speed) -> f64| {
        let values = r.targets.iter().map(|t| f(&t.speed)).collect();
        numpy::PyArray1::from_vec(py, values)
    };
    let joint: Vec<bool> = r.targets.iter().map(|t| t.speed == Speed::Joint).collect();
    out.set_item("joint", numpy::PyArray1::from_vec(py, joint))?;
    out.set_item(
        "feed_mm_s",
        of(|s| match s {
            Speed::Path(v) => v * 1e3,
            _ => f64::NAN,
        }),
    )?;
    out.set_item(
        "time_s",
        of(|s| match s {
            Speed::Duration(t) => *t,
            _ => f64::NAN,
        }),
    )?;
    let why: Vec<Option<String>> = (r.targets.iter())
        .map(|t| match &t.speed {
            Speed::Unread(why) => Some(why.clone()),
            _ => None,
        })
        .collect();
    out.set_item("speed_not_read", why)
}
