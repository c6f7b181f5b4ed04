//! The design criteria against independent formulas, their units, and rank deficiency.

use nalgebra::{DMatrix, Matrix6, Vector6};
use stiffid::internal::common::limits::JointBox;
use stiffid::internal::design::{self, criteria, Criterion, Evaluator};
use stiffid::internal::observation::{posture_block, rope_observation_matrix};
use stiffid::internal::robot::AxisMap;
use stiffid::internal::setup::{self, Noise, RopeLoad, Setup};
use stiffid::Robot;

fn paper() -> Setup {
    setup::builtin("zhang2021-comau-nj165").unwrap()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

fn cond(m: &DMatrix<f64>) -> f64 {
    let s = m.clone().svd(false, false).singular_values;
    s.max() / s.min()
}

/// Every criterion from its definition: `Psi` from the observation module, `S` formed explicitly,
/// singular values by SVD and `(S^T S)^-1` by explicit inversion.
fn reference(setup: &Setup, group: &[Vector6<f64>]) -> (Vec<f64>, Vector6<f64>) {
    let psi = rope_observation_matrix(setup, group);
    let h = setup.nominal_compliance().unwrap();
    let sigma = setup.noise().displacement_sd();
    let s =
        &psi * DMatrix::from_diagonal(&nalgebra::DVector::from_column_slice(h.as_slice())) / sigma;
    let c: Matrix6<f64> = (s.transpose() * &s)
        .fixed_view::<6, 6>(0, 0)
        .into_owned()
        .try_inverse()
        .unwrap();
    let unit_cov = (psi.transpose() * &psi).try_inverse().unwrap();
    let classical = criteria::classical(setup, group);
    let test_pose = setup
        .test_postures()
        .iter()
        .map(|q| {
            let frames = setup.robot().frames(q);
            let a = posture_block(setup.arm(), &frames, &setup.rope_wrench(&frames));
            (&a * &unit_cov * a.transpose()).trace()
        })
        .sum::<f64>()
        / setup.test_postures().len() as f64;
    let values = vec![
        classical,
        classical * cond(&psi),
        cond(&s),
        c.determinant().powf(1.0 / 12.0),
        (c.trace() / 6.0).sqrt(),
        sigma * test_pose.sqrt(),
    ];
    (values, c.diagonal().map(f64::sqrt))
}

#[test]
fn every_criterion_matches_its_definition() {
    let setup = paper();
    for seed in 0..5 {
        let group = design::random_group(&setup, 6, seed);
        let (want, want_std) = reference(&setup, &group);
        let e = design::evaluate(&setup, &group);
        let fast = Evaluator::new(&setup);
        for (c, w) in Criterion::ALL.into_iter().zip(&want) {
            assert!(rel(e.value(c), *w) < 1e-8, "{c}: {} vs {w}", e.value(c));
            assert!(rel(fast.value(c, &group), *w) < 1e-8, "{c} (value)");
        }
        assert!(rel(e.cond_psi, want[1] / want[0]) < 1e-8);
        for j in 0..6 {
            assert!(rel(e.relative_std[j], want_std[j]) < 1e-8);
            for (l, m) in setup.noise().levels.iter().enumerate() {
                let pct = 100.0 * (2.0 / std::f64::consts::PI).sqrt() * m.sqrt() * want_std[j];
                assert!(rel(e.predicted_deviation_pct[l][j], pct) < 1e-8);
            }
        }
    }
}

#[test]
fn hand_case_predicted_deviation_rate() {
    // 100 sqrt(2/pi) sqrt(m) s: s = 0.01 at m = 4 gives 100 * 0.797885 * 2 * 0.01.
    let p = criteria::predicted_deviation_pct(&Vector6::repeat(0.01), 4.0);
    for v in p {
        assert!((v - 1.595769).abs() < 1e-6, "{v}");
    }
}

/// The setup with joint coordinates `q' = D^-1 q` (a gear ratio on each spring): `M' = M D`, joint
/// limits, bounds and test postures `D^-1`, stiffness `k' = k d^2` (same spring energy). Psi's columns scale by
/// `d^2`, the compliances by `1/d^2`: the identification problem is the same, in other units.
fn in_other_joint_units(setup: &Setup, d: &Vector6<f64>) -> Setup {
    let r = setup.robot();
    let (map, limits) = (r.axis_map(), r.limits());
    let robot = r
        .clone()
        .with_axis_map(AxisMap {
            matrix: map.matrix * Matrix6::from_diagonal(d),
            offset: map.offset,
        })
        .and_then(|r| {
            r.with_limits(JointBox {
                lower: limits.lower.component_div(d),
                upper: limits.upper.component_div(d),
            })
        })
        .unwrap();
    let b = setup.bounds();
    setup
        .to_builder()
        .with_robot(robot)
        .with_bounds(JointBox {
            lower: b.lower.component_div(d),
            upper: b.upper.component_div(d),
        })
        .with_nominal_stiffness(
            setup
                .nominal_stiffness()
                .unwrap()
                .component_mul(&d.component_mul(d)),
        )
        .with_test_postures(
            setup
                .test_postures()
                .iter()
                .map(|q| q.component_div(d))
                .collect(),
        )
        .build()
        .unwrap()
}

/// The setup with every length times `c` (robot, tool, anchor, characteristic length, noise sigma)
/// and torques and stiffness in the matching unit (`k c`): e.g. metres to kilometres with
/// `c = 1e-3` (the setup's ranges hold the paper's cell in km, not in mm).
fn in_other_length_unit(setup: &Setup, c: f64) -> Setup {
    let r = setup.robot();
    let scale = |iso: &nalgebra::Isometry3<f64>| {
        let mut iso = *iso;
        iso.translation.vector *= c;
        iso
    };
    let mut joints = r.joints().clone();
    for j in &mut joints {
        j.pre = scale(&j.pre);
        j.post = scale(&j.post);
    }
    let robot = Robot::new(r.name(), r.source(), joints, *r.limits())
        .and_then(|x| x.with_axis_map(r.axis_map().clone()))
        .and_then(|x| x.with_base(scale(r.base())))
        .and_then(|x| x.with_flange(scale(r.flange())))
        .unwrap()
        .with_bodies(r.bodies().clone());
    let (tool, load, noise) = (setup.tool(), setup.load(), setup.noise());
    setup
        .to_builder()
        .with_robot(robot)
        .with_loading_point(tool.loading_point * c)
        .with_tcp(tool.tcp * c)
        .with_measuring_points(tool.measuring_points.iter().map(|p| p * c).collect())
        .with_load(RopeLoad {
            anchor: load.anchor * c,
            ..load.clone()
        })
        .with_characteristic_length(setup.characteristic_length().unwrap() * c)
        .with_noise(Noise {
            reading_variance: noise.reading_variance * c * c,
            ..noise.clone()
        })
        .with_nominal_stiffness(setup.nominal_stiffness().unwrap() * c)
        .build()
        .unwrap()
}

#[test]
fn scale_free_criteria_do_not_depend_on_units_and_the_papers_index_does() {
    let setup = paper();
    let group = design::random_group(&setup, 6, 4);
    let base = design::evaluate(&setup, &group);

    let c = 1e-3;
    let km = design::evaluate(&in_other_length_unit(&setup, c), &group);
    for k in [
        Criterion::DOptimal,
        Criterion::RelativeA,
        Criterion::ScaledCond,
        Criterion::Zhang2021,
    ] {
        assert!(rel(km.value(k), base.value(k)) < 1e-8, "{k} in km");
    }
    assert!(
        rel(km.test_pose, base.test_pose * c) < 1e-8,
        "test-pose is a length"
    );

    let d = Vector6::new(1.0, 10.0, 1.0, 0.5, 1.0, 0.1);
    let geared = in_other_joint_units(&setup, &d);
    let geared_group: Vec<_> = group.iter().map(|q| q.component_div(&d)).collect();
    let g = design::evaluate(&geared, &geared_group);
    for k in [
        Criterion::DOptimal,
        Criterion::RelativeA,
        Criterion::ScaledCond,
        Criterion::TestPose,
    ] {
        assert!(
            rel(g.value(k), base.value(k)) < 1e-8,
            "{k}: {} vs {}",
            g.value(k),
            base.value(k)
        );
    }
    for j in 0..6 {
        assert!(rel(g.relative_std[j], base.relative_std[j]) < 1e-8);
    }
    let change = g.zhang2021 / base.zhang2021;
    assert!(
        !(0.5..2.0).contains(&change),
        "zhang2021 changed by only {change}"
    );
    println!(
        "zhang2021 changes by a factor {change:.2} with the joint units; cond(Psi) by {:.2}",
        g.cond_psi / base.cond_psi
    );
}

#[test]
fn rank_deficient_groups_are_infinite_never_nan() {
    let setup = paper();
    let fast = Evaluator::new(&setup);
    // q5 = 0: axes 4 and 6 collinear, equal columns of Psi.
    let wrist: Vec<_> = design::random_group(&setup, 6, 5)
        .into_iter()
        .map(|mut q| {
            q[4] = 0.0;
            q
        })
        .collect();
    // One posture repeated: rows are those of one posture (rank 6 at most), still full rank, so
    // also try a single posture repeated at the wrist singularity.
    let repeated = vec![wrist[0]; 6];
    for group in [wrist, repeated] {
        let e = design::evaluate(&setup, &group);
        for c in Criterion::ALL
            .into_iter()
            .filter(|&c| c != Criterion::Classical)
        {
            assert_eq!(e.value(c), f64::INFINITY, "{c}");
            assert_eq!(fast.value(c, &group), f64::INFINITY, "{c}");
        }
        assert!(e.relative_std.iter().all(|s| *s == f64::INFINITY));
        assert!(e
            .predicted_deviation_pct
            .iter()
            .flatten()
            .all(|s| *s == f64::INFINITY));
    }
}
