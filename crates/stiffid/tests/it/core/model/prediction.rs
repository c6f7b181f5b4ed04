use nalgebra::{DMatrix, DVector};
use stiffid_core::model::prediction::*;

#[test]
fn the_ranks_follow_barber_et_al() {
    // N = 19 at 90%: ceil(0.9 * 20) = 18, floor(0.1 * 20) = 2.
    assert_eq!(ranks(19, 0.9), [Some(2), Some(18)]);
    // N = 9 at 90%: ceil(9.000000000000002) must be 9.
    assert_eq!(ranks(9, 0.9), [Some(1), Some(9)]);
    // Too few scores for 95%: both ends infinite.
    assert_eq!(ranks(10, 0.95), [None, None]);
}

#[test]
fn one_fold_of_constant_prediction_gives_the_empirical_quantile() {
    // One fold predicting 1 mm along x; scores 0.01..1.00 relative (N = 99 per coordinate
    // pooled: 33 measurements).
    let scores: Vec<f64> = (1..=99).map(|i| i as f64 / 100.0).collect();
    let cal = Calibration {
        postures: 1,
        noise_floor: 0.0,
        deflection: None,
        folds: vec![HeldOut {
            compliance: DVector::from_vec(vec![1e-3]),
            scores,
        }],
    };
    let rows = DMatrix::from_column_slice(3, 1, &[1.0, 0.0, 0.0]);
    let i = cal.interval(&rows, 0.9);
    // |mu| = 1e-3: upper = mu + R_(90) * 1e-3, R_(90) the 90th smallest = 0.90.
    assert!((i[0][1] - (1e-3 + 0.90e-3)).abs() < 1e-15, "{i:?}");
    assert!((i[0][0] - (1e-3 - 0.90e-3)).abs() < 1e-15, "{i:?}");
    assert!((i[1][1] - 0.90e-3).abs() < 1e-15, "{i:?}");
    assert!(inside(&i, &[1.5e-3, 0.0, -0.8e-3]).iter().all(|b| *b));
    assert_eq!(inside(&i, &[2.0e-3, 0.0, 0.0]), [false, true, true]);
    assert!(check_level("level", 0.95).is_ok());
    assert!(check_level("level", 1.0).is_err());
    assert!(check_level("level", f64::NAN).is_err());
}

/// The count of held-out values a finite bound needs at a level is the smallest at which the
/// conformal rank fits among them: 19 at 95%, 333 at 99.7%; one fewer gives an infinite end.
#[test]
fn a_finite_bound_needs_the_held_out_values_the_level_asks() {
    use stiffid::internal::model::prediction::{held_out_needed, ranks};
    for (level, needed) in [(0.95, 19), (0.997, 333), (0.9, 9), (0.5, 1)] {
        assert_eq!(held_out_needed(level), needed, "{level}");
        assert!(ranks(needed, level)[1].is_some(), "{level}");
        if needed > 1 {
            assert!(ranks(needed - 1, level)[1].is_none(), "{level}");
        }
    }
}
