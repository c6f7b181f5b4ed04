//! The turns a placement's program does not pin: a path near-symmetric under a turn about the
//! table's normal (a rectangular pocket is the same path turned by 180 deg about its centre) or a
//! flat optimum leaves several turns of the part equally good. The place job probes the chosen
//! position at every `PROBE_STEP_DEG` of turn within the region's rotation, adds the
//! placements its searches evaluated at that position, and warns when those within
//! `TOLERANCE` of the chosen one's objective turn the part more than `SPREAD_DEG` from it,
//! naming their turns.

use super::Evaluation;
use nalgebra::{Isometry3, UnitQuaternion, Vector3};
use rayon::prelude::*;
use stiffid_core::common::warning::{Warning, WarningKind};
use stiffid_core::robot::file::rpy;

/// The turns probed at the chosen position: every this many degrees.
pub(crate) const PROBE_STEP_DEG: f64 = 15.0;
/// Placements whose objective lies within this share of the chosen one's are equally good.
pub(crate) const TOLERANCE: f64 = 0.005;
/// Equally good placements turned more than this from the chosen one (deg) leave the turn open.
pub(crate) const SPREAD_DEG: f64 = 2.0;
/// Placements whose origin lies this close to the chosen one's (m) are at its position.
pub(crate) const POSITION_M: f64 = 0.01;
/// Turns of equally good placements this far apart (deg) or closer are one range: neighbouring
/// probes both as good.
const GAP_DEG: f64 = PROBE_STEP_DEG + 0.5;

/// The chosen placement `placed` turned about the base z axis through its origin by every
/// `PROBE_STEP_DEG` whose turn from the own rotation (`turn_of`) stays within `rotation`
/// (rad), the chosen one left out.
pub fn probes(
    placed: &Isometry3<f64>,
    turn_of: impl Fn(&Isometry3<f64>) -> f64,
    rotation: [f64; 2],
) -> Vec<Isometry3<f64>> {
    let steps = (360.0 / PROBE_STEP_DEG).round() as usize;
    (1..steps)
        .map(|k| {
            let turn = UnitQuaternion::from_axis_angle(
                &Vector3::z_axis(),
                (k as f64 * PROBE_STEP_DEG).to_radians(),
            );
            Isometry3::from_parts(placed.translation, turn * placed.rotation)
        })
        .filter(|p| (rotation[0] - 1e-12..=rotation[1] + 1e-12).contains(&turn_of(p)))
        .collect()
}

/// The feasible evaluations of `poses` by `evaluate`, in parallel, in their order.
pub(crate) fn evaluated(
    poses: &[Isometry3<f64>],
    evaluate: impl Fn(&Isometry3<f64>) -> Option<Evaluation> + Sync + Send,
) -> Vec<Evaluation> {
    let all: Vec<Option<Evaluation>> = poses.par_iter().map(evaluate).collect();
    all.into_iter().flatten().collect()
}

/// The part's turn about the base z axis, deg: the yaw of `base_from_part` (fixed-axis roll,
/// pitch, yaw, as the document's `rpy_deg`).
fn yaw_deg(base_from_part: &Isometry3<f64>) -> f64 {
    rpy(&base_from_part.rotation)[2].to_degrees()
}

/// The warning that `others` at `placed`'s position (within `POSITION_M`) and within
/// `TOLERANCE` of its objective (`cost`) turn the part more than `SPREAD_DEG` from it, naming
/// their turns' ranges; `None` when the turn is pinned.
pub fn warning(
    placed: &Evaluation,
    others: &[Evaluation],
    cost: impl Fn(&Evaluation) -> f64,
    objective: &str,
) -> Option<Warning> {
    let best = cost(placed);
    let at = yaw_deg(&placed.base_from_part);
    let turned = |yaw: f64| ((yaw - at) + 540.0).rem_euclid(360.0) - 180.0;
    let yaws: Vec<f64> = others
        .iter()
        .filter(|e| cost(e) <= best * (1.0 + TOLERANCE))
        .filter(|e| {
            let d = e.base_from_part.translation.vector - placed.base_from_part.translation.vector;
            d.norm() <= POSITION_M
        })
        .map(|e| yaw_deg(&e.base_from_part))
        .chain([at])
        .collect();
    if yaws.iter().all(|&y| turned(y).abs() <= SPREAD_DEG) {
        return None;
    }
    Some(Warning::new(
        WarningKind::Unidentifiable,
        format!(
            "place: the program does not pin the part's turn: at the chosen position, turned {} deg (yaw), it gets a {objective} error bound within {}% of the chosen one's ({:.4} mm at {at:.2} deg), a path near-symmetric under a turn or a flat optimum; the setup is written with the chosen turn: choose among them by the cell (access, clamping), or narrow --rotation-deg",
            ranges(yaws),
            TOLERANCE * 100.0,
            best * 1e3
        ),
    ))
}

/// `yaws` (deg) as ranges in increasing yaw, `a to b` or `a`, joined by `, `: yaws closer than
/// `GAP_DEG` are one range, across +-180 deg too (`170.00 to -175.00`).
fn ranges(mut yaws: Vec<f64>) -> String {
    yaws.sort_by(f64::total_cmp);
    let mut groups: Vec<(f64, f64)> = Vec::new();
    for y in yaws {
        match groups.last_mut() {
            Some(g) if y - g.1 <= GAP_DEG => g.1 = y,
            _ => groups.push((y, y)),
        }
    }
    // The last range joins the first across +-180 deg.
    if groups.len() > 1 && groups[0].0 + 360.0 - groups[groups.len() - 1].1 <= GAP_DEG {
        let (_, end) = groups.remove(0);
        groups.last_mut().expect("two ranges").1 = end;
    }
    let texts: Vec<String> = groups
        .iter()
        .map(|&(a, b)| match (b - a).abs() < 0.005 {
            true => format!("{a:.2}"),
            false => format!("{a:.2} to {b:.2}"),
        })
        .collect();
    texts.join(", ")
}
