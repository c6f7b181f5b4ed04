//! Held-out readings where the calibration extrapolates
//! (`stiffid::app::calibrate::extrapolation`).

use nalgebra::{Vector3, Vector6};
use stiffid::app::calibrate::extrapolation::*;
use stiffid_core::common::warning::{Warning, WarningKind};
use stiffid_metrology::calibration::error_model::Observation;
use stiffid_metrology::calibration::validation::{PointError, Validation};

fn observation(posture: usize, q_deg: [f64; 6]) -> Observation {
    Observation {
        posture,
        point: 0,
        q: Vector6::from(q_deg.map(f64::to_radians)),
        measured: Vector3::zeros(),
        wrench: Vector6::zeros(),
        e: Default::default(),
        table: false,
        direction: Vector6::zeros(),
    }
}

fn errors(lengths_mm: &[f64]) -> Validation {
    Validation::new(
        (lengths_mm.iter().enumerate())
            .map(|(posture, &l)| PointError {
                posture,
                point: 0,
                table: false,
                error: Vector3::new(0.0, l * 1e-3, 0.0),
            })
            .collect(),
    )
}

/// Two fitted postures span joint 4 over -100..70 deg and joint 6 over -90..0 deg; the second
/// held-out posture turns both beyond and the calibration misses it by 110 mm.
fn case(nominal_mm: f64, moved: bool) -> Option<Warning> {
    let fitted = [
        observation(0, [0.0, -90.0, 0.0, -100.0, 0.0, -90.0]),
        observation(1, [10.0, -80.0, 10.0, 70.0, 10.0, 0.0]),
    ];
    let held = [
        observation(0, [5.0, -85.0, 5.0, 0.0, 5.0, -45.0]),
        observation(1, [5.0, -85.0, 5.0, 193.0, 5.0, 90.0]),
    ];
    let labels = ["D1".to_string(), "D414".to_string()];
    warning(
        ("held.csv", moved),
        (&fitted, &held),
        &labels,
        (&errors(&[0.3, 110.0]), &errors(&[1.1, nominal_mm])),
        0.02,
    )
}

#[test]
fn names_the_posture_and_the_joints_outside_the_fitted_range() {
    let w = case(2.0, false).expect("the calibration misses a reading the nominal robot explains");
    assert_eq!(w.kind, WarningKind::Extrapolation);
    for part in [
        "1 held-out reading more than 20 mm off",
        "posture D414, point 1, 110.0 mm against 2.000 mm nominal",
        "joints 4, 6 outside the fitted postures' range: 193.0 deg against -100.0 to 70.0 deg, 90.0 deg against -90.0 to 0.0 deg",
    ] {
        assert!(w.message.contains(part), "{part}\n{}", w.message);
    }
    assert!(!w.message.contains("--reregister"), "{}", w.message);
    // Without --reregister, one reading of two missed is no moved tracker either.
    let w = case(2.0, true).unwrap();
    assert!(!w.message.contains("--reregister"), "{}", w.message);
}

/// The held-out postures of [`case`]: the second turns joint 4 123 deg and joint 6 90 deg
/// beyond the fitted range, the first lies within it; postures inside say nothing.
#[test]
fn held_out_postures_outside_the_fitted_ranges_are_named_with_their_distance() {
    let fitted = [
        observation(0, [0.0, -90.0, 0.0, -100.0, 0.0, -90.0]),
        observation(1, [10.0, -80.0, 10.0, 70.0, 10.0, 0.0]),
    ];
    let held = [
        observation(0, [5.0, -85.0, 5.0, 0.0, 5.0, -45.0]),
        observation(0, [5.0, -85.0, 5.0, 0.0, 5.0, -45.0]),
        observation(1, [5.0, -85.0, 5.0, 193.0, 5.0, 90.0]),
    ];
    let labels = ["D1".to_string(), "D414".to_string()];
    let w = outside_ranges("held.csv", (&fitted, &held), &labels).unwrap();
    assert_eq!(w.kind, WarningKind::Extrapolation);
    assert!(
        w.message.starts_with("held.csv: 1 of 2 held-out postures lie outside the fitted postures' range of joints 4, 6 by more than 1 deg (farthest: posture D414, 123.0 deg beyond on joint 4)"),
        "{}",
        w.message
    );
    assert!(outside_ranges("held.csv", (&fitted, &held[..2]), &labels).is_none());
}

/// Per posture: the second held-out posture of [`case`] lies 123 deg beyond on joint 4 (and
/// 90 deg on joint 6), the first within; joint 1's 0.5 deg beyond is inside the 1 deg margin.
#[test]
fn each_posture_outside_carries_its_distance_and_joints() {
    let fitted = [
        observation(0, [0.0, -90.0, 0.0, -100.0, 0.0, -90.0]),
        observation(1, [10.0, -80.0, 10.0, 70.0, 10.0, 0.0]),
    ];
    let held = [
        observation(0, [10.5, -85.0, 5.0, 0.0, 5.0, -45.0]),
        observation(1, [5.0, -85.0, 5.0, 193.0, 5.0, 90.0]),
        observation(1, [5.0, -85.0, 5.0, 193.0, 5.0, 90.0]),
    ];
    let (outside, count) = postures_outside(&fitted, &held);
    assert_eq!((count, outside.len()), (2, 1));
    let o = &outside[&1];
    assert_eq!((o.farthest, o.joints.clone()), (3, vec![3, 5]));
    assert!(
        (o.distance.to_degrees() - 123.0).abs() < 1e-12,
        "{}",
        o.distance
    );
}

#[test]
fn is_silent_when_the_nominal_robot_misses_the_reading_too() {
    // A reading of another robot: the gate refuses it, this warning has nothing to add.
    assert!(case(30.0, false).is_none());
}
