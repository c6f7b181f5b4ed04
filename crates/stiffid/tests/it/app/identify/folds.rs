//! The cross-validation folds a stiffness file carries (`stiffid::app::identify::folds`).

use nalgebra::{DVector, Vector6};
use stiffid::app::identify::folds::*;
use stiffid::app::measurements::Origin;
use stiffid_core::common::warning::WarningKind;
use stiffid_core::model::prediction::Calibration;
use stiffid_identify::cross_validation::{CrossValidation, Fold};

fn fold(posture: usize, compliance: DVector<f64>) -> Fold {
    Fold {
        postures: vec![posture],
        measurements: vec![posture],
        stiffness: compliance.map(|h| 1.0 / h),
        compliance,
        residuals: DVector::zeros(3),
        delta_b: vec![0.0],
        rms_delta_b: 0.0,
        influential: vec![false; 6],
    }
}

/// Three leave-one-posture-out folds of the six drives (1e-6 rad/Nm each); the fold without
/// posture B fits k3 at -1e6 Nm/rad and k5 at 1e-3 Nm/rad (below the stiffness files' 1
/// Nm/rad): the calibration is dropped and the warning names that fold and those drives.
#[test]
fn a_non_physical_fold_drops_the_prediction_and_is_named() {
    let model = stiffid_core::setup::builtin("zhang2021-comau-nj165")
        .unwrap()
        .model()
        .clone();
    let physical = DVector::from_element(6, 1e-6);
    let mut bad = physical.clone();
    bad[2] = -1e-6;
    bad[4] = 1e3;
    let cv = |middle: DVector<f64>| CrossValidation {
        folds: vec![
            fold(0, physical.clone()),
            fold(1, middle),
            fold(2, physical.clone()),
        ],
        stiffness_mean: DVector::zeros(6),
        stiffness_std: DVector::zeros(6),
        stiffness_range: [DVector::zeros(6), DVector::zeros(6)],
        rms_delta_b: 0.0,
        rms_measured: 0.0,
        explained_std_error: 0.0,
    };
    let origin = Origin::new(
        ["A", "B", "C"].into_iter().collect(),
        vec![0, 1, 2],
        vec![0; 3],
        (vec![Vector6::zeros(); 3], vec![Default::default(); 3]),
        None,
        [String::new(), String::new()],
    );
    let calibration = Calibration {
        postures: 3,
        noise_floor: 0.0,
        deflection: None,
        folds: Vec::new(),
    };
    let (kept, warning) = carried(
        Some(calibration.clone()),
        Some(&cv(physical.clone())),
        &origin,
        &model,
    );
    assert_eq!((kept, warning), (Some(calibration.clone()), None));
    let (kept, warning) = carried(Some(calibration), Some(&cv(bad)), &origin, &model);
    assert!(kept.is_none());
    let w = warning.expect("the fold without B is named");
    assert_eq!(w.kind, WarningKind::Negative);
    assert!(
        w.message
            .starts_with("1 of 3 cross-validation folds fitted a stiffness that is negative or out of range (without B: k3, k5)"),
        "{}",
        w.message
    );
}
