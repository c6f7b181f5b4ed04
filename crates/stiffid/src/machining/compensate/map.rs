//! The map of one free variable along a path: for every path point and every rotation about the
//! spindle on the free tool axis' grid, the error bound, the deflection, the condition number of
//! the TCP Jacobian and the distance to the joint limits, each angle's postures continued along
//! the path by inverse kinematics as the free tool axis' optimisation takes them (module docs of
//! [`super`], "The free tool axis"). The cell's bodies are not checked here: a cell with
//! obstacles needs its own check of the postures chosen.

use super::stream::nominal_postures;
use super::tool_axis::{column, Cost, Move};
use super::{Compliance, FreeToolAxis, Model, Options, PathPoint};
use crate::math::jacobi;
use crate::observation::deflection::base_wrench;
use crate::robot::kinematics::Coordinates;
use crate::setup::Arm;
use crate::Result;
use nalgebra::{DMatrix, Vector6};
use rayon::prelude::*;

/// The map (module docs). Every matrix has one row per path point (path order) and one column
/// per angle; `NaN` where inverse kinematics does not reach the turned pose.
#[derive(Debug, Clone, PartialEq)]
pub struct Map {
    /// Each path point's line in its file.
    pub lines: Vec<u64>,
    /// The rotations about tool z from the path's own, rad, ascending (the grid of the free
    /// tool axis, or of [`Map::DEFAULT_STEP_DEG`] and [`Map::DEFAULT_RANGE_DEG`] without one).
    pub angles: Vec<f64>,
    /// The error bound ([`super::Budget`], without the residual the Newton steps leave), m.
    pub bound: DMatrix<f64>,
    /// The TCP translation deflection under the point's wrench, m.
    pub deflection: DMatrix<f64>,
    /// The condition number of the TCP Jacobian (axis coordinates, rows `[v; omega]` in m/rad
    /// and rad/rad): larger near a singularity.
    pub condition: DMatrix<f64>,
    /// The smallest distance of an axis angle to its joint limits, rad.
    pub limit_distance: DMatrix<f64>,
    /// The rotation chosen at every point (the path's own, 0, without a free tool axis), rad:
    /// the line drawn on the map; empty until the compensate job fills it.
    pub chosen: Vec<f64>,
}

impl Map {
    /// The grid's step without a free tool axis, deg.
    pub const DEFAULT_STEP_DEG: f64 = 5.0;
    /// The grid's range without a free tool axis, deg.
    pub const DEFAULT_RANGE_DEG: f64 = 90.0;
}

/// The map of `points` (module docs) on the free tool axis' grid of `options` (else a 5 deg grid
/// within +-90 deg) under the error budget of `options`.
///
/// # Errors
/// Those of [`super::path`] for the options, the grid's size and the nominal postures.
pub fn map(
    arm: &Arm,
    compliance: &Compliance,
    points: &[PathPoint],
    options: &Options,
) -> Result<Map> {
    options.validate()?;
    let free = match options.free_tool_axis {
        Some(f) => f,
        None => FreeToolAxis::try_from_degrees(Map::DEFAULT_STEP_DEG, Map::DEFAULT_RANGE_DEG)?,
    };
    free.check_grid(points.len())?;
    let model = Model::new(arm, compliance)?
        .at_level(options.level)
        .with_force_tolerance(options.force_tolerance);
    let nominal = nominal_postures(arm, points, options.q0, options)?;
    let wrenches: Vec<Vector6<f64>> = points
        .par_iter()
        .zip(&nominal)
        .map(|(p, q)| base_wrench(&arm.robot().frames(q), &p.wrench, p.frame))
        .collect();
    let angles = free.angles();
    let n = points.len();
    let limits = arm.robot().limits();
    let cells: Vec<Vec<[f64; 4]>> = angles
        .par_iter()
        .map(|&phi| {
            let postures = column(
                &model,
                &nominal,
                &wrenches,
                (Move::turn(phi), &Cost::Bound),
                &options.ik,
            );
            (postures.iter().zip(&wrenches))
                .map(|(c, w)| match c {
                    None => [f64::NAN; 4],
                    Some((q, bound)) => {
                        let frames = arm.robot().frames(q);
                        let d = model.tcp_deflection(&frames, w).displacement;
                        let j = frames.jacobian(&arm.tool().tcp, Coordinates::Axis);
                        [
                            *bound,
                            d.fixed_rows::<3>(0).norm(),
                            jacobi::cond(&j),
                            limits.distance(q),
                        ]
                    }
                })
                .collect()
        })
        .collect();
    let matrix = |k: usize| DMatrix::from_fn(n, angles.len(), |i, g| cells[g][i][k]);
    Ok(Map {
        bound: matrix(0),
        deflection: matrix(1),
        condition: matrix(2),
        limit_distance: matrix(3),
        angles,
        lines: points.iter().map(|p| p.line).collect(),
        chosen: Vec::new(),
    })
}
