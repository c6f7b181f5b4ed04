//! The arcs of a compensated G-code path as the robot program's circular moves ([`arcs`]): which
//! targets are written and how, in the controller's kinematics.

use super::super::{arcs, written_targets, Move, Settings, Target, Targets};
use crate::compensate::{Compensated, PathPoint};
use crate::gcode::ArcBlock;
use crate::program::Dialect;
use crate::Report;
use arcs::{Circular, Form};
use nalgebra::Vector3;
use stiffid_core::{Result, Robot};

/// The targets and moves a program of `dialect` is written with, the arcs `arcs` as circular
/// moves where they stay within `tolerance` (m, the chord tolerance), with what each written
/// target stands for and the warnings; `controller`: the controller's kinematics the circles
/// are checked in when the targets are written as axis angles (INFORM's pulses; `Err`: not
/// known, its arcs as chords).
pub(super) fn circular(
    (dialect, settings): (Dialect, &Settings),
    arcs: &[ArcBlock],
    (targets, moves): (Vec<Target>, Vec<Move>),
    (tcp, compensated, controller): (&Vector3<f64>, &Report, Result<&Robot>),
    tolerance: f64,
) -> (Vec<Target>, Vec<Move>, Circular, Option<Form>) {
    let form = (dialect.controller().generator()).and_then(|g| g.circular(settings.targets));
    let cartesian = written_targets(dialect, settings.targets) == Targets::Cartesian;
    let positions: Option<Vec<Vector3<f64>>> = match (cartesian, controller) {
        (true, _) => Some(targets.iter().map(|t| t.pose.translation.vector).collect()),
        (false, Ok(robot)) => Some(
            (compensated.results.iter().zip(&compensated.points))
                .map(|(r, p)| {
                    let e = values(r, p);
                    Target::at(robot, tcp, &r.q_compensated, e)
                        .pose
                        .translation
                        .vector
                })
                .collect(),
        ),
        (false, Err(_)) => None,
    };
    let (Some(form), Some(positions)) = (form, positions) else {
        let mut plain = identity(targets.len(), &moves);
        let why = match form {
            None => "joint targets: the controller interpolates the axes between them",
            Some(_) => "the controller's kinematics, in which a circle is checked, are not known",
        };
        plain.warnings.extend(arcs::kept_as_points(arcs, why));
        return (targets, moves, plain, form);
    };
    let c = arcs::circular(arcs, (&targets, &positions, &moves), tolerance, form);
    let written = c.index.iter().map(|&i| targets[i].clone()).collect();
    let moves = c.moves.clone();
    (written, moves, c, Some(form))
}

/// Every target written as itself.
fn identity(n: usize, moves: &[Move]) -> Circular {
    Circular {
        index: (0..n).collect(),
        moves: moves.to_vec(),
        covers: (0..n).map(|i| i..i + 1).collect(),
        warnings: Vec::new(),
    }
}

/// The external axes' values of a compensated point (SI): those the compensation chose (a free
/// station), else the program's.
pub(super) fn values<'a>(r: &'a Compensated, p: &'a PathPoint) -> &'a [f64] {
    match r.external.is_empty() {
        true => p.external.as_slice(),
        false => r.external.as_slice(),
    }
}
