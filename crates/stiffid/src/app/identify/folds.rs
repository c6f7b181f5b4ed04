//! Folds of the cross-validation that a stiffness file cannot carry: a fold fitted without some
//! postures can go non-physical (a negative compliance) where the fit of every posture does not.
//! The full fit's stiffness file is still written, without what prediction intervals are built
//! from, and the warning names the folds.

use crate::app::measurements::Origin;
use crate::app::{Warning, WarningKind};
use stiffid_core::common::limits::{STIFFNESS_NM_PER_RAD, STIFFNESS_N_PER_MM};
use stiffid_core::model::prediction::Calibration;
use stiffid_core::model::{Model, ParameterKind};
use stiffid_identify::cross_validation::CrossValidation;

/// `calibration` when every fold of `cv` is physical (each parameter's compliance of `model` a
/// stiffness within its kind's range, as a stiffness file's reader checks it); otherwise `None`
/// and the warning ([`WarningKind::Negative`]) naming each such fold's held-out postures (labels
/// of `origin`) and parameters.
pub fn carried(
    calibration: Option<Calibration>,
    cv: Option<&CrossValidation>,
    origin: &Origin,
    model: &Model,
) -> (Option<Calibration>, Option<Warning>) {
    let Some(cv) = cv else {
        return (calibration, None);
    };
    let parameters = model.parameters();
    let outside: Vec<String> = (cv.folds.iter())
        .filter_map(|f| {
            let names: Vec<&str> = (parameters.iter().zip(f.compliance.iter()))
                .filter(|(p, h)| {
                    let (range, per_si) = match p.kind {
                        ParameterKind::Translation => (&STIFFNESS_N_PER_MM, 1e-3),
                        _ => (&STIFFNESS_NM_PER_RAD, 1.0),
                    };
                    !range.contains(per_si / **h)
                })
                .map(|(p, _)| p.name.as_str())
                .collect();
            (!names.is_empty()).then(|| {
                format!(
                    "without {}: {}",
                    origin.labels_of(&f.postures).join(", "),
                    names.join(", ")
                )
            })
        })
        .collect();
    if outside.is_empty() {
        return (calibration, None);
    }
    let warning = Warning::new(
        WarningKind::Negative,
        format!(
            "{} of {} cross-validation folds fitted a stiffness that is negative or out of range ({}): the fit of every posture is kept and its stiffness file written without the folds' prediction section, so it gives no prediction intervals; the folds stay in the cross-validation",
            outside.len(),
            cv.folds.len(),
            outside.join("; ")
        ),
    );
    (None, Some(warning))
}
