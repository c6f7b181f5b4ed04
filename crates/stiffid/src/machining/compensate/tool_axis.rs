//! The free tool axis: the stiffness-optimal rotation about tool z along the path by dynamic
//! programming (module docs of [`super`], "The free tool axis").

use super::{FreeToolAxis, Model, TIE_BREAK};
use crate::observation::dynamics::tcp_surge;
use crate::robot::dynamics::MassModel;
use crate::robot::ik::{self, tool_pose};
use crate::robot::kinematics::Frames;
use nalgebra::{UnitQuaternion, Vector3, Vector6};
use rayon::prelude::*;

/// What a point costs at an angle ([`super::Objective`]).
pub(super) enum Cost<'a> {
    /// The TCP translation deflection under the point's wrench, m.
    Deflection,
    /// At a drilling exit the surge speed of its thrust (m/s), elsewhere nothing.
    Surge {
        /// The arm's mass model.
        masses: Box<MassModel>,
        /// Each point's thrust (N, base frame) at a drilling exit, `None` elsewhere.
        thrusts: &'a [Option<Vector3<f64>>],
    },
}

impl Cost<'_> {
    /// The cost of point `i` in the posture `frames` under `wrench` (base frame); `None` where
    /// it cannot be computed (a surge at a singular posture).
    fn of(&self, model: &Model, i: usize, frames: &Frames, wrench: &Vector6<f64>) -> Option<f64> {
        match self {
            Cost::Deflection => Some(model.deflection(frames, wrench).0.fixed_rows::<3>(0).norm()),
            Cost::Surge { masses, thrusts } => match &thrusts[i] {
                None => Some(0.0),
                Some(force) => {
                    tcp_surge(masses, model.arm, frames, model.compliance, force).map(|s| s.speed)
                }
            },
        }
    }

    /// The scale of the tie-breaking cost of each point from the costs `own` at the path's
    /// angle: the point's own for the deflection, the largest for the surge (a point that is no
    /// exit costs nothing but still keeps the path smooth).
    fn scales(&self, own: &[f64]) -> Vec<f64> {
        match self {
            Cost::Deflection => own.to_vec(),
            Cost::Surge { .. } => {
                let largest = own.iter().copied().fold(0.0, f64::max);
                vec![if largest > 0.0 { largest } else { 1.0 }; own.len()]
            }
        }
    }
}

/// The postures and tool rotations of the free tool axis (module docs).
pub(super) fn optimise_tool_axis(
    model: &Model,
    nominal: &[Vector6<f64>],
    wrenches: &[Vector6<f64>],
    (free, cost): (&FreeToolAxis, &Cost),
    ik_options: &ik::Options,
) -> (Vec<Vector6<f64>>, Vec<f64>) {
    let (spacing, reach) = free.grid();
    let half = (free.range / spacing + 1e-9).floor() as isize;
    let angles: Vec<f64> = (-half..=half).map(|g| g as f64 * spacing).collect();
    let columns: Vec<Column> = angles
        .par_iter()
        .map(|&phi| column(model, nominal, wrenches, (phi, cost), ik_options))
        .collect();
    let zero = half as usize;
    let n = nominal.len();
    let g_count = angles.len();
    let own: Vec<f64> = columns[zero]
        .iter()
        .map(|c| c.map_or(0.0, |z| z.1))
        .collect();
    // cost[i][g]: the smallest sum of costs up to point i ending at angle g.
    let feasible = |i: usize, g: usize| {
        columns[g][i]
            .as_ref()
            .filter(|(_, d)| *d <= own[i])
            .map(|(_, d)| *d)
    };
    // The tie-breaking cost (module docs): TIE_BREAK of the scale per full range away from the
    // path's angle and per full step between points.
    let scales = cost.scales(&own);
    let weight = |i: usize| TIE_BREAK * scales[i];
    let mut cost = vec![vec![f64::INFINITY; g_count]; n];
    let mut from = vec![vec![0usize; g_count]; n];
    for i in 0..n {
        let w = weight(i);
        for g in 0..g_count {
            let Some(d) = feasible(i, g) else { continue };
            let own = d + w * angles[g].abs() / free.range;
            if i == 0 {
                cost[0][g] = own;
                continue;
            }
            let lo = g.saturating_sub(reach);
            let hi = (g + reach).min(g_count - 1);
            let turn =
                |a: usize| cost[i - 1][a] + w * (angles[g] - angles[a]).abs() / free.max_step;
            if let Some(best) = (lo..=hi).min_by(|&a, &b| turn(a).total_cmp(&turn(b))) {
                cost[i][g] = turn(best) + own;
                from[i][g] = best;
            }
        }
    }
    let mut g = (0..g_count)
        .min_by(|&a, &b| cost[n - 1][a].total_cmp(&cost[n - 1][b]))
        .unwrap_or(zero);
    let mut chosen = vec![zero; n];
    for i in (0..n).rev() {
        chosen[i] = g;
        g = from[i][g];
    }
    chosen
        .iter()
        .enumerate()
        .map(|(i, &g)| {
            let q = columns[g][i].as_ref().map_or(nominal[i], |c| c.0);
            (q, angles[g])
        })
        .unzip()
}

/// One angle's posture and [`Cost`] at every path point; `None` where inverse kinematics fails
/// or the cost cannot be computed.
type Column = Vec<Option<(Vector6<f64>, f64)>>;

/// The postures of the path turned by `phi` about tool z, continued along the path, and their
/// cost; `None` where inverse kinematics fails or the cost cannot be computed (at the path's own
/// angle such a cost is 0: no other angle is then taken there).
fn column(
    model: &Model,
    nominal: &[Vector6<f64>],
    wrenches: &[Vector6<f64>],
    (phi, cost): (f64, &Cost),
    ik_options: &ik::Options,
) -> Column {
    let arm = model.arm;
    let tcp = &arm.tool().tcp;
    let turn = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), phi);
    let options = ik::Options {
        restarts: 0,
        ..*ik_options
    };
    let mut previous: Option<Vector6<f64>> = None;
    nominal
        .iter()
        .zip(wrenches)
        .enumerate()
        .map(|(i, (q, w))| {
            let q = match phi == 0.0 {
                true => Some(*q),
                false => {
                    let mut target = tool_pose(&arm.robot().frames(q), tcp);
                    target.rotation *= turn;
                    let start = previous.unwrap_or(*q);
                    ik::solve(arm.robot(), tcp, &target, &start, &options)
                        .or_else(|_| ik::solve(arm.robot(), tcp, &target, q, &options))
                        .ok()
                        .map(|s| s.q)
                }
            };
            previous = q;
            let q = q?;
            match cost.of(model, i, &arm.robot().frames(&q), w) {
                Some(c) => Some((q, c)),
                None if phi == 0.0 => Some((q, 0.0)),
                None => None,
            }
        })
        .collect()
}
