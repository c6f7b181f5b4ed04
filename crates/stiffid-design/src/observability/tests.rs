//! The calibration's observability criteria (`crate::observability`).

use crate::observability::*;
use crate::study::observability as study;
use nalgebra::{DMatrix, Vector6};
use nalgebra::{Isometry3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use stiffid_core::robot::external::ExternalValues;
use stiffid_core::robot::presets;
use stiffid_core::Robot;
use stiffid_metrology::calibration::error_model::{MeasuredIn, Target};
use stiffid_metrology::calibration::ErrorModel;
use stiffid_metrology::calibration::{fit, gravity, validation, Estimate, Geometry};

const LENGTH: f64 = 1.0;

fn postures(robot: &Robot, n: usize, seed: u64) -> Vec<Vector6<f64>> {
    study::postures(robot, n, &mut ChaCha8Rng::seed_from_u64(seed))
}

fn design(noise: f64) -> (Robot, CalibrationDesign) {
    let robot = presets::get("fanuc-r2000ic-165f").unwrap();
    let points = [
        Vector3::new(0.15, 0.0, 0.25),
        Vector3::new(-0.1, 0.12, 0.3),
        Vector3::new(0.0, -0.14, 0.2),
    ];
    let g = gravity::Terms::lumped(&robot, stiffid_core::Coordinates::Axis);
    let model = ErrorModel::new(&robot, &points, MeasuredIn::Tracker, Geometry::Full, g).unwrap();
    let reference = postures(&robot, 60, 1);
    let test = postures(&robot, 20, 2);
    let d = CalibrationDesign::new(model, LENGTH, &reference, &test, noise).unwrap();
    (robot, d)
}

#[test]
fn criteria_match_a_direct_svd() {
    let (robot, d) = design(5e-5);
    let group = postures(&robot, 14, 3);
    let c = d.evaluate(&group).unwrap();
    // Direct: the unscaled Jacobian, the kept columns scaled by hand.
    let model = d.model();
    let scales = model.column_scales(LENGTH, &postures(&robot, 60, 1));
    let scaled = |qs: &[Vector6<f64>]| {
        let at: Vec<_> = (qs.iter())
            .flat_map(|q| (0..3).map(move |k| (*q, k)))
            .collect();
        let j = model.jacobian(&model.nominal(), &at).unwrap();
        DMatrix::from_fn(j.nrows(), d.kept().len(), |r, c| {
            j[(r, d.kept()[c])] * scales[d.kept()[c]]
        })
    };
    let j = scaled(&group);
    let s = j.clone().svd(false, false).singular_values;
    let p = s.len();
    assert_eq!(c.parameters, p);
    assert!(p > 30, "kept {p}");
    let product: f64 = s.iter().map(|v| v.ln()).sum::<f64>();
    let close = |a: f64, b: f64| assert!((a - b).abs() <= 1e-9 * b.abs(), "{a} against {b}");
    close(c.o1, (product / p as f64).exp() / (14f64).sqrt());
    close(c.o3, s.min());
    close(c.o4, s.min() * s.min() / s.max());
    close(c.o5, 1.0 / s.iter().map(|v| 1.0 / v).sum::<f64>());
    // D-optimality against the determinant of the information matrix (LU, a test only).
    let information = j.transpose() * &j;
    close(
        c.d_optimality.ln() * p as f64,
        information.determinant().ln(),
    );
    // The test-pose error against the pseudo-inverse.
    let a0 = scaled(&postures(&robot, 20, 2));
    let pinv = j.clone().pseudo_inverse(1e-14).unwrap();
    let direct = 5e-5 * ((&a0 * pinv).norm_squared() / 60.0).sqrt();
    assert!((c.predicted_rms - direct).abs() <= 1e-7 * direct);
}

#[test]
fn a_group_that_cannot_separate_the_parameters_scores_worst() {
    let (robot, d) = design(5e-5);
    let c = d.evaluate(&postures(&robot, 3, 4)).unwrap();
    assert_eq!((c.o3, c.o4, c.o5), (0.0, 0.0, 0.0));
    assert!(c.predicted_rms.is_infinite());
    assert!(d.evaluate(&[]).is_err());
    assert!(
        CalibrationDesign::new(d.model().clone(), 0.0, &[Vector6::zeros()], &[], 1e-5).is_err()
    );
}

/// The predicted RMS error at the test postures within 10% of a Monte Carlo of calibrations:
/// noisy readings of a robot with known errors, fitted by Levenberg-Marquardt, the calibrated
/// model's error at the test postures against the true positions.
#[test]
fn predicted_error_matches_a_monte_carlo_of_calibrations() {
    let noise = 5e-5;
    let (robot, d) = design(noise);
    let model = d.model();
    let group = postures(&robot, 12, 5);
    let test = postures(&robot, 20, 2);
    let predicted = d.evaluate(&group).unwrap().predicted_rms;
    let mut rng = ChaCha8Rng::seed_from_u64(6);
    let mut truth = model.nominal();
    for &c in d.kept().iter().filter(|&&c| c >= 6) {
        let p = &model.parameters()[c];
        let at = d.kept().iter().position(|&k| k == c).unwrap();
        let size = match p.kind {
            stiffid_metrology::calibration::Kind::Gravity => 1e-4 * d.layout.scales[at],
            _ => 1e-3,
        };
        truth[c] += size * (2.0 * rng.random::<f64>() - 1.0);
    }
    let frame = Isometry3::new(Vector3::new(3.2, -1.1, 0.4), Vector3::new(0.1, -0.05, 2.4));
    let truth = Estimate {
        frame,
        values: truth,
    };
    let held_out =
        crate::study::observability_tests::read(model, &truth, &test, 0.0, &mut rng).unwrap();
    let options = fit::Options {
        length: LENGTH,
        priors: None,
        ridge: 0.0,
        gravity: None,
    };
    let runs = 100;
    let mut squares = 0.0;
    for _ in 0..runs {
        let readings =
            crate::study::observability_tests::read(model, &truth, &group, noise, &mut rng)
                .unwrap();
        let start = fit::start(model, &readings).unwrap();
        let f = fit::fit(model, &readings, &start, &options).unwrap();
        // The same rank (a family of lumped terms may keep another member: the same span).
        assert_eq!(f.identifiability.rank, d.kept().len());
        let v = validation::validate(model, &f.estimate, &held_out).unwrap();
        squares += v.rms * v.rms;
    }
    let monte_carlo = (squares / runs as f64).sqrt();
    let ratio = predicted / monte_carlo;
    assert!(
        (0.9..1.1).contains(&ratio),
        "{predicted} against {monte_carlo}"
    );
}

/// A design on the FANUC preset (coupled J2/J3 axis map) with the gravity model `g`.
fn design_with(g: impl Fn(&Robot) -> gravity::Terms) -> (Robot, CalibrationDesign) {
    let robot = presets::get("fanuc-r2000ic-165f").unwrap();
    let masses: [stiffid_core::robot::LinkMass; 6] =
        std::array::from_fn(|l| stiffid_core::robot::LinkMass {
            mass: 200.0 - 30.0 * l as f64,
            centre: Vector3::new(0.05 * l as f64, -0.03, 0.1 + 0.02 * l as f64),
            ..Default::default()
        });
    let robot = robot.with_masses(Some(masses));
    let points = [
        Vector3::new(0.15, 0.0, 0.25),
        Vector3::new(-0.1, 0.12, 0.3),
        Vector3::new(0.0, -0.14, 0.2),
    ];
    let model = ErrorModel::new(
        &robot,
        &points,
        MeasuredIn::Tracker,
        Geometry::Full,
        g(&robot),
    )
    .unwrap();
    let reference = postures(&robot, 60, 1);
    let test = postures(&robot, 20, 2);
    let d = CalibrationDesign::new(model, LENGTH, &reference, &test, 5e-5).unwrap();
    (robot, d)
}

/// A gravity model of a robot.
type GravityOf = Box<dyn Fn(&Robot) -> gravity::Terms>;

fn gravity_models() -> Vec<(&'static str, GravityOf)> {
    vec![
        ("none", Box::new(gravity::Terms::none)),
        (
            "lumped",
            Box::new(|r: &Robot| gravity::Terms::lumped(r, stiffid_core::Coordinates::Axis)),
        ),
        (
            "lumped kinematic",
            Box::new(|r: &Robot| gravity::Terms::lumped(r, stiffid_core::Coordinates::Kinematic)),
        ),
        (
            "arm",
            Box::new(|r: &Robot| gravity::Terms::arm(r, stiffid_core::Coordinates::Axis).unwrap()),
        ),
        (
            "masses",
            Box::new(|r: &Robot| {
                let masses = *r.masses().unwrap();
                let nominal = Vector6::repeat(2e-6);
                gravity::Terms::masses(r, masses, stiffid_core::Coordinates::Axis, nominal).unwrap()
            }),
        ),
    ]
}

/// The design's own Jacobian (screws and regressors per posture) equals the error model's on
/// the rigid nominal chain, column-scaled, for every gravity model.
#[test]
fn design_jacobian_matches_the_error_model() {
    for (name, g) in gravity_models() {
        let (robot, d) = design_with(g);
        let model = d.model();
        let group = postures(&robot, 5, 9);
        let at: Vec<_> = (group.iter())
            .flat_map(|q| (0..3).map(move |k| (*q, k)))
            .collect();
        let full = model.jacobian(&rigid(model), &at).unwrap();
        let scales = model.column_scales(LENGTH, &postures(&robot, 60, 1));
        let fast = d.jacobian(&group).unwrap();
        assert_eq!(fast.ncols(), d.kept().len());
        for (c, &k) in d.kept().iter().enumerate() {
            for r in 0..full.nrows() {
                let (a, b) = (fast[(r, c)], full[(r, k)] * scales[k]);
                assert!(
                    (a - b).abs() <= 1e-12 * (1.0 + b.abs()),
                    "{name} {r} {k}: {a} {b}"
                );
            }
        }
    }
}

/// The exact gradient of every criterion's log against central differences, for every gravity
/// model (the regressors' derivatives) on a robot with a coupled axis map.
#[test]
fn log_gradients_match_central_differences() {
    for (name, g) in gravity_models() {
        let (robot, d) = design_with(g);
        let group = postures(&robot, 12, 10);
        for criterion in CalibrationCriterion::ALL {
            let (value, gradient) = d.value_and_log_gradient(criterion, &group);
            assert!(value.is_finite(), "{name} {criterion:?}");
            let c = d.evaluate(&group).unwrap();
            let loss = criterion.loss(&c);
            assert!(
                (value - loss).abs() <= 1e-8 * loss,
                "{value} against {loss}"
            );
            // The search's values come from the information matrix, accurate to about
            // cond(J_s)^2 eps relative: a step of 1e-5 rad keeps that rounding (divided by the
            // step) below the tolerance, and the central difference's truncation (h^2) too.
            let h = 1e-5;
            let mut worst: f64 = 0.0;
            let scale = gradient.iter().map(|g| g.amax()).fold(0.0, f64::max);
            for i in 0..group.len() {
                for a in 0..6 {
                    let mut up = group.clone();
                    let mut down = group.clone();
                    up[i][a] += h;
                    down[i][a] -= h;
                    let fd =
                        (d.value(criterion, &up).ln() - d.value(criterion, &down).ln()) / (2.0 * h);
                    worst = worst.max((fd - gradient[i][a]).abs());
                }
            }
            assert!(
                worst <= 1e-5 * scale,
                "{name} {criterion:?}: worst {worst} of {scale}"
            );
        }
    }
}

/// The FANUC on a 6 m track along x, its error motions of order 3 in the model; reference
/// postures dealt over six stations, test postures read at each.
fn track_design() -> (Robot, CalibrationDesign, Vec<ExternalValues>) {
    use stiffid_core::robot::external::{ExternalAxes, ExternalAxis};
    let axis = ExternalAxis::linear("track", Vector3::x_axis(), 0.0, 6.0);
    let robot = presets::get("fanuc-r2000ic-165f")
        .unwrap()
        .with_external(Some(ExternalAxes::new(vec![axis]).unwrap()));
    let stations = robot.external().unwrap().stations(6);
    let points = [
        Vector3::new(0.15, 0.0, 0.25),
        Vector3::new(-0.1, 0.12, 0.3),
        Vector3::new(0.0, -0.14, 0.2),
    ];
    let model = ErrorModel::new(
        &robot,
        &points,
        MeasuredIn::Tracker,
        Geometry::Full,
        gravity::Terms::none(&robot),
    )
    .unwrap()
    .with_external(&[3], 0)
    .unwrap();
    let reference: Vec<Placed> = (postures(&robot, 60, 1).iter().enumerate())
        .map(|(i, q)| (*q, stations[i % 6]))
        .collect();
    let test: Vec<Placed> = (postures(&robot, 20, 2).iter().enumerate())
        .map(|(i, q)| (*q, stations[i % 6]))
        .collect();
    let d = CalibrationDesign::new_placed(model, LENGTH, &reference, &test, 5e-5).unwrap();
    (robot, d, stations)
}

/// On a track, the design keeps the track's direction and error motions, its Jacobian equals
/// the error model's with the carrier's columns at every posture's station, and the exact
/// gradient of a group at one station after postures fixed at the others matches central
/// differences.
#[test]
fn a_track_campaign_is_designed_with_the_tracks_columns() {
    let (robot, d, stations) = track_design();
    let model = d.model();
    let carrier = (d.kept().iter())
        .filter(|&&c| matches!(model.parameters()[c].target, Target::External { .. }))
        .count();
    // The direction's 2 and the 18 error motions, less the straightnesses of order 1 (a turn
    // of the direction) and the positioning of order 1 (merged with the joint offsets' scale).
    assert!(carrier >= 15, "kept {carrier} of the track's 20");
    let group: Vec<Placed> = (postures(&robot, 8, 9).iter().enumerate())
        .map(|(i, q)| (*q, stations[i % 6]))
        .collect();
    let readings = readings(model, &group);
    let full = model.jacobian_of(&rigid(model), &readings).unwrap();
    let qs: Vec<Vector6<f64>> = postures(&robot, 60, 1);
    let scales = model.column_scales(LENGTH, &qs);
    let fast = d.jacobian_placed(&group).unwrap();
    for (c, &k) in d.kept().iter().enumerate() {
        for r in 0..full.nrows() {
            let (a, b) = (fast[(r, c)], full[(r, k)] * scales[k]);
            assert!((a - b).abs() <= 1e-12 * (1.0 + b.abs()), "{r} {k}: {a} {b}");
        }
    }
    let fixed: Vec<Placed> = (postures(&robot, 30, 11).iter().enumerate())
        .map(|(i, q)| (*q, stations[1 + i % 5]))
        .collect();
    let here = d.on_station(stations[0], &fixed).unwrap();
    let group = postures(&robot, 8, 12);
    let mut all = fixed.clone();
    all.extend(group.iter().map(|q| (*q, stations[0])));
    for criterion in [
        CalibrationCriterion::TestPose,
        CalibrationCriterion::DOptimality,
    ] {
        let (value, gradient) = here.value_and_log_gradient(criterion, &group);
        let whole = d.value_placed(criterion, &all);
        assert!((value - whole).abs() <= 1e-9 * whole, "{value} {whole}");
        let h = 1e-5;
        let mut worst: f64 = 0.0;
        let scale = gradient.iter().map(|g| g.amax()).fold(0.0, f64::max);
        for i in 0..group.len() {
            for a in 0..6 {
                let (mut up, mut down) = (group.clone(), group.clone());
                up[i][a] += h;
                down[i][a] -= h;
                let fd = (here.value(criterion, &up).ln() - here.value(criterion, &down).ln())
                    / (2.0 * h);
                worst = worst.max((fd - gradient[i][a]).abs());
            }
        }
        assert!(
            worst <= 1e-5 * scale,
            "{criterion:?}: worst {worst} of {scale}"
        );
    }
}

/// A step at one station of the track is scored on the arm's columns (`station`): its value and
/// gradient equal those of the whole Jacobian with every column, for each criterion read from
/// the information matrix, and a step without fixed postures is not reduced.
#[test]
fn a_step_at_a_station_reduced_to_the_arm_equals_the_whole_jacobian() {
    let (robot, d, stations) = track_design();
    assert!(d.on_station(stations[0], &[]).unwrap().reduced.is_none());
    let fixed: Vec<Placed> = (postures(&robot, 30, 11).iter().enumerate())
        .map(|(i, q)| (*q, stations[1 + i % 5]))
        .collect();
    let here = d.on_station(stations[2], &fixed).unwrap();
    let reduced = here
        .reduced
        .as_deref()
        .expect("a step on the track is reduced");
    assert!(reduced.kept().len() < here.kept().len());
    let whole = here.whole();
    let group = postures(&robot, 12, 13);
    for criterion in [
        CalibrationCriterion::TestPose,
        CalibrationCriterion::DOptimality,
        CalibrationCriterion::O1,
    ] {
        let (value, gradient) = here.value_and_log_gradient(criterion, &group);
        let (expected, exact) = whole.value_and_log_gradient(criterion, &group);
        assert!(value.is_finite() && (value - expected).abs() <= 1e-10 * expected);
        assert!((here.value(criterion, &group) - expected).abs() <= 1e-10 * expected);
        let scale = exact.iter().map(|g| g.amax()).fold(0.0, f64::max);
        for (g, e) in gradient.iter().zip(&exact) {
            assert!((g - e).amax() <= 1e-8 * scale, "{criterion:?}: {g} {e}");
        }
    }
}
