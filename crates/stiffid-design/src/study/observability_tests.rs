//! The calibration criteria's study (`crate::study::observability`).

use crate::study::observability::*;

/// At a small size every criterion ranks the groups the right way round: the indices
/// against the held-out error, the predicted error with it.
#[test]
fn criteria_predict_held_out_error_at_small_size() {
    let s = calibration_study(16, 12, 5e-5, 1, 1).unwrap();
    let rho = |name: &str| s.rho[CRITERIA.iter().position(|c| *c == name).unwrap()].unwrap();
    assert!(rho("test-pose") > 0.0);
    for index in &CRITERIA[..5] {
        assert!(rho(index) < -0.3, "{index}: {}", rho(index));
    }
    assert!(calibration_study(2, 12, 5e-5, 1, 1).is_err());
    assert!(calibration_study(3, 12, 0.0, 1, 1).is_err());
}

/// With several noise draws a group (the held-out error's expectation, not one draw's
/// luck), the predicted error ranks the groups best of all criteria: the default of
/// `select --for calibration`.
#[test]
fn the_predicted_error_ranks_groups_best() {
    let s = calibration_study(64, 12, 5e-5, 8, 7).unwrap();
    let rho = |name: &str| s.rho[CRITERIA.iter().position(|c| *c == name).unwrap()].unwrap();
    assert!(rho("test-pose") > 0.6, "{}", rho("test-pose"));
    for index in &CRITERIA[..5] {
        assert!(
            rho("test-pose") > -rho(index) + 0.1,
            "{index}: {}",
            rho(index)
        );
    }
}
