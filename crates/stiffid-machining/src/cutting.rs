//! Where the tool cuts: the one rule that decides which points of a program carry the process's
//! wrench, whatever language the program is written in, so that the same program as G-code, KRL,
//! RAPID, LS or INFORM gets the same wrench at the same points.
//!
//! A point cuts when an operation covers it ([`super::Operation`]'s selector) and
//! 1. it is reached by a feed move, not a joint move ([`joint_moves`]: G-code `G0`, KRL `PTP`,
//!    RAPID `MoveJ` and `MoveAbsJ`, LS `J`, INFORM `MOVJ`): a joint move approaches, retracts or
//!    moves between cuts;
//! 2. for a drilling operation, it is fed into the part: its feed ([`feeds`]) points towards the
//!    tool's tip, within [`DRILL_CONE_DEG`] of the tool axis. A drill's retract, or a move across
//!    its axis, cuts nothing; nor does a G-code canned cycle's feed in the air or in the hole
//!    already drilled ([`idle`]: from `R` down to the surface, a peck's re-entry), nor in any
//!    language the first feed after a joint move (an approach) that a further feed into the
//!    part continues: it brings the drill to the material, as a cycle written as moves does
//!    (its next point, the same again, is where the drill takes its thrust).
//!
//! A milling point fed along the tool axis (a plunge or a linear retract) keeps its operation but
//! takes no force ([`super::Operation::base_wrench`]: the feed frame needs a feed across the axis).

use crate::gcode::Motion;
use crate::process::{Kind, Operation};
use crate::program::generate::arcs::Circle;
use crate::Program;
use nalgebra::{Isometry3, Vector3};

/// The largest angle between a drilling point's feed and the tool axis (towards the tip) at
/// which the drill cuts, deg.
pub(crate) const DRILL_CONE_DEG: f64 = 45.0;

/// Whether each point is reached by a joint move: a G-code rapid move (`G0`), a robot
/// program's joint motion ([`crate::program::JointProgram::joint_moves`]).
pub(crate) fn joint_moves(program: &Program) -> Vec<bool> {
    match program {
        Program::GCode(g) => g.points.iter().map(|p| p.motion == Motion::Rapid).collect(),
        Program::Robot(r) => r.joint_moves(),
    }
}

/// Whether each point cuts nothing whatever covers it: reached by a joint move (`joint`,
/// [`joint_moves`]) or fed by a G-code canned cycle in the air or in the hole already drilled
/// ([`crate::gcode::GCode::drilled_in_air`]: the feed from `R` to the surface, a peck's
/// re-entry).
pub(crate) fn idle(program: &Program, joint: &[bool]) -> Vec<bool> {
    match program {
        Program::GCode(g) => (g.drilled_in_air().into_iter())
            .zip(joint)
            .map(|(air, j)| air || *j)
            .collect(),
        Program::Robot(_) => joint.to_vec(),
    }
}

/// Each point's feed: the TCP's motion from the previous point (the first point takes the
/// second's), in the frame of `poses`; a point that does not move (a dwell) keeps the feed
/// before it; `None` where no point has moved yet.
pub(crate) fn feeds(poses: &[Isometry3<f64>]) -> Vec<Option<Vector3<f64>>> {
    let mut previous = None;
    (0..poses.len())
        .map(|i| {
            let here = poses[i].translation.vector;
            let feed = match i {
                0 => poses.get(1).map(|p| p.translation.vector - here),
                _ => Some(here - poses[i - 1].translation.vector),
            }
            .filter(|f| f.norm() > 1e-12)
            .or(previous);
            previous = feed;
            feed
        })
        .collect()
}

/// Each point's feed ([`feeds`]), a robot program's circular motion's via point and end fed
/// along the circle through its start, via point and end (its tangent there, the direction the
/// tool moves: as a G-code arc's chord points are, each fed along the arc), not along the chord
/// from the point before; `poses` in the frame the feed is measured in.
pub(crate) fn feeds_of(program: &Program, poses: &[Isometry3<f64>]) -> Vec<Option<Vector3<f64>>> {
    let mut feeds = feeds(poses);
    let Program::Robot(r) = program else {
        return feeds;
    };
    let p = |i: usize| poses[i].translation.vector;
    for (i, t) in r.targets.iter().enumerate() {
        if !t.via || i == 0 || i + 1 >= poses.len() {
            continue;
        }
        let Some(circle) = Circle::through(&p(i - 1), &p(i), &p(i + 1)) else {
            continue;
        };
        feeds[i] = Some(circle.tangent(&p(i)) * (p(i) - p(i - 1)).norm());
        feeds[i + 1] = Some(circle.tangent(&p(i + 1)) * (p(i + 1) - p(i)).norm());
    }
    feeds
}

/// The operation each point cuts under (module docs), from `covered`, the operation covering
/// each point: `None` at a joint move (`joint`) and at a drilling point not fed into the part;
/// `poses` the TCP poses in the frame the feed is measured in (the part's when the part moves),
/// `feeds` their feeds ([`feeds_of`]).
///
/// # Panics
/// If `joint`, `poses`, `feeds` and `covered` differ in length.
pub(crate) fn cutting<'a>(
    joint: &[bool],
    (poses, feeds): (&[Isometry3<f64>], &[Option<Vector3<f64>>]),
    covered: Vec<Option<(usize, &'a Operation)>>,
) -> Vec<Option<(usize, &'a Operation)>> {
    assert!(joint.len() == poses.len() && poses.len() == covered.len());
    assert_eq!(feeds.len(), poses.len());
    let cos = DRILL_CONE_DEG.to_radians().cos();
    covered
        .into_iter()
        .enumerate()
        .map(|(i, op)| {
            let (_, o) = op?;
            if joint[i] {
                return None;
            }
            match o.kind {
                Kind::Milling(_) => op,
                Kind::Drilling(_) => {
                    let into = |k: usize| {
                        let tip = poses[k].rotation * Vector3::z();
                        feeds[k].is_some_and(|f| f.dot(&tip) > cos * f.norm())
                    };
                    // The first feed after an approach, continued by a deeper one, brings the
                    // drill to the material: it cuts from there on.
                    let moved = i > 0 && poses[i].translation != poses[i - 1].translation;
                    let approach = moved && joint[i - 1] && joint.get(i + 1) == Some(&false);
                    match into(i) && !(approach && into(i + 1)) {
                        true => op,
                        false => None,
                    }
                }
            }
        })
        .collect()
}
