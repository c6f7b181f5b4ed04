//! The home posture of a generated program (`[controller] home_deg`): a joint motion to it before
//! the first target and back to it after the last, so that a program starts and ends where the
//! cell's other programs expect the robot. Its targets are written as every other target of the
//! program (Cartesian: the controller's forward kinematics of the home angles with their
//! configuration, which its inverse kinematics returns; joint: the angles), at the rapid speed;
//! a cell's external axes keep the first (last) target's values. The home posture is checked
//! against the robot's joint limits when the setup is read.

use super::super::{Move, Target};
use nalgebra::Vector6;
use stiffid_core::{Robot, Setup};

/// Adds the home posture of `setup` (if any) before the first and after the last of `targets`
/// (with a rapid move and no G-code line); whether it did.
pub(super) fn add(
    setup: &Setup,
    controller: &Robot,
    (targets, moves, lines): (&mut Vec<Target>, &mut Vec<Move>, &mut Vec<Option<u64>>),
) -> bool {
    let Some(home) = setup.workcell().controller().program.home_deg else {
        return false;
    };
    let (Some(first), Some(last)) = (targets.first(), targets.last()) else {
        return false;
    };
    let tool = setup.tool();
    let q = Vector6::from(home).map(f64::to_radians);
    let at = |t: &Target| {
        let e = setup
            .robot()
            .external()
            .map_or(Vec::new(), |a| a.to_si(&t.external));
        let mut h = Target::at(controller, &tool.tcp, &q, &e);
        h.pose.rotation *= tool.rotation;
        h
    };
    let (start, end) = (at(first), at(last));
    targets.insert(0, start);
    targets.push(end);
    moves.insert(0, Move::Rapid);
    moves.push(Move::Rapid);
    lines.insert(0, None);
    lines.push(None);
    true
}
