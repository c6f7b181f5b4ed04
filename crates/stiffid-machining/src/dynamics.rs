//! The robot's mass along a machining program: the breakthrough surge at every drilling exit and
//! the first natural frequency of every milling point against the tooth-passing frequency
//! ([`stiffid_core::observation::dynamics`] for one posture).
//!
//! **Drilling exits.** A point of a drilling operation is an exit when the drill leaves the
//! material after it: the next point belongs to no operation or another one, or moves back
//! against the tool's z (a retract, by more than a nanometre), or the path ends there
//! (`exit_thrusts`). At an exit the thrust `F` of the operation (`k_f f D / 2`,
//! `crate::process::drilling`) acts along the tool axis; its sudden release gives
//! the surge `F sqrt(c / m)` with the held effective mass `m = u^T Lambda_vv u`
//! ([`stiffid_core::observation::dynamics::surge`]). A `G83` peck's every bottom is an exit (the last
//! one is the breakthrough). The free tool axis can choose the rotation about the tool z that
//! minimises it ([`crate::compensate::Objective::Surge`]).
//!
//! **Milling points.** Every point of a milling operation gets the first natural frequency of
//! its posture (`K v = w^2 M v`, [`stiffid_core::robot::dynamics::modes`]), per point because the
//! modes move with the posture along the path; with the operation's spindle speed it is set
//! against the tooth-passing frequency `f_t = N n` and its harmonics `k f_t`: the nearest
//! harmonic `k = max(1, round(f_1 / f_t))` and the relative distance `|f_1 - k f_t| / (k f_t)`,
//! within `CLOSE` (10%) a chatter risk (Altintas 2012, ch. 3). Points of no operation, rapid moves
//! and the non-exit drilling points get nothing, so the modes are computed only where needed.
//!
//! Every posture is the point's nominal one (`q`: where the loaded robot holds the tool).

use crate::compensate::{Compensated, Compliance, PathPoint};
use crate::process::{Kind, Process};
use nalgebra::{Isometry3, Vector3, Vector6};
use stiffid_core::common::warning::{Warning, WarningKind};
use stiffid_core::observation::dynamics::{self, Surge};
use stiffid_core::robot::dynamics::{modes, MassModel};
use stiffid_core::robot::kinematics::Coordinates;
use stiffid_core::setup::Arm;

/// The relative distance of the first frequency to a tooth-passing harmonic below which a
/// milling point is a chatter risk (10%).
pub(crate) const CLOSE: f64 = 0.1;

/// The dynamics of one path point; all `None` for a point that is neither a drilling exit nor
/// a milling point, or without a mass model.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Dynamics {
    /// At a drilling exit: the breakthrough surge of the operation's thrust.
    pub surge: Option<Surge>,
    /// At a drilling exit with the free tool axis: the surge at the path's own rotation about
    /// tool z (before the rotation was chosen).
    pub surge_before: Option<Surge>,
    /// At a milling point: the lowest natural frequency of the posture, Hz.
    pub first_frequency: Option<f64>,
    /// At a milling point whose operation gives its spindle speed: the tooth-passing frequency,
    /// Hz.
    pub tooth_passing: Option<f64>,
    /// With both frequencies: the nearest harmonic of the tooth-passing frequency.
    pub harmonic: Option<Harmonic>,
}

/// The harmonic `k f_t` of the tooth-passing frequency nearest the first frequency.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Harmonic {
    /// Its order `k >= 1`.
    pub order: u32,
    /// `|f_1 - k f_t| / (k f_t)`, relative.
    pub distance: f64,
}

impl Harmonic {
    /// The harmonic of `tooth_passing` (Hz) nearest `first` (Hz), module docs.
    pub(crate) fn nearest(first: f64, tooth_passing: f64) -> Self {
        let order = (first / tooth_passing).round().max(1.0);
        Harmonic {
            order: order as u32,
            distance: (first - order * tooth_passing).abs() / (order * tooth_passing),
        }
    }
}

/// The dynamics of every point of a compensated program (module docs), in path order:
/// `results` the points' compensation, `operations` each point's operation (index into
/// `process`), `masses` the arm's mass model with its tool, `compliance` the model's. With the
/// free tool axis each drilling exit gets the surge at the path's own rotation too
/// ([`Compensated::q_before`]).
///
/// # Panics
/// If `operations` and `results` differ in length or the compliance does not have one value per
/// parameter of the arm's model.
pub fn program(
    arm: &Arm,
    masses: &MassModel,
    compliance: &Compliance,
    process: &Process,
    results: &[Compensated],
    operations: &[Option<usize>],
) -> Vec<Dynamics> {
    use rayon::prelude::*;
    assert_eq!(results.len(), operations.len(), "one operation per point");
    let point = arm.tool().tcp;
    let poses: Vec<Isometry3<f64>> = results.iter().map(|r| r.pose).collect();
    let thrusts = exit_thrusts(process, &poses, operations);
    (0..results.len())
        .into_par_iter()
        .map(|i| {
            let Some(op) = operations[i] else {
                return Dynamics::default();
            };
            let r = &results[i];
            match &process.operations[op].kind {
                Kind::Drilling(_) => {
                    let Some(force) = thrusts[i] else {
                        return Dynamics::default();
                    };
                    let surge = |q: &Vector6<f64>| {
                        dynamics::tcp_surge(masses, arm, &arm.robot().frames(q), compliance, &force)
                    };
                    Dynamics {
                        surge: surge(&r.q),
                        surge_before: r.q_before.as_ref().and_then(surge),
                        ..Dynamics::default()
                    }
                }
                Kind::Milling(mill) => {
                    let frames = arm.robot().frames(&r.q);
                    let m = masses.mass_matrix(arm.robot(), &frames, Coordinates::Axis);
                    let first = dynamics::joint_compliance(arm, &frames, &point, &compliance.h)
                        .and_then(|c| modes::modes(&m, &c))
                        .map(|modes| modes.frequencies[0]);
                    let tooth_passing = mill.tooth_passing_frequency();
                    Dynamics {
                        first_frequency: first,
                        tooth_passing,
                        harmonic: first
                            .zip(tooth_passing)
                            .map(|(f, t)| Harmonic::nearest(f, t)),
                        ..Dynamics::default()
                    }
                }
            }
        })
        .collect()
}

/// What one operation of a program meets along its points ([`per_operation`]), SI.
#[derive(Debug, Clone, PartialEq)]
pub struct OperationSummary {
    /// The operation's index in the process.
    pub index: usize,
    /// Whether it drills (else it mills).
    pub drilling: bool,
    /// Drilling: its exits with a surge; milling: its points.
    pub points: usize,
    /// Drilling: the largest breakthrough surge over its exits, with that exit's line.
    pub max_surge: Option<(u64, Surge)>,
    /// Drilling with the free tool axis: the largest surge over its exits at the path's own
    /// rotation about tool z, m/s.
    pub max_surge_before: Option<f64>,
    /// Milling: the lowest and highest first natural frequency over its points, Hz.
    pub first_frequency: Option<[f64; 2]>,
    /// Milling with the operation's spindle speed: the tooth-passing frequency, Hz.
    pub tooth_passing: Option<f64>,
    /// Milling: the point whose first frequency is nearest a harmonic of the tooth-passing
    /// frequency: its line and that harmonic.
    pub nearest_harmonic: Option<(u64, Harmonic)>,
}

/// The dynamics of every operation of `process` that cuts a point of `points` (`operations`:
/// each point's operation, `dynamics`: each point's, [`program`]), in process order, and a
/// [`WarningKind::Chatter`] warning for each milling operation with a point within `CLOSE` (10%) of
/// a harmonic of its tooth-passing frequency.
pub fn per_operation(
    process: &Process,
    points: &[PathPoint],
    operations: &[Option<usize>],
    dynamics: &[Dynamics],
) -> (Vec<OperationSummary>, Vec<Warning>) {
    let mut out = Vec::new();
    let mut warnings = Vec::new();
    for (index, op) in process.operations.iter().enumerate() {
        let mine = || {
            (points.iter().zip(operations).zip(dynamics))
                .filter(move |((_, o), _)| **o == Some(index))
                .map(|((p, _), d)| (p.line, d))
        };
        let mut summary = OperationSummary {
            index,
            drilling: false,
            points: 0,
            max_surge: None,
            max_surge_before: None,
            first_frequency: None,
            tooth_passing: None,
            nearest_harmonic: None,
        };
        match &op.kind {
            Kind::Drilling(_) => {
                summary.drilling = true;
                let surges: Vec<_> = mine()
                    .filter_map(|(l, d)| d.surge.map(|s| (l, s)))
                    .collect();
                summary.points = surges.len();
                summary.max_surge =
                    (surges.into_iter()).max_by(|a, b| a.1.speed.total_cmp(&b.1.speed));
                summary.max_surge_before = mine()
                    .filter_map(|(_, d)| d.surge_before.map(|s| s.speed))
                    .reduce(f64::max);
            }
            Kind::Milling(m) => {
                summary.points = mine().count();
                summary.tooth_passing = m.tooth_passing_frequency();
                let firsts: Vec<f64> = mine().filter_map(|(_, d)| d.first_frequency).collect();
                summary.first_frequency = (!firsts.is_empty()).then(|| {
                    let low = firsts.iter().copied().fold(f64::INFINITY, f64::min);
                    let high = firsts.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                    [low, high]
                });
                let nearest = mine()
                    .filter_map(|(l, d)| d.harmonic.zip(d.first_frequency).map(|(h, f)| (l, h, f)))
                    .min_by(|a, b| a.1.distance.total_cmp(&b.1.distance));
                if let Some((line, h, f)) = nearest {
                    summary.nearest_harmonic = Some((line, h));
                    if h.distance <= CLOSE {
                        let t = summary.tooth_passing.unwrap_or(f64::NAN);
                        warnings.push(Warning::new(
                            WarningKind::Chatter,
                            format!(
                                "milling operation '{}': at line {line} the first natural frequency {f:.1} Hz is within {:.1}% of {} x the tooth-passing frequency {t:.1} Hz ({} flutes): chatter is likely there; change the spindle speed or the posture",
                                op.name,
                                h.distance * 100.0,
                                h.order,
                                m.flutes
                            ),
                        ));
                    }
                }
            }
        }
        if summary.points > 0 {
            out.push(summary);
        }
    }
    (out, warnings)
}

/// The thrust `-F z_tool` (N, base frame) released at each drilling exit of a path (module
/// docs), `None` at every other point: `poses` every point's TCP pose (base frame), `operations`
/// its operation (index into `process`). A rotation about the tool z changes no exit and no
/// thrust.
///
/// # Panics
/// If `operations` and `poses` differ in length.
pub(crate) fn exit_thrusts(
    process: &Process,
    poses: &[Isometry3<f64>],
    operations: &[Option<usize>],
) -> Vec<Option<Vector3<f64>>> {
    assert_eq!(poses.len(), operations.len(), "one operation per point");
    (0..poses.len())
        .map(
            |i| match operations[i].map(|o| &process.operations[o].kind) {
                Some(Kind::Drilling(d)) if is_exit(poses, operations, i) => {
                    Some(-(poses[i].rotation * Vector3::z()) * d.thrust())
                }
                _ => None,
            },
        )
        .collect()
}

/// A move back against the tool's z shorter than this is no retract, m (round-off between a
/// programmed pose and the forward kinematics of its posture).
const RETRACT: f64 = 1e-9;

/// Whether point `i` (of a drilling operation) is an exit (module docs).
fn is_exit(poses: &[Isometry3<f64>], operations: &[Option<usize>], i: usize) -> bool {
    let Some(next) = poses.get(i + 1) else {
        return true;
    };
    if operations[i + 1] != operations[i] {
        return true;
    }
    let tool_z = poses[i].rotation * Vector3::z();
    let step = next.translation.vector - poses[i].translation.vector;
    step.dot(&tool_z) < -RETRACT
}
