use nalgebra::{DMatrix, DVector};
use stiffid_core::model::prediction::*;

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
