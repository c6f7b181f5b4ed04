//! The map of one free variable along a path: for every path point and every value of the
//! variable, the error bound, the deflection, the condition number of the TCP Jacobian, the
//! distance to the joint limits and, in a cell with bodies to clear, the distance to them. The
//! variable is the rotation about the spindle on the free tool axis' grid
//! ([`MapVariable::Rotation`]) or the track station on the free station's grid
//! ([`MapVariable::Track`]); each value's
//! postures continued along the path by inverse kinematics as the optimisation takes them
//! (module docs of [`super`], "The free tool axis", "The free station"). The collision distance
//! is that of the robot's bodies (and the tool's capsule) to the cell's floor and obstacles
//! ([`crate::cell::body_floor`], [`crate::cell::body_box`]; the base stands on the floor), the
//! arm on its carriage at the point's station; the robot's self-collision is not mapped.

use super::station::{free_axes, states, Own, Station};
use super::stream::nominal_postures;
use super::tool_axis::{column, Cost, Move};
use super::{Compliance, FreeStation, FreeToolAxis, MapVariable, Model, Options, PathPoint};
use crate::cell::{bodies, body_box, body_floor, Part};
use crate::common::error::JobOption;
use crate::math::jacobi;
use crate::observation::deflection::base_wrench;
use crate::robot::external::ExternalValues;
use crate::robot::ik::tool_pose;
use crate::robot::kinematics::Coordinates;
use crate::setup::{Arm, Cell};
use crate::{Error, Result};
use nalgebra::{DMatrix, Vector6};
use rayon::prelude::*;

/// The map (module docs). Every matrix has one row per path point (path order) and one column
/// per value of the variable; `NaN` where inverse kinematics does not reach the moved pose or
/// the station is beyond the track's travel.
#[derive(Debug, Clone, PartialEq)]
pub struct Map {
    /// Each path point's line in its file.
    pub lines: Vec<u64>,
    /// The variable mapped.
    pub variable: MapVariable,
    /// With [`MapVariable::Rotation`], the columns: the rotations about tool z from the path's
    /// own, rad, ascending (the grid of the free tool axis, or of [`Map::DEFAULT_STEP_DEG`] and
    /// [`Map::DEFAULT_RANGE_DEG`] without one); empty for the track.
    pub angles: Vec<f64>,
    /// With [`MapVariable::Track`], the columns: the station's offsets from the path's own, m,
    /// ascending (the grid of the free station, or of [`Map::DEFAULT_STATION_STEP_MM`] and
    /// [`Map::DEFAULT_STATION_RANGE_MM`] without one); empty for the rotation.
    pub stations: Vec<f64>,
    /// The error bound ([`super::Budget`], without the residual the Newton steps leave), m.
    pub bound: DMatrix<f64>,
    /// The TCP translation deflection under the point's wrench, m.
    pub deflection: DMatrix<f64>,
    /// The condition number of the TCP Jacobian (axis coordinates, rows `[v; omega]` in m/rad
    /// and rad/rad): larger near a singularity.
    pub condition: DMatrix<f64>,
    /// The smallest distance of an axis angle to its joint limits, rad.
    pub limit_distance: DMatrix<f64>,
    /// The smallest distance of the robot's bodies to the cell's floor and obstacles (m,
    /// negative: penetration; module docs); `None` for a cell without a floor or obstacles.
    pub collision_distance: Option<DMatrix<f64>>,
    /// The value chosen at every point (the rotation, rad, or the station's offset, m; the
    /// path's own, 0, where the variable is not free): the line drawn on the map; empty until
    /// the compensate job fills it.
    pub chosen: Vec<f64>,
}

impl Map {
    /// The grid's step without a free tool axis, deg.
    pub const DEFAULT_STEP_DEG: f64 = 5.0;
    /// The grid's range without a free tool axis, deg.
    pub const DEFAULT_RANGE_DEG: f64 = 90.0;
    /// The track map's step without a free station, mm.
    pub const DEFAULT_STATION_STEP_MM: f64 = 50.0;
    /// The track map's range without a free station, mm.
    pub const DEFAULT_STATION_RANGE_MM: f64 = 1000.0;
}

/// The map of `points` (module docs; in the arm's frame on its carriage at each point's own
/// external values, as the compensation takes them) over [`Options::map_over`]: the free tool
/// axis' grid of `options` (else a 5 deg grid within +-90 deg), or the free station's (else a
/// 50 mm grid within +-1000 mm), under the error budget of `options`; `cell` the setup's
/// `[cell]` (the collision distance, with a floor or obstacles).
///
/// # Errors
/// Those of [`super::path`] for the options, the grid's size and the nominal postures; for the
/// track, those of [`super::path_on_track`] for a robot without a carrier axis and the grid's
/// size.
pub fn map(
    arm: &Arm,
    compliance: &Compliance,
    points: &[PathPoint],
    (options, cell): (&Options, Option<&Cell>),
) -> Result<Map> {
    options.validate()?;
    let model = Model::new(arm, compliance)?
        .at_level(options.level)
        .with_force_tolerance(options.force_tolerance);
    let nominal = nominal_postures(arm, points, options.q0, options)?;
    let wrenches: Vec<Vector6<f64>> = points
        .par_iter()
        .zip(&nominal)
        .map(|(p, q)| base_wrench(&arm.robot().frames(q), &p.wrench, p.frame))
        .collect();
    let own: Vec<ExternalValues> = points.iter().map(|p| p.external).collect();
    let mapped = Mapped {
        model: &model,
        cell: cell.filter(|c| c.floor_z.is_some() || !c.obstacles.is_empty()),
        nominal: &nominal,
        options,
    };
    let (angles, stations, cells) = match options.map_over {
        MapVariable::Rotation => {
            let free = match options.free_tool_axis {
                Some(f) => f,
                None => {
                    FreeToolAxis::try_from_degrees(Map::DEFAULT_STEP_DEG, Map::DEFAULT_RANGE_DEG)?
                }
            };
            free.check_grid(points.len())?;
            let angles = free.angles();
            let cells: Vec<Cells> = (angles.par_iter())
                .map(|&phi| mapped.column(Move::turn(phi), &wrenches, &own, None))
                .collect();
            (angles, Vec::new(), cells)
        }
        MapVariable::Track => {
            let (stations, cells) = track(&mapped, arm, &wrenches, &own)?;
            (Vec::new(), stations, cells)
        }
    };
    let columns = cells.len();
    let matrix = |k: usize| DMatrix::from_fn(points.len(), columns, |i, g| cells[g][i][k]);
    Ok(Map {
        bound: matrix(0),
        deflection: matrix(1),
        condition: matrix(2),
        limit_distance: matrix(3),
        collision_distance: mapped.cell.map(|_| matrix(4)),
        variable: options.map_over,
        angles,
        stations,
        lines: points.iter().map(|p| p.line).collect(),
        chosen: Vec::new(),
    })
}

/// The track map's stations (offsets, m) and each station's column of cells: the free
/// station's grid (else the default one), the points moved as the free station moves them.
fn track(
    mapped: &Mapped,
    arm: &Arm,
    wrenches: &[Vector6<f64>],
    own: &[ExternalValues],
) -> Result<(Vec<f64>, Vec<Cells>)> {
    let station = match mapped.options.free_station {
        Some(s) => s,
        None => {
            FreeStation::try_from_mm(Map::DEFAULT_STATION_RANGE_MM, Map::DEFAULT_STATION_STEP_MM)?
        }
    };
    let only = Options {
        free_station: Some(station),
        free_positioner: None,
        free_tilt: None,
        ..mapped.options.clone()
    };
    if arm.robot().external().is_none_or(|c| c.carrier_len() == 0) {
        return Err(Error::InvalidOption {
            option: JobOption::Map,
            message: "track: the robot has no carrier axis (a track) to map; the robot file's [[external_axis]] with role = \"carrier\" gives one".into(),
        });
    }
    let (axes, free) = free_axes(arm.robot().external(), &only)?;
    let offsets = station.offsets();
    let states = states(&free);
    super::station::check_grid(&only, states.len() as f64, own.len())?;
    let at = Own {
        values: own,
        wrenches,
        poses: (mapped.nominal.iter())
            .map(|q| tool_pose(&arm.robot().frames(q), &arm.tool().tcp))
            .collect(),
        weight: None,
        tcp: arm.tool().tcp,
    };
    let cells = (states.par_iter().zip(&offsets))
        .map(|(moves, &d)| {
            let st = Station::new(axes, &at, moves);
            let m = Move {
                phi: 0.0,
                shift: (d != 0.0).then_some(st.shift.as_slice()),
                lean: None,
                line: None,
            };
            mapped.column(m, &st.wrenches, &st.external, Some(&st.inside))
        })
        .collect();
    Ok((offsets, cells))
}

/// One column of the map: per point the bound, deflection, condition number, joint-limit
/// distance and collision distance (SI).
type Cells = Vec<[f64; 5]>;

/// What every column of the map shares.
struct Mapped<'a> {
    model: &'a Model<'a>,
    /// The cell's floor and obstacles, `None` without either.
    cell: Option<&'a Cell>,
    nominal: &'a [Vector6<f64>],
    options: &'a Options,
}

impl Mapped<'_> {
    /// The cells of one value of the variable: the points moved by `m` under `wrenches` (the
    /// arm's frame there), the arm on its carriage at `external`; `NaN` where not reached or
    /// not `inside` the travel.
    fn column(
        &self,
        m: Move,
        wrenches: &[Vector6<f64>],
        external: &[ExternalValues],
        inside: Option<&[bool]>,
    ) -> Cells {
        let arm = self.model.arm;
        let limits = arm.robot().limits();
        let postures = column(
            self.model,
            self.nominal,
            wrenches,
            (m, &Cost::Bound),
            &self.options.ik,
        );
        (postures.iter().zip(wrenches).enumerate())
            .map(|(i, (c, w))| match c {
                Some((q, bound)) if inside.is_none_or(|x| x[i]) => {
                    let frames = arm.robot().frames(q);
                    let d = self.model.tcp_deflection(&frames, w).displacement;
                    let j = frames.jacobian(&arm.tool().tcp, Coordinates::Axis);
                    [
                        *bound,
                        d.fixed_rows::<3>(0).norm(),
                        jacobi::cond(&j),
                        limits.distance(q),
                        self.clearance(q, &external[i]),
                    ]
                }
                _ => [f64::NAN; 5],
            })
            .collect()
    }

    /// The smallest distance of the bodies at `q` (the arm on its carriage at `e`) to the cell's
    /// floor and obstacles, m; `NaN` without a cell.
    fn clearance(&self, q: &Vector6<f64>, e: &ExternalValues) -> f64 {
        let Some(cell) = self.cell else {
            return f64::NAN;
        };
        let arm = self.model.arm;
        let frames = arm.robot().frames_at(q, e.as_slice());
        let mut nearest = f64::INFINITY;
        for b in bodies(arm, &frames) {
            // The base stands on the floor (as the cell's floor check has it).
            if let Some(z) = cell.floor_z.filter(|_| b.part() != Part::Base) {
                nearest = nearest.min(body_floor(&b, z));
            }
            for o in &cell.obstacles {
                nearest = nearest.min(body_box(&b, o));
            }
        }
        nearest
    }
}
