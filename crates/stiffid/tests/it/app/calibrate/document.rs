//! The calibration's document (`stiffid::app::calibrate::document`): held-out intervals
//! outside the fitted ranges.

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
