//! Postures of a group that are not distinct (crate::design::distinct): close axis angles and the
//! same flange pose on another branch are flagged, distinct postures are not.

use nalgebra::Vector6;
use std::f64::consts::PI;
use stiffid::design::distinct::{near_pairs, JOINT_TOLERANCE};

/// On the paper's robot (a spherical wrist): a posture repeated 0.5 deg away and a wrist flip
/// (`q4 + pi`, `-q5`, `q6 + pi`: the same flange pose) are flagged, the flip as another branch
/// with its flanges within 1e-6 mm; the other pairs of a spread group are not.
#[test]
fn duplicate_postures_and_wrist_flips_are_flagged() {
    let setup = stiffid::setup::builtin("zhang2021-comau-nj165").unwrap();
    let robot = setup.robot();
    let a = Vector6::new(0.2, -0.3, 0.4, 0.5, 0.6, -0.7);
    let b = Vector6::new(-0.8, 0.1, -0.2, -1.0, 1.1, 0.9);
    let c = Vector6::new(1.0, 0.4, 0.1, 0.3, -0.9, 0.2);
    let near_a = a + Vector6::repeat(0.5_f64.to_radians());
    let flip_b = Vector6::new(b[0], b[1], b[2], b[3] + PI, -b[4], b[5] + PI);
    let group = [a, b, c, near_a, flip_b];
    let pairs = near_pairs(robot, &group);
    assert_eq!(pairs.len(), 2, "{pairs:?}");
    let dup = pairs.iter().find(|n| (n.a, n.b) == (0, 3)).unwrap();
    assert!((dup.joint_distance - 0.5_f64.to_radians()).abs() < 1e-12);
    assert!(!dup.same_pose_other_branch());
    let flip = pairs.iter().find(|n| (n.a, n.b) == (1, 4)).unwrap();
    assert!(flip.same_pose_other_branch() && flip.joint_distance > JOINT_TOLERANCE);
    assert!(
        flip.position_distance < 1e-9 && flip.angle_distance < 1e-9,
        "{flip:?}"
    );
    assert!(near_pairs(robot, &[a, b, c]).is_empty());
}
