//! One campaign, one model of the robot: the paths a user takes to the program land on the
//! simulated true robot of [`crate::true_robot`] (geometric errors in every joint, the weight of
//! its links, drives 30 % more compliant than nominal, a tracker with 0.015 mm of noise), run by
//! a controller with its nominal kinematics. The calibrated robot carries the sag under its own
//! weight, so the compliance identified apart combines with it: calibrate from unloaded readings,
//! identify from load steps on the calibrated robot, compensate.

use crate::true_robot::{
    calibrated, dh_case, gcode_landing, landing, postures, q0, with_part, Row, Truth, WRENCHES,
};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use stiffid::app::identify::{self as identify, Request};
use stiffid::app::measurements::Data;
use stiffid::internal::metrology::calibration::gravity::Gravity;
use stiffid::internal::model::Compliance;
use stiffid::internal::setup::{Controller, Kinematics, Tracker};

/// The six drives identified from load-step readings `text` (tracker frame) on `setup`.
pub(crate) fn identified(setup: &stiffid::Setup, text: &str) -> Compliance {
    let report = identify::run(Request {
        progress: &(),
        setup_name: "setup".into(),
        setup,
        data: Data::File {
            name: "load-steps.csv".into(),
            reader: text.as_bytes(),
        },
        options: Default::default(),
    })
    .unwrap();
    let identify::Report::Drives(r) = report.report else {
        panic!("not the six drives")
    };
    let id = &r.identification;
    let covariance = id.uncertainty.as_ref().map(|u| u.compliance_covariance);
    Compliance::drives(id.compliance, covariance)
}

pub(crate) fn print(path: &str, what: &str, r: &Row) {
    eprintln!(
        "{path}: {what}: TCP error mean {:.4} mm, max {:.4} mm",
        r.mean * 1e3,
        r.max * 1e3
    );
}

/// Path (2): `calibrate --gravity masses` from unloaded readings, `identify` from load steps on
/// the calibrated robot (the tracker registered by the calibration), `compensate` with that
/// stiffness: the sag travels with the calibrated robot, the load steps (loaded minus unloaded)
/// carry none of it, and joint and Cartesian targets land within 3x the held-out calibration
/// error plus the predicted deflection's standard deviation, and within 0.05 mm, for a controller
/// with its nominal kinematics and for one running the calibrated model. The same stiffness on
/// the calibrated robot without its sag misses by far more.
#[test]
fn calibrate_then_identify_then_compensate_keeps_the_sag() {
    let case = dh_case();
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let truth = Truth::new(&case.setup, &mut rng);
    let fit = postures(30, &mut rng, case.angles);
    let data = truth.readings(&fit, &WRENCHES[..1], &mut rng);
    let held_postures = postures(12, &mut rng, case.angles);
    let held = truth.readings(&held_postures, &WRENCHES[..1], &mut rng);
    let (setup, _, frame, held_rms, _) = calibrated(&case, Gravity::Masses, &data, &held);
    assert!(setup.robot().own_weight().is_some());
    // The load steps, read on the calibrated robot, the tracker where the calibration put it.
    let setup = setup
        .to_builder()
        .with_tracker(tracker(frame))
        .build()
        .unwrap();
    let steps = postures(20, &mut rng, case.angles);
    let compliance = identified(&setup, &truth.readings(&steps, &WRENCHES, &mut rng));
    assert!(compliance.own_weight.is_none());
    let q0 = q0(&case);
    let (setup, _) = with_part(&setup, &q0);
    let nominal = case.setup.robot();
    let (joint, cartesian, _, std) = landing(&truth, nominal, (&setup, &compliance), &q0, &frame);
    let gcode = gcode_landing(&truth, nominal, (&setup, &compliance), &q0, &frame);
    let expected = held_rms + std;
    let path = "calibrate (masses, unloaded), identify (load steps), compensate";
    print(path, "joint targets", &joint);
    print(path, "Cartesian targets", &cartesian);
    print(path, "G-code", &gcode);
    eprintln!(
        "{path}: expected (held-out + deflection sd) {:.4} mm",
        expected * 1e3
    );
    for r in [joint, cartesian, gcode] {
        assert!(r.mean <= 3.0 * expected, "{r:?} vs {expected}");
        assert!(r.mean <= 0.05e-3, "{r:?}");
    }
    // A controller running the calibrated model: the program written in its kinematics (its
    // inverse kinematics of the Cartesian targets and of the G-code returns the compensated
    // angles) lands as well.
    let controller = Controller {
        kinematics: Kinematics::Calibrated,
        ..Default::default()
    };
    let own = setup
        .to_builder()
        .with_controller(controller)
        .build()
        .unwrap();
    let model = own.robot();
    let (joint_c, cartesian_c, _, _) = landing(&truth, model, (&own, &compliance), &q0, &frame);
    let gcode_c = gcode_landing(&truth, model, (&own, &compliance), &q0, &frame);
    print(path, "calibrated controller, joint targets", &joint_c);
    print(
        path,
        "calibrated controller, Cartesian targets",
        &cartesian_c,
    );
    print(path, "calibrated controller, G-code", &gcode_c);
    for r in [joint_c, cartesian_c, gcode_c] {
        assert!(r.mean <= 3.0 * expected, "{r:?} vs {expected}");
        assert!(r.mean <= 0.05e-3, "{r:?}");
    }
    // The calibrated robot without its sag: the program misses by the sag.
    let rigid = setup.robot().clone().with_own_weight(None);
    let rigid = setup.to_builder().with_robot(rigid).build().unwrap();
    let (dropped, _, _, _) = landing(&truth, nominal, (&rigid, &compliance), &q0, &frame);
    print(path, "joint targets, the sag dropped", &dropped);
    assert!(dropped.mean > 10.0 * joint.mean, "{dropped:?} vs {joint:?}");
}

/// Path (4): the robot calibrated (`--gravity masses`) and its drives identified from load steps
/// on one day; on another day its joint offsets have drifted by up to 0.03 deg, and
/// `calibrate --update` from a short check campaign (15 unloaded postures) refits the offsets,
/// the tracker and the tool on the calibrated robot file (its sag kept). The day-one stiffness
/// on the updated robot lands joint and Cartesian targets and G-code within 3x the update's
/// held-out error plus the predicted deflection's standard deviation, and within 0.05 mm; the
/// day-one robot, not updated, misses by the drift.
#[test]
fn an_update_on_another_day_keeps_the_older_stiffness() {
    let case = dh_case();
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let truth = Truth::new(&case.setup, &mut rng);
    let fit = postures(30, &mut rng, case.angles);
    let data = truth.readings(&fit, &WRENCHES[..1], &mut rng);
    let held = truth.readings(
        &postures(12, &mut rng, case.angles),
        &WRENCHES[..1],
        &mut rng,
    );
    let (setup, _, frame, _, _) = calibrated(&case, Gravity::Masses, &data, &held);
    let setup = setup
        .to_builder()
        .with_tracker(tracker(frame))
        .build()
        .unwrap();
    let steps = postures(20, &mut rng, case.angles);
    let compliance = identified(&setup, &truth.readings(&steps, &WRENCHES, &mut rng));
    // Another day: the offsets drifted; a check campaign updates the calibrated robot.
    let drift = [0.0, 0.03, -0.02, 0.025, -0.03, 0.0].map(f64::to_radians);
    let day2 = truth.drifted(&drift);
    let check = day2.readings(
        &postures(15, &mut rng, case.angles),
        &WRENCHES[..1],
        &mut rng,
    );
    let held = day2.readings(
        &postures(12, &mut rng, case.angles),
        &WRENCHES[..1],
        &mut rng,
    );
    let report = stiffid::app::calibrate::run(&crate::calibration_update::request(
        &setup,
        &check,
        Some(&held),
        true,
    ))
    .unwrap();
    let robot =
        stiffid::internal::robot::file::parse(report.robot_toml.as_ref().unwrap(), "updated.toml")
            .unwrap();
    assert_eq!(robot.own_weight(), setup.robot().own_weight());
    let frame2 = report.fit.estimate.frame;
    let held_rms = report.validation.as_ref().unwrap().calibrated.rms;
    eprintln!("update: held out {:.4} mm", held_rms * 1e3);
    let updated = (setup.to_builder())
        .with_robot(robot)
        .with_tcp(report.tcp.unwrap())
        .with_tracker(tracker(frame2))
        .build()
        .unwrap();
    let q0 = q0(&case);
    let (updated, _) = with_part(&updated, &q0);
    let nominal = case.setup.robot();
    let (joint, cartesian, _, std) = landing(&day2, nominal, (&updated, &compliance), &q0, &frame2);
    let gcode = gcode_landing(&day2, nominal, (&updated, &compliance), &q0, &frame2);
    let expected = held_rms + std;
    let path = "calibrate, identify; another day calibrate --update, compensate";
    print(path, "joint targets", &joint);
    print(path, "Cartesian targets", &cartesian);
    print(path, "G-code", &gcode);
    eprintln!(
        "{path}: expected (held-out + deflection sd) {:.4} mm",
        expected * 1e3
    );
    for r in [joint, cartesian, gcode] {
        assert!(r.mean <= 3.0 * expected, "{r:?} vs {expected}");
        assert!(r.mean <= 0.05e-3, "{r:?}");
    }
    // The day-one robot on the drifted one: the program misses by the drift.
    let (old, _) = with_part(&setup, &q0);
    let (stale, _, _, _) = landing(&day2, nominal, (&old, &compliance), &q0, &frame);
    print(path, "joint targets, not updated", &stale);
    assert!(stale.mean > 10.0 * joint.mean, "{stale:?} vs {joint:?}");
}

/// The tracker registered at `frame` (base from tracker).
pub(crate) fn tracker(frame: nalgebra::Isometry3<f64>) -> Tracker {
    Tracker {
        position: frame.translation.vector,
        max_incidence: None,
        measuring_normals: Vec::new(),
        base_from_tracker: Some(frame),
        registration_uncertainty: None,
    }
}
