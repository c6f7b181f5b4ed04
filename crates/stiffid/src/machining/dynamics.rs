//! The robot's mass along a machining program: the breakthrough surge at every drilling exit and
//! the first natural frequency of every milling point against the tooth-passing frequency
//! ([`crate::observation::dynamics`] for one posture).
//!
//! **Drilling exits.** A point of a drilling operation is an exit when the drill leaves the
//! material after it: the next point belongs to no operation or another one, or moves back
//! against the tool's z (a retract), or the path ends there. At an exit the thrust `F` of the
//! operation (`k_f f D / 2`, [`crate::machining::process::drilling`]) acts along the tool axis;
//! its sudden release gives the surge `F sqrt(c / m)` with the held effective mass
//! `m = u^T Lambda_vv u` ([`crate::observation::dynamics::surge`]). A `G83` peck's every bottom
//! is an exit (the last one is the breakthrough).
//!
//! **Milling points.** Every point of a milling operation gets the first natural frequency of
//! its posture (`K v = w^2 M v`, [`crate::robot::dynamics::modes`]), per point because the
//! modes move with the posture along the path; with the operation's spindle speed it is set
//! against the tooth-passing frequency `f_t = N n` and its harmonics `k f_t`: the nearest
//! harmonic `k = max(1, round(f_1 / f_t))` and the relative distance `|f_1 - k f_t| / (k f_t)`,
//! within [`CLOSE`] a chatter risk (Altintas 2012, ch. 3). Points of no operation, rapid moves
//! and the non-exit drilling points get nothing, so the modes are computed only where needed.
//!
//! Every posture is the point's nominal one (`q`: where the loaded robot holds the tool).

use crate::machining::compensate::{Compensated, Compliance};
use crate::machining::process::{Kind, Process};
use crate::observation::dynamics::{self, Surge};
use crate::robot::dynamics::{modes, operational_inertia, MassModel};
use crate::robot::kinematics::Coordinates;
use crate::setup::Arm;
use nalgebra::Vector3;

/// The relative distance of the first frequency to a tooth-passing harmonic below which a
/// milling point is a chatter risk (10%).
pub const CLOSE: f64 = 0.1;

/// The dynamics of one path point; all `None` for a point that is neither a drilling exit nor
/// a milling point, or without a mass model.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Dynamics {
    /// At a drilling exit: the breakthrough surge of the operation's thrust.
    pub surge: Option<Surge>,
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
    pub fn nearest(first: f64, tooth_passing: f64) -> Self {
        let order = (first / tooth_passing).round().max(1.0);
        Harmonic {
            order: order as u32,
            distance: (first - order * tooth_passing).abs() / (order * tooth_passing),
        }
    }
}

/// The dynamics of every point of a compensated program (module docs), in path order:
/// `results` the points' compensation, `operations` each point's operation (index into
/// `process`), `masses` the arm's mass model with its tool, `compliance` the model's.
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
    (0..results.len())
        .into_par_iter()
        .map(|i| {
            let Some(op) = operations[i] else {
                return Dynamics::default();
            };
            let r = &results[i];
            let frames = arm.robot().frames(&r.q);
            match &process.operations[op].kind {
                Kind::Drilling(d) if is_exit(results, operations, i) => {
                    let tool_z = r.pose.rotation * Vector3::z();
                    let m = masses.mass_matrix(arm.robot(), &frames, Coordinates::Axis);
                    let jacobian = frames.jacobian(&point, Coordinates::Axis);
                    let surge = operational_inertia(&m, &jacobian).and_then(|lambda| {
                        let force = -tool_z * d.thrust();
                        dynamics::surge(arm, &frames, &point, &lambda, compliance, &force)
                    });
                    Dynamics {
                        surge,
                        ..Dynamics::default()
                    }
                }
                Kind::Drilling(_) => Dynamics::default(),
                Kind::Milling(mill) => {
                    let m = masses.mass_matrix(arm.robot(), &frames, Coordinates::Axis);
                    let first = dynamics::joint_compliance(arm, &frames, &point, &compliance.h)
                        .and_then(|c| modes::modes(&m, &c))
                        .map(|modes| modes.frequencies[0]);
                    let tooth_passing = mill.tooth_passing_frequency();
                    Dynamics {
                        surge: None,
                        first_frequency: first,
                        tooth_passing,
                        harmonic: first
                            .zip(tooth_passing)
                            .map(|(f, t)| Harmonic::nearest(f, t)),
                    }
                }
            }
        })
        .collect()
}

/// Whether point `i` (of a drilling operation) is an exit (module docs).
fn is_exit(results: &[Compensated], operations: &[Option<usize>], i: usize) -> bool {
    let Some(next) = results.get(i + 1) else {
        return true;
    };
    if operations[i + 1] != operations[i] {
        return true;
    }
    let tool_z = results[i].pose.rotation * Vector3::z();
    let step = next.pose.translation.vector - results[i].pose.translation.vector;
    step.dot(&tool_z) < 0.0
}

#[cfg(test)]
mod tests {
    use super::Harmonic;

    #[test]
    fn the_nearest_harmonic_and_its_distance() {
        let h = Harmonic::nearest(21.0, 20.0);
        assert_eq!(h.order, 1);
        assert!((h.distance - 0.05).abs() < 1e-15);
        let h = Harmonic::nearest(59.0, 20.0);
        assert_eq!(h.order, 3);
        assert!((h.distance - 1.0 / 60.0).abs() < 1e-15);
        // Below the tooth-passing frequency the first harmonic is the nearest.
        let h = Harmonic::nearest(5.0, 20.0);
        assert_eq!(h.order, 1);
        assert!((h.distance - 0.75).abs() < 1e-15);
    }
}
