//! Postures of a group that are not distinct (crate::design::distinct): close axis angles and the
//! same flange pose on another branch are flagged, distinct postures are not.

use nalgebra::Vector6;
use std::f64::consts::PI;
use stiffid::internal::design::distinct::near_pairs;

/// On the paper's robot (a spherical wrist): a posture repeated 0.5 deg away and a wrist flip
/// (`q4 + pi`, `-q5`, `q6 + pi`: the same flange pose) are flagged, the flip as another branch
/// with its flanges within 1e-6 mm; the other pairs of a spread group are not.
#[test]
fn duplicate_postures_and_wrist_flips_are_flagged() {
    let setup = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
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
    assert!(flip.same_pose_other_branch() && flip.joint_distance > 2f64.to_radians());
    assert!(
        flip.position_distance < 1e-9 && flip.angle_distance < 1e-9,
        "{flip:?}"
    );
    assert!(near_pairs(robot, &[a, b, c]).is_empty());
}

/// `distinct` in a pool choice: a pool of six spread postures, each with a repeat 0.5 deg away
/// (toward the middle of the bounds). Eight postures from it must hold at least two near pairs
/// (six places); with `distinct` the pool keeps the first of every pair, six postures are chosen
/// with no near pair, and eight are refused naming why.
#[test]
fn a_pool_choice_with_distinct_has_no_near_postures() {
    use stiffid::app::select::{self, Method, PoolInput, Request};
    use stiffid::internal::design::distinct::Distinctness;
    let setup = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    let bounds = setup.bounds();
    let middle = (bounds.lower + bounds.upper) / 2.0;
    let spread = stiffid::internal::design::random_group(&setup, 6, 3);
    let step = 0.5_f64.to_radians();
    let mut pool = spread.clone();
    pool.extend(
        spread
            .iter()
            .map(|q| q + (middle - q).map(|d| step * d.signum())),
    );
    let run = |n: usize, distinct: Option<Distinctness>| {
        select::run(&Request {
            setup: &setup,
            criterion: stiffid::internal::design::Criterion::RelativeA,
            purpose: Default::default(),
            calibration: Default::default(),
            method: Method::Pool,
            start: None,
            pool: Some(PoolInput {
                name: "pool".into(),
                postures: pool.clone(),
            }),
            postures: n,
            target_pct: None,
            options: Default::default(),
            restarts: Some(8),
            distinct,
            for_candidates: false,
            candidates: None,
            stations: Vec::new(),
            progress: &(),
            out: None,
            report_dir: None,
        })
    };
    let free = run(8, None).unwrap();
    assert!(free.near.len() >= 2, "{:?}", free.near);
    assert_eq!(free.warnings.len(), free.near.len());
    let strict = run(6, Some(Distinctness::default())).unwrap();
    assert!(strict.near.is_empty() && strict.warnings.is_empty());
    assert!(near_pairs(setup.robot(), &strict.postures).is_empty());
    let p = strict.pool.as_ref().unwrap();
    assert_eq!(p.usable, 6);
    let dropped: Vec<(usize, usize)> = (7..=12).map(|i| (i, i - 6)).collect();
    assert_eq!(p.not_distinct, dropped);
    let err = run(8, Some(Distinctness::default()))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("only 6 of the 12") && err.contains("are distinct"),
        "{err}"
    );
}

/// The measurement plan flags the same pairs: its document's `near_postures` (1-based) and a
/// warning per pair; a spread group has none.
#[test]
fn the_plan_flags_near_postures() {
    use stiffid::app::plan::{self, Request};
    use stiffid::app::WarningKind;
    let setup = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    let a = Vector6::new(0.2, -0.3, 0.4, 0.5, 0.6, -0.7);
    let b = Vector6::new(-0.8, 0.1, -0.2, -1.0, 1.1, 0.9);
    let c = Vector6::new(1.0, 0.4, 0.1, 0.3, -0.9, 0.2);
    let near_a = a + Vector6::repeat(0.5_f64.to_radians());
    let run = |group: &[Vector6<f64>]| {
        let request = Request {
            scene: false,
            setup: &setup,
            criterion: stiffid::internal::design::Criterion::RelativeA,
            postures: group,
            target_pct: None,
            external: &[],
        };
        plan::run(&request).unwrap()
    };
    let report = run(&[a, b, c, near_a]);
    let doc = serde_json::to_value(&report.report).unwrap();
    let near = doc["near_postures"].as_array().unwrap();
    assert_eq!(near.len(), 1);
    assert_eq!(near[0]["postures"], serde_json::json!([1, 4]));
    let distance = near[0]["joint_distance_deg"].as_f64().unwrap();
    assert!((distance - 0.5).abs() < 1e-9, "{distance}");
    assert_eq!(report.warnings.len(), 1);
    assert_eq!(report.warnings[0].kind, WarningKind::NearPostures);
    let spread = run(&[a, b, c]);
    assert!(spread.near.is_empty() && spread.warnings.is_empty());
}
