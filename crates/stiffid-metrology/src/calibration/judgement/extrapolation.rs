//! Held-out readings the calibration misses where the nominal robot does not: the calibration
//! extrapolates there. A complete geometric model (and more so joint error maps) fitted on
//! postures that cover a small region can predict postures outside it far off, centimetres on a
//! real UR10 whose fitted postures leave joints 4 and 6 a quarter of their travel. Such readings
//! are of this robot (the nominal robot, registered on them, explains them), so the validation
//! keeps them and says so, rather than refusing them as readings of another robot.

use super::{Warning, WarningKind};
use crate::calibration::error_model::Observation;
use crate::calibration::validation::Validation;
use nalgebra::Vector6;
use stiffid_core::common::warning::joint_list;
use stiffid_core::io::readings::point_name;

/// How far a held-out posture's axis angle may lie beyond the fitted postures' range before it
/// is named as outside it: 1 degree.
pub(crate) const OUTSIDE_RAD: f64 = std::f64::consts::PI / 180.0;

/// The warning ([`WarningKind::Extrapolation`]) when the calibration misses held-out readings
/// (`calibrated`, one error per observation of `held`) by more than `limit` (m) while the
/// nominal robot's errors (`nominal`, aligned with them) stay within it; `None` otherwise. It names
/// the worst such reading's posture (`labels`) and the joints whose angle there lies outside the
/// range of the `fitted` observations' angles; with `moved` (the tracker not registered anew on
/// the held-out readings) and most readings missed, it says the tracker may have moved.
pub fn warning(
    (name, moved): (&str, bool),
    (fitted, held): (&[Observation], &[Observation]),
    labels: &[String],
    (calibrated, nominal): (&Validation, &Validation),
    limit: f64,
) -> Option<Warning> {
    let missed: Vec<usize> = (0..held.len().min(calibrated.errors.len()))
        .filter(|&i| {
            calibrated.errors[i].error.norm() > limit
                && nominal
                    .errors
                    .get(i)
                    .is_some_and(|e| e.error.norm() <= limit)
        })
        .collect();
    let worst = *missed.iter().max_by(|&&a, &&b| {
        let length = |i: usize| calibrated.errors[i].error.norm();
        length(a).total_cmp(&length(b))
    })?;
    let obs = &held[worst];
    let label = labels.get(obs.posture).map_or("?", String::as_str);
    Some(Warning::new(
        WarningKind::Extrapolation,
        format!(
            "{name}: the calibration predicts {} held-out reading{} more than {:.0} mm off where the nominal robot, registered on them, is within it: it extrapolates there (worst: posture {}, point {}, {:.1} mm against {:.3} mm nominal{}); a calibration holds where its postures were: fit postures that cover the region the robot works in{}",
            missed.len(),
            if missed.len() == 1 { "" } else { "s" },
            limit * 1e3,
            stiffid_core::common::limits::short(label),
            point_name(obs.point, obs.table),
            calibrated.errors[worst].error.norm() * 1e3,
            nominal.errors[worst].error.norm() * 1e3,
            outside(fitted, &obs.q),
            // A moved tracker shifts every reading, not a few.
            match moved && 2 * missed.len() > held.len() {
                true => " (or the tracker moved since the fitted readings: --reregister registers it on the held-out ones)",
                false => "",
            },
        ),
    ))
}

/// A held-out posture outside the fitted postures' axis ranges.
#[derive(Debug, Clone, PartialEq)]
pub struct Outside {
    /// The largest distance of an axis angle beyond its fitted range, rad.
    pub distance: f64,
    /// The joint at that distance (0-based).
    pub farthest: usize,
    /// The joints beyond their range by more than 1 deg (0-based, ascending).
    pub joints: Vec<usize>,
}

/// The held-out postures (`held`'s posture indices, table observations left out) whose axis angles
/// lie outside the `fitted` observations' ranges by more than 1 deg, each with its [`Outside`], and
/// the count of distinct held-out postures.
pub fn postures_outside(
    fitted: &[Observation],
    held: &[Observation],
) -> (std::collections::BTreeMap<usize, Outside>, usize) {
    let ranges = ranges(fitted);
    let mut postures = std::collections::BTreeMap::new();
    for o in held.iter().filter(|o| !o.table) {
        postures.entry(o.posture).or_insert(o.q);
    }
    let beyond = |q: &Vector6<f64>, j: usize| {
        let (lo, hi) = ranges[j];
        (lo - q[j]).max(q[j] - hi).max(0.0)
    };
    let outside = (postures.iter()).filter_map(|(&posture, q)| {
        let joints: Vec<usize> = (0..6).filter(|&j| beyond(q, j) > OUTSIDE_RAD).collect();
        let farthest =
            (joints.iter().copied()).max_by(|&a, &b| beyond(q, a).total_cmp(&beyond(q, b)))?;
        let distance = beyond(q, farthest);
        Some((
            posture,
            Outside {
                distance,
                farthest,
                joints,
            },
        ))
    });
    (outside.collect(), postures.len())
}

/// The warning ([`WarningKind::Extrapolation`]) when held-out postures (`held`, labelled by
/// `labels`) lie outside the `fitted` observations' axis ranges by more than 1 deg, whatever their
/// errors: how many, the joints outside, and the farthest posture with its distance (deg) beyond
/// the range and its joint; `None` when every held-out posture lies within.
pub fn outside_ranges(
    name: &str,
    (fitted, held): (&[Observation], &[Observation]),
    labels: &[String],
) -> Option<Warning> {
    let (outside, count) = postures_outside(fitted, held);
    let joints = (outside.values()).flat_map(|o| o.joints.iter().copied());
    let joints: std::collections::BTreeSet<usize> = joints.collect();
    let (posture, far) = (outside.iter()).max_by(|a, b| a.1.distance.total_cmp(&b.1.distance))?;
    Some(Warning::new(
        WarningKind::Extrapolation,
        format!(
            "{name}: {} of {count} held-out postures lie outside the fitted postures' range of {} by more than 1 deg (farthest: posture {}, {:.1} deg beyond on joint {}): the calibration extrapolates there, and its errors and intervals there say nothing of the region it was fitted in; fit postures that cover the region the robot works in",
            outside.len(),
            joint_list(joints),
            stiffid_core::common::limits::short(labels.get(*posture).map_or("?", String::as_str)),
            far.distance.to_degrees(),
            far.farthest + 1
        ),
    ))
}

/// The range of each axis angle over the `fitted` observations, rad.
pub fn ranges(fitted: &[Observation]) -> [(f64, f64); 6] {
    std::array::from_fn(|j| {
        (fitted.iter().map(|o| o.q[j])).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        })
    })
}

/// `; joints 4, 6 outside the fitted postures' range (193.2 deg against -108.3 to 71.6 deg, ...)`
/// for the joints of `q` beyond the `fitted` angles' range by more than [`OUTSIDE_RAD`]; empty
/// when every joint lies within it.
fn outside(fitted: &[Observation], q: &Vector6<f64>) -> String {
    let ranges = ranges(fitted);
    let joints: Vec<(usize, (f64, f64))> = (0..6)
        .map(|j| (j, ranges[j]))
        .filter(|&(j, (lo, hi))| q[j] < lo - OUTSIDE_RAD || q[j] > hi + OUTSIDE_RAD)
        .collect();
    if joints.is_empty() {
        return String::new();
    }
    let angles: Vec<String> = (joints.iter())
        .map(|&(j, (lo, hi))| {
            format!(
                "{:.1} deg against {:.1} to {:.1} deg",
                q[j].to_degrees(),
                lo.to_degrees(),
                hi.to_degrees()
            )
        })
        .collect();
    format!(
        "; {} outside the fitted postures' range: {}",
        joint_list(joints.iter().map(|&(j, _)| j)),
        angles.join(", ")
    )
}
