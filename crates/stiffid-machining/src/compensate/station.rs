//! The free track station and the free positioner: the carrier's first axis, a two-axis
//! positioner's first (the tilt) and the positioner's last (the table) chosen at every point of
//! a path file or a program, jointly with the rotation about tool z, by the dynamic programming
//! of the free tool axis over the grid of (station, tilt, table angle, rotation) states (module
//! docs of [`super`], "The free station").

use super::feasible::{Checks, Removed};
use super::lead_tilt::{cones, lean_count, Leaning};
use super::refine::{refine, Evaluate, Layout, Line};
use super::stream::{compensate_chosen, nominal_postures, path_in_cones, Chosen};
use super::tool_axis::{choose, column, lean_axes, rotation_axis, Axis, Column, Cost, Grid, Move};
use super::PathPoint;
use super::{Compensated, Compliance, FreeRange, Model, Objective, Options, MAX_GRID_CELLS};
use crate::cell::{on_carriage, turned};
use nalgebra::{Isometry3, Vector3, Vector6};
use rayon::prelude::*;
use stiffid_core::common::error::JobOption;
use stiffid_core::observation::deflection::base_wrench;
use stiffid_core::robot::external::{ExternalAxes, ExternalValues};
use stiffid_core::robot::ik::tool_pose;
use stiffid_core::setup::{Arm, Payload};
use stiffid_core::{Error, Result};

/// Compensates the points of a path file of a cell with a carrier (a track), as
/// [`crate::path::points`] gives them (a pose is a point of the part, each point with
/// its external values), with the track station free (`super::FreeVariables::station`) and, with
/// [`super::FreeVariables::tool_rotation`], the tool rotation too; each result's
/// [`Compensated::external`] holds the station chosen. The results are in the arm's frame on
/// its carriage at that station ([`crate::cell::path_to_cell`] takes them to the
/// cell). Without a free station the points are compensated at their own values.
///
/// # Errors
/// Those of [`super::path`]; those of [`on_carriage`] for a point's external values;
/// [`Error::InvalidOption`] ([`JobOption::StationRange`]) for a robot without a carrier axis and
/// for a grid of more than 5 000 000 cells (stations x rotations x points).
pub fn path_on_track(
    arm: &Arm,
    compliance: &Compliance,
    points: &[PathPoint],
    options: &Options,
) -> Result<Vec<Compensated>> {
    options.validate()?;
    let robot = arm.robot();
    let placed: Vec<PathPoint> = (points.iter())
        .map(|p| on_carriage(robot, p.clone()))
        .collect::<Result<_>>()?;
    let own: Vec<ExternalValues> = points.iter().map(|p| p.external).collect();
    let cones = match &options.free.lead_tilt() {
        Some(l) => cones(l, points.len(), None)?,
        None => Vec::new(),
    };
    on_track(arm, compliance, &placed, (&own, false, &cones), options)
}

/// Compensates `placed`, points in the arm's frame on its carriage at their own external values
/// `own` (a path file's points placed by [`on_carriage`], a program's placed by
/// [`crate::compensate()`]), with the station free ([`super::FreeVariables::station`]), the
/// positioner's angles free ([`super::FreeVariables::positioner`], [`super::FreeVariables::tilt`]) and the tool
/// rotation with
/// [`super::FreeVariables::tool_rotation`]; each result's [`Compensated::external`] holds the values chosen,
/// its postures in the arm's frame on the carriage at them. `weighted`: the points' wrenches
/// hold the tool's weight ([`stiffid_core::setup::Payload::wrench`] at the nominal pose, a program's),
/// which stays along the cell's `-z` when the positioner turns the tool with the part. Without
/// a free station or positioner, the points at their own values.
///
/// # Errors
/// Those of [`path_on_track`]; [`Error::InvalidOption`] ([`JobOption::PositionerRange`]) for
/// a cell without a positioner axis, ([`JobOption::TiltRange`]) without a two-axis
/// positioner.
pub(crate) fn on_track(
    arm: &Arm,
    compliance: &Compliance,
    placed: &[PathPoint],
    (own, weighted, cones): (&[ExternalValues], bool, &[f64]),
    options: &Options,
) -> Result<Vec<Compensated>> {
    options.validate()?;
    let robot = arm.robot();
    let (objective, aggregate) = (options.free.minimise, options.free.aggregate);
    if !options.free.frees_external() {
        let mut plain = options.clone();
        plain.free = plain.free.keeping(|f| !f.is_external());
        let results = path_in_cones(arm, compliance, placed, (&[], cones), &plain)?;
        return given(results, own);
    }
    let (cell, free) = free_axes(robot.external(), options)?;
    let angles = options
        .free
        .tool_rotation()
        .map_or(vec![0.0], |f| f.angles());
    let states = states(&free);
    let sizes = (states.len(), angles.len(), free.len());
    check_sizes(options, sizes, cones, placed.len())?;
    let model = Model::new(arm, compliance)?
        .at_level(options.level)
        .with_max_iterations(options.max_iterations)
        .with_force_tolerance(options.force_tolerance);
    let nominal = nominal_postures(arm, placed, options.q0, options)?;
    let wrenches: Vec<Vector6<f64>> = (placed.par_iter().zip(&nominal))
        .map(|(p, q)| base_wrench(&robot.frames(q), &p.wrench, p.frame))
        .collect();
    let at = Own {
        values: own,
        wrenches: &wrenches,
        poses: (nominal.iter())
            .map(|q| tool_pose(&robot.frames(q), &arm.tool().tcp))
            .collect(),
        weight: weighted.then(|| arm.payload()).flatten(),
        tcp: arm.tool().tcp,
    };
    let stations: Vec<Station> = (states.par_iter())
        .map(|moves| Station::new(cell, &at, moves))
        .collect();
    let leaning = Leaning::new(options.free.lead_tilt().as_ref(), &at.poses, cones.to_vec());
    let cost = match objective {
        Objective::Deflection => Cost::Deflection,
        _ => Cost::Bound,
    };
    let grid = (angles.as_slice(), &leaning);
    let columns = grid_columns(&model, &nominal, &stations, &states, grid, (&cost, options));
    let per_station = leaning.len() * angles.len();
    let mut axes: Vec<Axis> = free.iter().map(FreeAxis::axis).collect();
    axes.extend(lean_axes(&leaning));
    if let Some(f) = &options.free.tool_rotation() {
        axes.push(rotation_axis(f, &angles));
    }
    let checks = Checks::new(&model, &options.feasible);
    let external: Vec<&[ExternalValues]> = (0..columns.len())
        .map(|s| stations[s / per_station].external.as_slice())
        .collect();
    let grid = Grid { axes };
    let (chosen, mut removed) = choose((&columns, &external), &grid, (&cost, &checks), aggregate);
    let layout = Layout::new(free.len(), &leaning, options.free.tool_rotation().is_some());
    let along = |values: &[Vec<f64>]| {
        let moves: Vec<Vec<(usize, f64)>> = (values.iter())
            .map(|v| free.iter().zip(v).map(|(f, &d)| (f.index, d)).collect())
            .collect();
        Station::along(cell, &at, |i| &moves[i])
    };
    let evaluate = |values: &[Vec<f64>]| {
        let st = along(values);
        let line: Vec<[f64; 3]> = values.iter().map(|v| layout.turn_lean(v)).collect();
        let m = Move {
            phi: 0.0,
            shift: Some(&st.shift),
            lean: leaning.at(leaning.len() / 2),
            line: Some(&line),
        };
        let c = column(&model, &nominal, &st.wrenches, (m, &cost), &options.ik);
        (within_travel(c, &st.inside), st.external)
    };
    let refined = (options.refine, &evaluate as &Evaluate);
    let line = refine(
        &grid,
        (&columns, &chosen, &external),
        refined,
        (&cost, &checks),
        aggregate,
        &mut removed,
    );
    let st = along(&line.values);
    let before = (wrenches.as_slice(), removed.as_slice());
    compensate_line(&model, placed, (&line, st), &layout, &nominal, before)
}

/// The grid's size and the refinement's checked against their limits ([`check_grid`],
/// [`super::refine::check`]): `states` of the free external axes, `angles` about tool z, `free`
/// external axes.
fn check_sizes(
    options: &Options,
    (states, angles, free): (usize, usize, usize),
    cones: &[f64],
    points: usize,
) -> Result<()> {
    let largest = cones.iter().copied().fold(0.0, f64::max);
    let leans = (options.free.lead_tilt().as_ref()).map_or(1.0, |l| lean_count(l, largest));
    check_grid(options, (states * angles) as f64 * leans, points)?;
    let lean_axes_count = 2 * usize::from(options.free.lead_tilt().is_some());
    let axes = free + lean_axes_count + usize::from(options.free.tool_rotation().is_some());
    super::refine::check(options.refine, axes, points)
}

/// The grid's columns, one per station state, lean and rotation about tool z (in that order of
/// nesting), each point's cell; none beyond the travel.
fn grid_columns(
    model: &Model,
    nominal: &[Vector6<f64>],
    stations: &[Station],
    states: &[Vec<(usize, f64)>],
    (angles, leaning): (&[f64], &Leaning),
    (cost, options): (&Cost, &Options),
) -> Vec<Column> {
    let (a, per_station) = (angles.len(), leaning.len() * angles.len());
    (0..stations.len() * per_station)
        .into_par_iter()
        .map(|s| {
            let k = s / per_station;
            let st = &stations[k];
            // A state beyond the travel at every point is no state: no inverse kinematics.
            if !st.inside.contains(&true) {
                return vec![None; nominal.len()];
            }
            let m = Move {
                phi: angles[s % a],
                shift: states[k]
                    .iter()
                    .any(|m| m.1 != 0.0)
                    .then_some(st.shift.as_slice()),
                lean: leaning.at(s % per_station / a),
                line: None,
            };
            let c = column(model, nominal, &st.wrenches, (m, cost), &options.ik);
            within_travel(c, &st.inside)
        })
        .collect()
}

/// `column` without the cells of the points beyond the travel (`inside` false).
fn within_travel(mut column: Column, inside: &[bool]) -> Column {
    for (cell, inside) in column.iter_mut().zip(inside) {
        if !inside {
            *cell = None;
        }
    }
    column
}

/// The points compensated along the refined `line` at the station `st` it moves them to: each
/// at its chosen posture, rotation, lean and external values, from its `nominal` posture; the
/// wrenches at the points' own values and the states the checks removed.
fn compensate_line(
    model: &Model,
    placed: &[PathPoint],
    (line, st): (&Line, Station),
    layout: &Layout,
    nominal: &[Vector6<f64>],
    (wrenches, removed): (&[Vector6<f64>], &[Removed]),
) -> Result<Vec<Compensated>> {
    let postures: Vec<Vector6<f64>> = (line.cells.iter().zip(nominal))
        .map(|(c, q)| c.as_ref().map_or(*q, |c| c.0))
        .collect();
    let turned: Vec<[f64; 3]> = line.values.iter().map(|v| layout.turn_lean(v)).collect();
    let rotations: Vec<f64> = turned.iter().map(|t| t[0]).collect();
    let leans: Vec<(f64, f64)> = turned.iter().map(|t| (t[1], t[2])).collect();
    let moved = st.wrenches;
    let at = Chosen {
        nominal,
        postures: &postures,
        rotations: &rotations,
        leans: &leans,
        wrenches: &moved,
        wrenches_before: wrenches,
        removed,
    };
    let mut results = compensate_chosen(model, placed, &at, true)?;
    for (r, e) in results.iter_mut().zip(st.external) {
        r.external = e;
    }
    Ok(results)
}

/// Each result's external values: the point's own.
fn given(mut results: Vec<Compensated>, own: &[ExternalValues]) -> Result<Vec<Compensated>> {
    for (r, e) in results.iter_mut().zip(own) {
        r.external = *e;
    }
    Ok(results)
}

/// One free external axis: its index in the cell, its offsets from the path's own values (m or
/// rad, ascending, 0 among them), its range and step.
pub(super) struct FreeAxis {
    index: usize,
    offsets: Vec<f64>,
    range: f64,
    max_step: f64,
}

impl FreeAxis {
    /// The grid's axis over the offsets.
    fn axis(&self) -> Axis<'_> {
        Axis {
            values: &self.offsets,
            reach: 1,
            range: self.range,
            max_step: self.max_step,
            zero: self.offsets.len() / 2,
        }
    }
}

/// The cell and the free external axes of `options` in the cell's order: the carrier's first
/// axis for the free station, a two-axis positioner's first for the free tilt, the positioner's
/// last for the free positioner; each refused where the cell lacks it.
pub(super) fn free_axes<'a>(
    cell: Option<&'a ExternalAxes>,
    options: &Options,
) -> Result<(&'a ExternalAxes, Vec<FreeAxis>)> {
    let carriers = cell.map_or(0, ExternalAxes::carrier_len);
    let positioners = cell.map_or(0, ExternalAxes::len) - carriers;
    let mut out = Vec::new();
    if let Some(s) = &options.free.station() {
        if carriers == 0 {
            return Err(Error::InvalidOption {
                option: JobOption::StationRange,
                message: "the robot has no carrier axis (a track): a free station moves the carrier's first axis, which the robot file's [[external_axis]] with role = \"carrier\" gives".into(),
            });
        }
        out.push(FreeAxis {
            index: 0,
            offsets: s.offsets(),
            range: s.range,
            max_step: s.step,
        });
    }
    if let Some(p) = &options.free.tilt() {
        if positioners < 2 {
            return Err(Error::InvalidOption {
                option: JobOption::TiltRange,
                message: format!("the robot's positioner has {positioners} axis(es): a free tilt turns a two-axis positioner's first axis (the table's turn, its last, is --free positioner), which the robot file's [[external_axis]] with role = \"positioner\" give"),
            });
        }
        out.push(FreeAxis {
            index: carriers,
            offsets: p.offsets(),
            range: p.range,
            max_step: p.step,
        });
    }
    if let Some(p) = &options.free.positioner() {
        if positioners == 0 {
            return Err(Error::InvalidOption {
                option: JobOption::PositionerRange,
                message: "the robot has no positioner axis: a free positioner turns the positioner's last axis, which the robot file's [[external_axis]] with role = \"positioner\" gives".into(),
            });
        }
        out.push(FreeAxis {
            index: carriers + positioners - 1,
            offsets: p.offsets(),
            range: p.range,
            max_step: p.step,
        });
    }
    match cell {
        Some(cell) if !out.is_empty() => Ok((cell, out)),
        _ => Err(Error::InvalidOption {
            option: JobOption::StationRange,
            message: "no free external axis given".into(),
        }),
    }
}

/// Every combination of the free axes' offsets, `(axis index, offset)` per free axis, the last
/// axis' offset running fastest (the order of [`Grid`]'s states).
pub(super) fn states(free: &[FreeAxis]) -> Vec<Vec<(usize, f64)>> {
    free.iter().fold(vec![Vec::new()], |states, a| {
        (states.iter())
            .flat_map(|s| {
                a.offsets.iter().map(move |&d| {
                    let mut s = s.clone();
                    s.push((a.index, d));
                    s
                })
            })
            .collect()
    })
}

/// Refuses a grid of more than [`MAX_GRID_CELLS`] cells.
pub(super) fn check_grid(options: &Options, states: f64, points: usize) -> Result<()> {
    let cells = states * points as f64;
    if cells <= MAX_GRID_CELLS {
        return Ok(());
    }
    let degrees = |p: &FreeRange| {
        let (range, step) = (p.range.to_degrees(), p.step.to_degrees());
        format!("+-{range} deg in steps of {step} deg")
    };
    let (option, what) = match (&options.free.station(), &options.free.positioner()) {
        (Some(s), _) => (
            JobOption::StationRange,
            format!("+-{} mm in steps of {} mm", s.range * 1e3, s.step * 1e3),
        ),
        (None, Some(p)) => (JobOption::PositionerRange, degrees(p)),
        (None, None) => match &options.free.tilt() {
            Some(p) => (JobOption::TiltRange, degrees(p)),
            None => (JobOption::StationRange, String::new()),
        },
    };
    Err(Error::InvalidOption {
        option,
        message: format!(
            "{what} makes {states} states (stations x tilts x table angles x leans x rotations) x {points} path points = {cells:.3e} cells; at most {:.0e} (a larger step, a smaller range, a coarser rotation grid or a shorter path)",
            MAX_GRID_CELLS
        ),
    })
}

/// The points at their own external values: the values, the wrenches (the arm's frame on the
/// carriage there), the nominal TCP poses (the same frame) and the tool's weight the wrenches
/// hold (`None`: none).
pub(super) struct Own<'a> {
    pub values: &'a [ExternalValues],
    pub wrenches: &'a [Vector6<f64>],
    pub poses: Vec<Isometry3<f64>>,
    pub weight: Option<&'a Payload>,
    pub tcp: Vector3<f64>,
}

impl Own<'_> {
    /// The weight's wrench in the arm's frame on the carriage `carrier` of a tool at `pose`
    /// (that frame); zero without one.
    fn weight(&self, carrier: &Isometry3<f64>, pose: &Isometry3<f64>) -> Vector6<f64> {
        self.weight.map_or(Vector6::zeros(), |w| {
            let inverse = carrier.rotation.inverse().to_rotation_matrix();
            turned(&inverse, &w.wrench(&(carrier * pose).rotation, &self.tcp))
        })
    }
}

/// One state of the free external axes: the values, whether they are within the travel, the
/// change of a point's pose in the arm's frame and the wrench in the moved arm's frame.
pub(super) struct Station {
    pub external: Vec<ExternalValues>,
    pub inside: Vec<bool>,
    pub shift: Vec<Isometry3<f64>>,
    pub wrenches: Vec<Vector6<f64>>,
}

impl Station {
    /// The state `moves` (per free axis its index and offset, m or rad) from the points' own
    /// values. The part moves with the positioner, so a point's pose in the arm's frame moves
    /// by `C(e')^-1 P(e') P(e)^-1 C(e)` (module docs of [`stiffid_core::robot::external`]); the
    /// process wrench turns with it (the cut follows the part) and the tool's weight stays along
    /// the cell's `-z` at the turned tool.
    pub(super) fn new(cell: &ExternalAxes, at: &Own, moves: &[(usize, f64)]) -> Self {
        Self::along(cell, at, |_| moves)
    }

    /// [`Station::new`] with each point's own `moves(i)` (a refined line's, [`super::refine`]).
    pub(super) fn along<'m>(
        cell: &ExternalAxes,
        at: &Own,
        moves: impl Fn(usize) -> &'m [(usize, f64)],
    ) -> Self {
        let values = (at.values.iter().enumerate()).map(|(i, own)| {
            let mut values = own.as_slice().to_vec();
            for &(k, d) in moves(i) {
                values[k] += d;
            }
            values
        });
        Self::at_values(cell, at, values)
    }

    /// Each point moved from its own values to its own of `values` (the cell's order, SI), as
    /// [`Station::new`] moves them.
    pub(super) fn at_values(
        cell: &ExternalAxes,
        at: &Own,
        values: impl Iterator<Item = Vec<f64>>,
    ) -> Self {
        let n = at.values.len();
        let mut out = Station {
            external: Vec::with_capacity(n),
            inside: Vec::with_capacity(n),
            shift: Vec::with_capacity(n),
            wrenches: Vec::with_capacity(n),
        };
        for (i, (own, values)) in at.values.iter().zip(values).enumerate() {
            // Only the moved axes: the own values are the path's or the program's.
            let inside = (cell.axes().iter().zip(&values).zip(own.as_slice()))
                .all(|((a, v), o)| v == o || (*v >= a.lower && *v <= a.upper));
            let e = ExternalValues::new(&values).unwrap_or(*own);
            let (from, to) = (own.as_slice(), values.as_slice());
            let (c, c_moved) = (cell.carrier_pose(from), cell.carrier_pose(to));
            let shift = c_moved.inverse()
                * cell.positioner_pose(to)
                * cell.positioner_pose(from).inverse()
                * c;
            let weight = at.weight(&c, &at.poses[i]);
            let process = turned(
                &shift.rotation.to_rotation_matrix(),
                &(at.wrenches[i] - weight),
            );
            let moved_pose = shift * at.poses[i];
            out.wrenches
                .push(process + at.weight(&c_moved, &moved_pose));
            out.inside.push(inside);
            out.shift.push(shift);
            out.external.push(e);
        }
        out
    }
}
