//! Inverse kinematics in a named configuration: the one solution of a pose whose configuration
//! data are the ones asked, the nearest a start posture.
//!
//! Damped least squares ([`stiffid_core::robot::ik::solve`], one start at a time) from the start, from
//! the start with its wrist flipped (`q4 + 180, -q5, q6 + 180` deg), then from [`RANDOM_STARTS`]
//! seeded random postures within the joint limits, each solution also with its wrist flipped;
//! every solution is tried with each axis turned by whole revolutions within its limits (the
//! turn data of KUKA, ABB and FANUC name the revolution). The first start that gives a solution
//! in the configuration asked gives it, the variant nearest the start. A solution with an axis
//! within 1e-6 rad of a quarter turn (a configuration boundary, such as a wrist axis at 0 on a
//! vertical tool) is in the configuration of either side.

use super::Flags;
use crate::program::Dialect;
use nalgebra::{Isometry3, Vector3, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::{PI, TAU};
use stiffid_core::robot::configuration::Configuration;
use stiffid_core::robot::ik;
use stiffid_core::Robot;

/// Seeded random starts after the start and its wrist flip.
pub(crate) const RANDOM_STARTS: usize = 48;

/// Why no solution was taken: the configurations reached instead, or the closest miss.
pub(crate) enum Miss {
    /// The pose is reached, in these configurations only.
    Elsewhere(Vec<Flags>),
    /// The pose is not reached at all: inverse kinematics' error from the start.
    Unreachable(String),
}

/// The posture of `robot` with the tool point `tcp` (flange frame, m) at `target` (base frame)
/// whose configuration `wanted` accepts (module docs), from `start` (rad).
pub(crate) fn configured(
    robot: &Robot,
    tcp: &Vector3<f64>,
    target: &Isometry3<f64>,
    start: &Vector6<f64>,
    (dialect, wanted): (Dialect, &dyn Fn(&Configuration) -> bool),
    options: &ik::Options,
) -> Result<Vector6<f64>, Miss> {
    let one = ik::Options {
        restarts: 0,
        ..*options
    };
    let mut rng = ChaCha8Rng::seed_from_u64(options.seed);
    let limits = robot.limits();
    let random = |rng: &mut ChaCha8Rng| {
        Vector6::from_fn(|i, _| {
            let (lo, hi) = (limits.lower[i].max(-PI), limits.upper[i].min(PI));
            lo + (hi - lo) * rng.random::<f64>()
        })
    };
    let mut reached: Vec<Flags> = Vec::new();
    let mut first_error = None;
    let mut starts = vec![*start, flip(start)];
    for k in 0..2 + RANDOM_STARTS {
        if k >= starts.len() {
            starts.push(random(&mut rng));
        }
        let solution = match ik::solve(robot, tcp, target, &starts[k], &one) {
            Ok(s) => s.q,
            Err(e) => {
                first_error.get_or_insert_with(|| e.to_string());
                continue;
            }
        };
        let mut solutions = vec![solution];
        if let Ok(s) = ik::solve(robot, tcp, target, &flip(&solution), &one) {
            solutions.push(s.q);
        }
        let mut best: Option<(f64, Vector6<f64>)> = None;
        for q in solutions.iter().flat_map(|q| turns(robot, q)) {
            let arm = Configuration::of(robot, &q);
            let either = |n: &Vector6<f64>| wanted(&Configuration::of(robot, n));
            if wanted(&arm) || either_side(&q).iter().any(either) {
                let d = (q - start).norm();
                if best.is_none_or(|(b, _)| d < b) {
                    best = Some((d, q));
                }
            } else {
                let f = Flags::of(dialect, &arm);
                if !reached.contains(&f) {
                    reached.push(f);
                }
            }
        }
        if let Some((_, q)) = best {
            return Ok(q);
        }
    }
    match reached.is_empty() {
        true => Err(Miss::Unreachable(first_error.unwrap_or_default())),
        false => Err(Miss::Elsewhere(reached)),
    }
}

/// How near a quarter turn an axis angle is on the boundary of the configuration data, rad
/// (1e-6 rad: far below a controller's resolution, far above the inverse kinematics' error).
const BOUNDARY: f64 = 1e-6;

/// `q` with each axis within [`BOUNDARY`] of a multiple of 90 deg (where ABB's quadrant data,
/// KUKA's turn bits and FANUC's turn numbers change) put just across it, every combination:
/// a posture on the boundary has the configuration data of either side (the targets a
/// controller was told, read back, land within rounding of where they were written).
fn either_side(q: &Vector6<f64>) -> Vec<Vector6<f64>> {
    let quarter = PI / 2.0;
    let mut out = vec![*q];
    for k in 0..6 {
        let edge = (q[k] / quarter).round() * quarter;
        if (q[k] - edge).abs() > BOUNDARY {
            continue;
        }
        let across = |p: &Vector6<f64>, side: f64| {
            let mut p = *p;
            p[k] = edge + side * 2.0 * BOUNDARY;
            p
        };
        out = (out.iter())
            .flat_map(|p| [across(p, -1.0), across(p, 1.0)])
            .collect();
    }
    out
}

/// The same pose with the wrist flipped (exact for a spherical wrist, a start otherwise).
fn flip(q: &Vector6<f64>) -> Vector6<f64> {
    let mut f = *q;
    f[3] += if q[3] > 0.0 { -PI } else { PI };
    f[4] = -q[4];
    f[5] += if q[5] > 0.0 { -PI } else { PI };
    f
}

/// `q` with every combination of whole revolutions of its axes within the joint limits.
fn turns(robot: &Robot, q: &Vector6<f64>) -> Vec<Vector6<f64>> {
    let limits = robot.limits();
    let mut out = vec![*q];
    for k in 0..6 {
        let values: Vec<f64> = (-2..=2)
            .map(|m| q[k] + m as f64 * TAU)
            .filter(|v| *v >= limits.lower[k] && *v <= limits.upper[k])
            .collect();
        out = out
            .iter()
            .flat_map(|p| {
                values.iter().map(move |v| {
                    let mut p = *p;
                    p[k] = *v;
                    p
                })
            })
            .collect();
    }
    out
}
