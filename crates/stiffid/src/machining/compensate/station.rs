//! The free track station: the carrier's first axis chosen at every point of a path file,
//! jointly with the rotation about tool z, by the dynamic programming of the free tool axis over
//! the grid of (station, rotation) pairs (module docs of [`super`], "The free station").

use super::feasible::Checks;
use super::stream::{compensate_chosen, nominal_postures, Chosen};
use super::tool_axis::{choose, column, rotation_axis, Axis, Column, Cost, Grid, Move};
use super::PathPoint;
use super::{Compensated, Compliance, FreeStation, FreeToolAxis, Model, Objective, Options};
use crate::common::error::JobOption;
use crate::machining::cell::{on_carriage, turned};
use crate::observation::deflection::base_wrench;
use crate::robot::external::{ExternalAxes, ExternalValues};
use crate::setup::Arm;
use crate::{Error, Result};
use nalgebra::{Isometry3, Vector6};
use rayon::prelude::*;

/// Compensates the points of a path file of a cell with a carrier (a track), as
/// [`crate::machining::path::points`] gives them (a pose is a point of the part, each point with
/// its external values), with the track station free ([`Options::free_station`]) and, with
/// [`Options::free_tool_axis`], the tool rotation too; each result's
/// [`Compensated::external`] holds the station chosen. The results are in the arm's frame on
/// its carriage at that station ([`crate::machining::cell::path_to_cell`] takes them to the
/// cell). Without a free station the points are compensated at their own values.
///
/// # Errors
/// Those of [`super::path`]; those of [`on_carriage`] for a point's external values;
/// [`Error::InvalidOption`] ([`JobOption::FreeStationMm`]) for a robot without a carrier axis
/// and for a grid of more than [`FreeToolAxis::MAX_GRID_CELLS`] cells (stations x rotations x
/// points).
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
    let Some(station) = &options.free_station else {
        let plain = Options {
            free_station: None,
            ..options.clone()
        };
        return given(super::path(arm, compliance, &placed, &plain)?, points);
    };
    let cell = carrier(robot.external())?;
    let angles = options.free_tool_axis.map_or(vec![0.0], |f| f.angles());
    let offsets = station.offsets();
    check_grid(station, offsets.len() * angles.len(), points.len())?;
    let model = Model::new(arm, compliance)?
        .at_level(options.level)
        .with_max_iterations(options.max_iterations)
        .with_force_tolerance(options.force_tolerance);
    let nominal = nominal_postures(arm, &placed, options.q0, options)?;
    let wrenches: Vec<Vector6<f64>> = (placed.par_iter().zip(&nominal))
        .map(|(p, q)| base_wrench(&robot.frames(q), &p.wrench, p.frame))
        .collect();
    let stations: Vec<Station> = (offsets.iter())
        .map(|&d| Station::new(cell, points, &wrenches, d))
        .collect();
    let cost = match station.objective {
        Objective::Deflection => Cost::Deflection,
        _ => Cost::Bound,
    };
    let columns: Vec<Column> = (0..stations.len() * angles.len())
        .into_par_iter()
        .map(|s| {
            let (k, g) = (s / angles.len(), s % angles.len());
            let st = &stations[k];
            let m = Move {
                phi: angles[g],
                shift: (offsets[k] != 0.0).then_some(st.shift.as_slice()),
            };
            let mut c = column(&model, &nominal, &st.wrenches, (m, &cost), &options.ik);
            for (cell, inside) in c.iter_mut().zip(&st.inside) {
                if !inside {
                    *cell = None;
                }
            }
            c
        })
        .collect();
    let mut axes = vec![station_axis(station, &offsets)];
    if let Some(f) = &options.free_tool_axis {
        axes.push(rotation_axis(f, &angles));
    }
    let checks = Checks::new(&model, &options.feasible, true);
    let (chosen, removed) = choose(
        &columns,
        &Grid { axes },
        (&cost, &checks),
        station.aggregate,
    );
    let pick = |i: usize, s: usize| {
        let st = &stations[s / angles.len()];
        let q = columns[s][i].as_ref().map_or(nominal[i], |c| c.0);
        (q, angles[s % angles.len()], st.wrenches[i], st.external[i])
    };
    let picked: Vec<_> = chosen
        .iter()
        .enumerate()
        .map(|(i, &s)| pick(i, s))
        .collect();
    let postures: Vec<Vector6<f64>> = picked.iter().map(|p| p.0).collect();
    let rotations: Vec<f64> = picked.iter().map(|p| p.1).collect();
    let moved: Vec<Vector6<f64>> = picked.iter().map(|p| p.2).collect();
    let at = Chosen {
        nominal: &nominal,
        postures: &postures,
        rotations: &rotations,
        wrenches: &moved,
        wrenches_before: &wrenches,
        removed: &removed,
    };
    let mut results = compensate_chosen(&model, &placed, &at, true)?;
    for (r, p) in results.iter_mut().zip(&picked) {
        r.external = p.3;
    }
    Ok(results)
}

/// Each result's external values: the point's own.
fn given(mut results: Vec<Compensated>, points: &[PathPoint]) -> Result<Vec<Compensated>> {
    for (r, p) in results.iter_mut().zip(points) {
        r.external = p.external;
    }
    Ok(results)
}

/// The cell's axes, refused without a carrier axis.
fn carrier(cell: Option<&ExternalAxes>) -> Result<&ExternalAxes> {
    cell.filter(|c| c.carrier_len() > 0)
        .ok_or_else(|| Error::InvalidOption {
            option: JobOption::FreeStationMm,
            message: "the robot has no carrier axis (a track): a free station moves the carrier's first axis, which the robot file's [[external_axis]] with role = \"carrier\" gives".into(),
        })
}

/// Refuses a grid of more than [`FreeToolAxis::MAX_GRID_CELLS`] cells.
fn check_grid(station: &FreeStation, states: usize, points: usize) -> Result<()> {
    let cells = states as f64 * points as f64;
    if cells <= FreeToolAxis::MAX_GRID_CELLS {
        return Ok(());
    }
    Err(Error::InvalidOption {
        option: JobOption::FreeStationMm,
        message: format!(
            "+-{} mm in steps of {} mm makes {states} states (stations x rotations) x {points} path points = {cells:.3e} cells; at most {:.0e} (a larger step, a smaller range, a coarser rotation grid or a shorter path)",
            station.range * 1e3,
            station.max_step * 1e3,
            FreeToolAxis::MAX_GRID_CELLS
        ),
    })
}

/// The grid's axis of the station over `offsets` ([`FreeStation::offsets`]).
fn station_axis<'a>(station: &FreeStation, offsets: &'a [f64]) -> Axis<'a> {
    Axis {
        values: offsets,
        reach: 1,
        range: station.range,
        max_step: station.max_step,
        zero: offsets.len() / 2,
    }
}

/// One offset of the station from each point's own: the values, whether they are within the
/// travel, the change of the arm's frame and the wrench in the moved arm's frame.
struct Station {
    external: Vec<ExternalValues>,
    inside: Vec<bool>,
    shift: Vec<Isometry3<f64>>,
    wrenches: Vec<Vector6<f64>>,
}

impl Station {
    /// The station `offset` (m) from each of `points`' own, `wrenches` the points' (the arm's
    /// frame at their own station).
    fn new(
        cell: &ExternalAxes,
        points: &[PathPoint],
        wrenches: &[Vector6<f64>],
        offset: f64,
    ) -> Self {
        let axis = &cell.axes()[0];
        let mut out = Station {
            external: Vec::with_capacity(points.len()),
            inside: Vec::with_capacity(points.len()),
            shift: Vec::with_capacity(points.len()),
            wrenches: Vec::with_capacity(points.len()),
        };
        for (p, w) in points.iter().zip(wrenches) {
            let own = p.external;
            let mut e = own;
            let mut values = own.as_slice().to_vec();
            values[0] += offset;
            if let Ok(moved) = ExternalValues::new(&values) {
                e = moved;
            }
            let shift = cell.carrier_pose(&values).inverse() * cell.carrier_pose(own.as_slice());
            out.inside
                .push(values[0] >= axis.lower && values[0] <= axis.upper);
            out.wrenches
                .push(turned(&shift.rotation.to_rotation_matrix(), w));
            out.shift.push(shift);
            out.external.push(e);
        }
        out
    }
}
