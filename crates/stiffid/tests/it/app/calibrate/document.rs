//! The calibration's document (`stiffid::app::calibrate::document`): held-out intervals
//! outside the fitted ranges, and the held-out RMS within and beyond them.

use stiffid::app::calibrate::document::*;
use stiffid::app::calibrate::{Held, Outside};
use stiffid_metrology::calibration::validation::PointError as Error;
use stiffid_metrology::calibration::validation::Validation;

/// Two held-out readings with intervals, the second's posture 12.5 deg beyond joint 2's
/// fitted range and 3 deg beyond joint 5's: its interval is marked as not holding, with the
/// distance and joints; the first's holds.
#[test]
fn intervals_of_postures_outside_the_fitted_ranges_do_not_hold() {
    let error = |posture| Error {
        posture,
        point: 0,
        table: false,
        error: nalgebra::Vector3::new(1e-4, 0.0, 0.0),
    };
    let outside = Outside {
        distance: 12.5f64.to_radians(),
        farthest: 1,
        joints: vec![1, 4],
    };
    let h = Held {
        name: "held.csv".into(),
        calibrated: Validation::new(vec![error(0), error(1)]),
        nominal: Validation::new(vec![error(0), error(1)]),
        labels: vec!["A".into(), "B".into()],
        intervals: Some(vec![[[-1e-3, 1e-3]; 3]; 2]),
        coverage: None,
        from_fit: 0,
        outside: [(1, outside)].into_iter().collect(),
    };
    let doc = held(&h);
    assert_eq!(doc.errors[0].interval_holds, Some(true));
    assert_eq!(doc.errors[0].outside_range, None);
    assert_eq!(doc.errors[1].interval_holds, Some(false));
    let o = doc.errors[1].outside_range.as_ref().unwrap();
    assert!(
        (o.distance.to_degrees() - 12.5).abs() < 1e-12,
        "{}",
        o.distance
    );
    assert_eq!(o.joints, [2, 5]);
    let h = Held {
        intervals: None,
        ..h
    };
    let without = held(&h);
    assert_eq!(without.errors[1].interval_holds, None);
    assert!(without.errors[1].outside_range.is_some());
}

/// The held-out RMS split at the fitted ranges: two readings within (0.3 and 0.4 mm) and one
/// posture beyond (1.2 mm) give 0.3536 mm within and 1.2 mm beyond, and together the RMS of all
/// three; without a posture beyond, the RMS within is the whole RMS and the one beyond is null.
#[test]
fn the_held_out_rms_splits_at_the_fitted_ranges() {
    let error = |posture, x: f64| Error {
        posture,
        point: 0,
        table: false,
        error: nalgebra::Vector3::new(0.0, x, 0.0),
    };
    let errors = vec![error(0, 3e-4), error(1, -4e-4), error(2, 1.2e-3)];
    let outside = Outside {
        distance: 4f64.to_radians(),
        farthest: 2,
        joints: vec![0],
    };
    let h = Held {
        name: "held.csv".into(),
        calibrated: Validation::new(errors.clone()),
        nominal: Validation::new(errors),
        labels: vec!["A".into(), "B".into(), "C".into()],
        intervals: None,
        coverage: None,
        from_fit: 0,
        outside: [(2, outside)].into_iter().collect(),
    };
    let doc = held(&h);
    let within = doc.within_range_rms.unwrap();
    let beyond = doc.beyond_range_rms.unwrap();
    assert!((within - (12.5e-8f64).sqrt()).abs() < 1e-15, "{within}");
    assert!((beyond - 1.2e-3).abs() < 1e-15, "{beyond}");
    assert_eq!(doc.beyond_range_readings, 1);
    let all = ((2.0 * within * within + beyond * beyond) / 3.0).sqrt();
    assert!((all - doc.rms).abs() < 1e-15, "{all} {}", doc.rms);
    let inside = Held {
        outside: Default::default(),
        ..h
    };
    let doc = held(&inside);
    assert_eq!(doc.beyond_range_rms, None);
    assert_eq!(doc.beyond_range_readings, 0);
    assert!((doc.within_range_rms.unwrap() - doc.rms).abs() < 1e-15);
}
