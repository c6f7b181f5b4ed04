//! The free configuration: the path compensated in every configuration of the arm, the one
//! chosen equal to an exhaustive evaluation of each configuration compensated alone, every
//! configuration's postures on the path's poses, refusals naming the point, the path's own kept
//! when no other takes the path, and the combinations refused.

use crate::common::on_robot;
use crate::compensate::{line_path, options};
use nalgebra::{Translation3, UnitQuaternion, Vector3, Vector6};
use stiffid::internal::common::limits::JointBox;
use stiffid::internal::machining::compensate::{
    self, path_configurations, Aggregate, Compensated, Configurations, Free, FreeVariables,
    Objective, Options, PathPoint, Scope, Target,
};
use stiffid::internal::robot::ik::tool_pose;
use stiffid::{internal::setup, Coordinates, Error, JobOption, Setup};

/// The FANUC preset with its TCP on the flange axis, 250 mm out, and joint limits `limits_deg`
/// (lower, upper per axis).
pub(crate) fn fanuc(limits_deg: [(f64, f64); 6]) -> Setup {
    let s = setup::builtin("fanuc-r2000ic-165f").unwrap();
    let tcp = Vector3::new(0.0, 0.0, 0.25);
    let s = s
        .to_builder()
        .with_tcp(tcp)
        .with_loading_point(tcp)
        .build()
        .unwrap();
    let lower = Vector6::from_fn(|i, _| limits_deg[i].0.to_radians());
    let upper = Vector6::from_fn(|i, _| limits_deg[i].1.to_radians());
    let robot = s
        .robot()
        .clone()
        .with_limits(JointBox::new(lower, upper))
        .unwrap();
    on_robot(&s, robot, Coordinates::Axis)
}

/// Every axis within +-300 deg: every configuration of the arm reaches the path.
pub(crate) const WIDE: [(f64, f64); 6] = [(-300.0, 300.0); 6];

fn free_options(s: &Setup, aggregate: Aggregate) -> Options {
    Options {
        free: FreeVariables {
            free: vec![Free::Configuration(Scope::Program)],
            minimise: Objective::Bound,
            aggregate,
        },
        ..options(s, None)
    }
}

/// The largest and the summed bound of a compensated path, m.
fn peak_sum(results: &[Compensated]) -> (f64, f64) {
    let bounds = results.iter().map(|r| r.budget.bound);
    (bounds.clone().fold(0.0, f64::max), bounds.sum())
}

/// Each configuration compensated alone: the path's own as given, every other from its first
/// posture with the points' poses.
fn alone(
    s: &Setup,
    path: &[PathPoint],
    o: &Options,
    c: &Configurations,
) -> Vec<Option<Vec<Compensated>>> {
    let compliance = s.model_compliance("test").unwrap();
    let mut plain = o.clone();
    plain.free = plain.free.keeping(|f| !matches!(f, Free::Configuration(_)));
    // The points' poses: each posture target replaced by its TCP pose, by hand.
    let pose = |q: &Vector6<f64>| tool_pose(&s.robot().frames(q), &s.tool().tcp);
    let moved: Vec<PathPoint> = (path.iter())
        .map(|p| match &p.target {
            Target::Posture(q) => PathPoint {
                target: Target::Pose(pose(q)),
                ..p.clone()
            },
            Target::Pose(_) => p.clone(),
        })
        .collect();
    (c.branches.iter())
        .map(|b| {
            let q0 = Vector6::from(b.configuration.q_deg).map(f64::to_radians);
            let run = match b.own {
                true => compensate::path(s.arm(), &compliance, path, &plain),
                false => compensate::path(
                    s.arm(),
                    &compliance,
                    &moved,
                    &Options {
                        q0,
                        ..plain.clone()
                    },
                ),
            };
            run.ok()
        })
        .collect()
}

#[test]
fn the_configuration_chosen_is_the_best_of_every_configuration_compensated_alone() {
    let s = fanuc(WIDE);
    let path = line_path(&s, 12);
    let compliance = s.model_compliance("test").unwrap();
    for aggregate in [Aggregate::Sum, Aggregate::Max] {
        let o = free_options(&s, aggregate);
        let (results, c) = path_configurations(s.arm(), &compliance, &path, &o).unwrap();
        assert!(c.branches.len() >= 4, "{:?}", c.branches.len());
        let keys: Vec<_> = (c.branches.iter())
            .map(|b| {
                (
                    b.configuration.behind(),
                    b.configuration.elbow_down(),
                    b.configuration.wrist_negative(),
                )
            })
            .collect();
        let mut distinct = keys.clone();
        distinct.dedup();
        assert_eq!(distinct, keys, "one branch per configuration, in order");
        let runs = alone(&s, &path, &o, &c);
        let mut best: Option<(usize, f64)> = None;
        for (k, (b, run)) in c.branches.iter().zip(&runs).enumerate() {
            let run = run.as_ref().expect("every configuration reaches the path");
            let (peak, sum) = peak_sum(run);
            // Equal to the inverse kinematics' tolerance (the start given in degrees).
            assert!((b.peak.unwrap() - peak).abs() <= 1e-8 * peak, "{k}");
            assert!((b.sum.unwrap() - sum).abs() <= 1e-8 * sum, "{k}");
            // Every posture reaches the point's pose (forward kinematics) and stays in the
            // configuration.
            for (p, r) in path.iter().zip(run) {
                let Target::Pose(t) = &p.target else {
                    unreachable!()
                };
                let at = tool_pose(&s.robot().frames(&r.q), &s.tool().tcp);
                assert!(
                    (at.translation.vector - t.translation.vector).norm() < 1e-7,
                    "{k}"
                );
                assert!(at.rotation.angle_to(&t.rotation) < 1e-7, "{k}");
            }
            let value = match aggregate {
                Aggregate::Sum => sum,
                Aggregate::Max => peak,
            };
            if b.refused.is_none() && best.is_none_or(|(_, v)| value < v * (1.0 - 1e-6)) {
                best = Some((k, value));
            }
        }
        let (k, value) = best.unwrap();
        assert_eq!(c.chosen, k, "{aggregate:?}");
        let own = c.branches.iter().position(|b| b.own).unwrap();
        let own_value = match aggregate {
            Aggregate::Sum => c.branches[own].sum.unwrap(),
            Aggregate::Max => c.branches[own].peak.unwrap(),
        };
        assert!(value <= own_value, "never worse than the path's own");
        // The configurations differ: the best gains on the path's own here.
        assert!(value < 0.99 * own_value, "{value} against {own_value}");
        let chosen = runs[k].as_ref().unwrap();
        for (r, e) in results.iter().zip(chosen) {
            assert!((r.q_compensated - e.q_compensated).amax() < 1e-9);
        }
    }
}

/// The path of `s`'s first test pose turned about tool z by 0, -10, ..., -60 deg: axis 6 alone
/// turns (the TCP on its axis).
fn turning_path(s: &Setup) -> Vec<PathPoint> {
    let start = tool_pose(&s.robot().frames(&s.test_postures()[0]), &s.tool().tcp);
    (0..7)
        .map(|i| {
            let turn = UnitQuaternion::from_axis_angle(
                &Vector3::z_axis(),
                -(10.0 * i as f64).to_radians(),
            );
            PathPoint {
                line: i as u64 + 2,
                target: Target::Pose(Translation3::identity() * start * turn),
                wrench: Vector6::new(200.0, 0.0, -100.0, 0.0, 0.0, 0.0),
                frame: stiffid::internal::observation::deflection::Frame::Tool,
                external: stiffid::internal::robot::external::ExternalValues::NONE,
            }
        })
        .collect()
}

#[test]
fn a_configuration_that_fails_a_point_is_refused_naming_it_and_the_path_own_is_kept() {
    let mut limits = [
        (-185.0, 185.0),
        (-60.0, 76.0),
        (-132.0, 180.0),
        (-360.0, 360.0),
        (-125.0, 125.0),
        (-200.0, 200.0),
    ];
    let s0 = fanuc(limits);
    let q6 = s0.test_postures()[0][5].to_degrees();
    // Axis 6 within 200 deg of the first posture's angle, the other way round than it turns:
    // the wrist's flip (axis 6 half a turn off) runs into the limit's margin along the path.
    limits[5] = (q6 - 200.0, q6 + 200.0);
    let s = fanuc(limits);
    let path = turning_path(&s);
    let compliance = s.model_compliance("test").unwrap();
    let o = free_options(&s, Aggregate::Sum);
    let (results, c) = path_configurations(s.arm(), &compliance, &path, &o).unwrap();
    let own = c.branches.iter().find(|b| b.own).unwrap();
    assert!(c.branches[c.chosen].own);
    let flip = (c.branches.iter())
        .find(|b| !b.own && b.configuration.wrist_negative() != own.configuration.wrist_negative())
        .expect("the wrist's flip reaches the first point");
    // Its axis 6 sits half a turn from the path's own; the first point whose angle there is
    // within the margin (5 deg) of a limit is the one named.
    let side = flip.configuration.q_deg[5] - own.configuration.q_deg[5];
    assert!((side.abs() - 180.0).abs() < 1e-6, "{side}");
    let margin = 5.0;
    let first = (path.iter().zip(&results))
        .find(|(_, r)| {
            let at = r.q[5].to_degrees() + side;
            at < limits[5].0 + margin || at > limits[5].1 - margin
        })
        .map(|(p, _)| p.line)
        .unwrap();
    let (line, why) = flip.refused.clone().unwrap();
    assert_eq!(line, Some(first), "{why}");
    // The first point within the margin: its posture fails the margin, or (at the limit) its
    // compensation leaves the joint limits.
    assert!(
        why.contains("margin") || why.contains("joint limits"),
        "{why}"
    );
    assert!(c
        .branches
        .iter()
        .filter(|b| !b.own)
        .all(|b| b.refused.is_some()));
    assert!(
        c.warnings
            .iter()
            .any(|w| w.contains("no other configuration")),
        "{:?}",
        c.warnings
    );
    // The path's own, as compensated without the free configuration.
    let plain = compensate::path(s.arm(), &compliance, &path, &options(&s, None)).unwrap();
    for (r, e) in results.iter().zip(&plain) {
        assert_eq!(r.q_compensated, e.q_compensated);
    }
}

#[test]
fn the_free_configuration_refuses_the_surge_and_too_long_paths_naming_itself() {
    let s = fanuc(WIDE);
    let mut o = options(&s, Some(crate::compensate::rotation(90.0, 2.0)));
    o.free.minimise = Objective::Surge;
    o.validate().unwrap();
    o.free.set(Free::Configuration(Scope::Program));
    match o.validate().unwrap_err() {
        Error::InvalidOption { option, message } => {
            assert_eq!(option, JobOption::Minimise);
            assert!(message.contains("configuration"), "{message}");
        }
        e => panic!("{e}"),
    }
    let o = free_options(&s, Aggregate::Max);
    let compliance = s.model_compliance("test").unwrap();
    let one = line_path(&s, 1);
    let long = vec![one[0].clone(); 100_000 + 1];
    match path_configurations(s.arm(), &compliance, &long, &o).unwrap_err() {
        Error::InvalidOption { option, message } => {
            assert_eq!(option, JobOption::Configuration);
            assert!(message.contains("100000"), "{message}");
        }
        e => panic!("{e}"),
    }
}
