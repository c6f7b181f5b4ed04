//! The map of one free variable along a path: for every path point and every value of the
//! variable, the error bound, the deflection, the condition number of the TCP Jacobian, the
//! distance to the joint limits and, in a cell with bodies to clear, the distance to them. The
//! variable is the rotation about the spindle on the free tool axis' grid
//! ([`MapVariable::Rotation`]) or the track station on the free station's grid
//! ([`MapVariable::Track`]); each value's
//! postures continued along the path by inverse kinematics as the optimisation takes them
//! (module docs of [`super`], "The free tool axis", "The free station"), every other free
//! variable at the value the compensation chose at that point ([`ChosenValues`]: the rotation,
//! the lead and tilt, the station, the positioner's angles), so that the cell of the value
//! chosen is the compensated point's bound. The collision distance
//! is that of the robot's bodies (and the tool's capsule) to the cell's floor and obstacles
//! ([`stiffid_core::cell::body_floor`], [`stiffid_core::cell::body_box`]; the base stands on the floor), the
//! arm on its carriage at the point's station; the robot's self-collision is not mapped.

use super::lead_tilt::{lean, lean_frames};
use super::station::{Own, Station};
use super::stream::nominal_postures;
use super::tool_axis::{column, Cost, Move};
use super::{Compliance, FreeRange, MapVariable, Model, Options, PathPoint, Variable};
use nalgebra::{DMatrix, Isometry3, Translation3, UnitQuaternion, Vector3, Vector6};
use rayon::prelude::*;
use stiffid_core::cell::{bodies, body_box, body_floor, Part};
use stiffid_core::common::error::JobOption;
use stiffid_core::math::jacobi;
use stiffid_core::observation::deflection::base_wrench;
use stiffid_core::robot::external::ExternalValues;
use stiffid_core::robot::ik::tool_pose;
use stiffid_core::robot::kinematics::Coordinates;
use stiffid_core::setup::{Arm, Cell};
use stiffid_core::{Error, Result};

/// The map (module docs). Every matrix has one row per path point (path order) and one column
/// per value of the variable; `NaN` where inverse kinematics does not reach the moved pose or
/// the station is beyond the track's travel.
#[derive(Debug, Clone, PartialEq)]
pub struct Map {
    /// Each path point's line in its file.
    pub lines: Vec<u64>,
    /// The variable mapped.
    pub variable: MapVariable,
    /// With [`MapVariable::Rotation`], the columns: the rotations about tool z from the path's own,
    /// rad, ascending (the grid of the free tool axis, or of 5 deg and 90 deg without one); empty
    /// for the track.
    pub angles: Vec<f64>,
    /// With [`MapVariable::Track`], the columns: the station's offsets from the path's own, m,
    /// ascending (the grid of the free station, or of 50 mm and 1000 mm without one); empty for the
    /// rotation.
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
    /// The value chosen at every point (the rotation, rad, or the station's offset from the
    /// point's own, m; the path's own, 0, where the variable is not free), from the
    /// [`ChosenValues`] the map was drawn with: the line drawn on the map.
    pub chosen: Vec<f64>,
}

impl Map {
    /// The grid's step without a free tool axis, deg.
    pub(crate) const DEFAULT_STEP_DEG: f64 = 5.0;
    /// The grid's range without a free tool axis, deg.
    pub(crate) const DEFAULT_RANGE_DEG: f64 = 90.0;
    /// The track map's step without a free station, mm.
    pub(crate) const DEFAULT_STATION_STEP_MM: f64 = 50.0;
    /// The track map's range without a free station, mm.
    pub(crate) const DEFAULT_STATION_RANGE_MM: f64 = 1000.0;
}

/// What the compensation chose at one path point besides the point itself: the values the
/// map holds fixed while it maps one variable (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ChosenValues {
    /// The rotation about tool z, rad ([`super::Compensated::tool_rotation`]).
    pub rotation: f64,
    /// The lead and the tilt, rad ([`super::Compensated::lead`], [`super::Compensated::tilt`]).
    pub lean: (f64, f64),
    /// The external axes' values (SI, the cell's order; [`super::Compensated::external`]); empty
    /// without external axes.
    pub external: ExternalValues,
}

impl ChosenValues {
    /// The values of a compensated point: its rotation, lean and external values (`own`, the
    /// point's own, where the result holds none).
    pub fn of(r: &super::Compensated, own: &ExternalValues) -> Self {
        ChosenValues {
            rotation: r.tool_rotation,
            lean: (r.lead, r.tilt),
            external: match r.external.is_empty() {
                true => *own,
                false => r.external,
            },
        }
    }
}

/// The map of `points` (module docs; in the arm's frame on its carriage at each point's own
/// external values, as the compensation takes them) over [`Options::map_over`]: the free tool
/// axis' grid of `options` (else a 5 deg grid within +-90 deg), or the free station's (else a
/// 50 mm grid within +-1000 mm), under the error budget of `options`, every other variable at
/// `chosen` (one per point: what the compensation chose; [`ChosenValues::default`] with the
/// points' own external values for the path's own); `weighted`: the points' wrenches hold the
/// tool's weight (a program's, [`super::path_on_track`]'s rule); `cell` the setup's `[cell]`
/// (the collision distance, with a floor or obstacles).
///
/// # Errors
/// Those of [`super::path`] for the options, the grid's size and the nominal postures; for the
/// track, [`Error::InvalidOption`] ([`JobOption::Map`]) for a robot without a carrier axis and
/// the grid's size; [`Error::InvalidField`] (`chosen`) for a count other than the points'.
pub fn map(
    arm: &Arm,
    compliance: &Compliance,
    points: &[PathPoint],
    (options, cell): (&Options, Option<&Cell>),
    (chosen, weighted): (&[ChosenValues], bool),
) -> Result<Map> {
    options.validate()?;
    if chosen.len() != points.len() {
        return Err(Error::InvalidField {
            field: "chosen".into(),
            message: format!("{} values for {} path points", chosen.len(), points.len()),
        });
    }
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
    let at = Own {
        values: &own,
        wrenches: &wrenches,
        poses: (nominal.iter())
            .map(|q| tool_pose(&arm.robot().frames(q), &arm.tool().tcp))
            .collect(),
        weight: weighted.then(|| arm.payload()).flatten(),
        tcp: arm.tool().tcp,
    };
    let mapped = Mapped {
        model: &model,
        cell: cell.filter(|c| c.floor_z.is_some() || !c.obstacles.is_empty()),
        nominal: &nominal,
        options,
    };
    let leans = leans(&at.poses, chosen);
    let (angles, stations, cells) = match options.map_over {
        MapVariable::Rotation => {
            let free = match options.free.tool_rotation() {
                Some(f) => f,
                None => FreeRange::checked(
                    &Variable::ToolRotation,
                    Map::DEFAULT_RANGE_DEG,
                    Map::DEFAULT_STEP_DEG,
                )?,
            };
            free.check_rotation_grid(points.len())?;
            let angles = free.angles();
            let values = chosen.iter().map(|c| c.external.as_slice().to_vec());
            let st = moved(arm, &at, values);
            let shift = rest(&st, &at.poses, &leans, &vec![0.0; points.len()]);
            let cells: Vec<Cells> = (angles.par_iter())
                .map(|&phi| {
                    let m = Move {
                        phi,
                        shift: shift.as_deref(),
                        lean: None,
                        line: None,
                    };
                    mapped.column(m, &st.wrenches, &st.external, None)
                })
                .collect();
            (angles, Vec::new(), cells)
        }
        MapVariable::Track => {
            let (stations, cells) = track(&mapped, arm, &at, (chosen, &leans))?;
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
        chosen: (chosen.iter().zip(&own))
            .map(|(c, o)| match options.map_over {
                MapVariable::Rotation => c.rotation,
                MapVariable::Track => match (c.external.as_slice(), o.as_slice()) {
                    ([e, ..], [o, ..]) => e - o,
                    _ => 0.0,
                },
            })
            .collect(),
    })
}

/// Each point's chosen lean as a turn about its TCP (`None` for none): the rotation of
/// [`lean`] in the point's lean frame.
fn leans(poses: &[Isometry3<f64>], chosen: &[ChosenValues]) -> Vec<Option<UnitQuaternion<f64>>> {
    if chosen.iter().all(|c| c.lean == (0.0, 0.0)) {
        return vec![None; chosen.len()];
    }
    (lean_frames(poses).iter().zip(chosen))
        .map(|(f, c)| (c.lean != (0.0, 0.0)).then(|| lean(f, c.lean.0, c.lean.1)))
        .collect()
}

/// The points moved to their external `values` (one per point, the cell's order): on a robot
/// without external axes, or at their own values, the points as they are.
fn moved(arm: &Arm, at: &Own, values: impl Iterator<Item = Vec<f64>>) -> Station {
    let values: Vec<Vec<f64>> = values.collect();
    let own = (at.values.iter().zip(&values)).all(|(o, v)| o.as_slice() == v.as_slice());
    match arm.robot().external() {
        Some(cell) if !own => Station::at_values(cell, at, values.into_iter()),
        _ => Station {
            external: at.values.to_vec(),
            inside: vec![true; at.values.len()],
            shift: vec![Isometry3::identity(); at.values.len()],
            wrenches: at.wrenches.to_vec(),
        },
    }
}

/// Each point's move to the rest of its chosen values, left of its pose `poses[i]`: the
/// station's shift of `st` after the chosen lean (`leans`) after the chosen rotation about
/// tool z (`rotations`), both about the TCP, as [`column`] moves a point; `None` where every
/// point keeps its own pose.
fn rest(
    st: &Station,
    poses: &[Isometry3<f64>],
    leans: &[Option<UnitQuaternion<f64>>],
    rotations: &[f64],
) -> Option<Vec<Isometry3<f64>>> {
    let mut any = false;
    let out = (0..poses.len())
        .map(|i| {
            let r = poses[i].rotation;
            let turn =
                r * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), rotations[i]) * r.inverse();
            let about = leans[i].unwrap_or_else(UnitQuaternion::identity) * turn;
            let o = poses[i].translation.vector;
            any |=
                rotations[i] != 0.0 || leans[i].is_some() || st.shift[i] != Isometry3::identity();
            st.shift[i] * Isometry3::from_parts(Translation3::from(o - about * o), about)
        })
        .collect();
    any.then_some(out)
}

/// The track map's stations (offsets, m) and each station's column of cells: the free
/// station's grid (else the default one), the points moved as the free station moves them,
/// every other variable at its `chosen` values (the `leans` of [`leans`]).
fn track(
    mapped: &Mapped,
    arm: &Arm,
    at: &Own,
    (chosen, leans): (&[ChosenValues], &[Option<UnitQuaternion<f64>>]),
) -> Result<(Vec<f64>, Vec<Cells>)> {
    let station = match mapped.options.free.station() {
        Some(s) => s,
        None => FreeRange::checked(
            &Variable::Station,
            Map::DEFAULT_STATION_RANGE_MM,
            Map::DEFAULT_STATION_STEP_MM,
        )?,
    };
    if arm.robot().external().is_none_or(|c| c.carrier_len() == 0) {
        return Err(Error::InvalidOption {
            option: JobOption::Map,
            message: "track: the robot has no carrier axis (a track) to map; the robot file's [[external_axis]] with role = \"carrier\" gives one".into(),
        });
    }
    let offsets = station.offsets();
    let mut only = mapped.options.clone();
    only.free = only.free.keeping(|f| !f.is_external());
    only.free.free.push(super::Free::Station(station));
    super::station::check_grid(&only, offsets.len() as f64, at.values.len())?;
    let rotations: Vec<f64> = chosen.iter().map(|c| c.rotation).collect();
    let cells = (offsets.par_iter())
        .map(|&d| {
            let values = (chosen.iter().zip(at.values)).map(|(c, own)| {
                let mut v = c.external.as_slice().to_vec();
                v[0] = own.as_slice()[0] + d;
                v
            });
            let st = moved(arm, at, values);
            let shift = rest(&st, &at.poses, leans, &rotations);
            let m = Move {
                phi: 0.0,
                shift: shift.as_deref(),
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
    /// floor and obstacles (those a positioner carries turned to `e`), m; `NaN` without a cell.
    fn clearance(&self, q: &Vector6<f64>, e: &ExternalValues) -> f64 {
        let Some(cell) = self.cell else {
            return f64::NAN;
        };
        let arm = self.model.arm;
        let frames = arm.robot().frames_at(q, e.as_slice());
        let obstacles = cell.obstacles_at(arm.robot(), e.as_slice());
        let mut nearest = f64::INFINITY;
        for b in bodies(arm, &frames) {
            // The base stands on the floor (as the cell's floor check has it).
            if let Some(z) = cell.floor_z.filter(|_| b.part() != Part::Base) {
                nearest = nearest.min(body_floor(&b, z));
            }
            for o in obstacles.iter() {
                nearest = nearest.min(body_box(&b, o));
            }
        }
        nearest
    }
}
