//! The compliance a calibration fits, as `identify` writes it: every parameter of the setup's
//! model with its covariance; and the own weight's fitted gravity terms, as the calibrated robot
//! file carries them.

use nalgebra::{DMatrix, DVector};
use stiffid_core::Setup;
use stiffid_metrology::calibration::error_model::Target;
use stiffid_metrology::calibration::fit::Fit;
use stiffid_metrology::calibration::gravity::Term;
use stiffid_metrology::calibration::ErrorModel;

/// The compliance of every parameter of the setup's model (SI: rad/(N m), m/N) and its
/// covariance, from a calibration that fits compliances: what `identify` writes as a stiffness
/// file.
#[derive(Debug, Clone, PartialEq)]
pub struct FittedCompliance {
    /// The setup's model's parameters (drives first).
    pub parameters: Vec<stiffid_core::model::Parameter>,
    /// One per parameter.
    pub h: DVector<f64>,
    /// `Cov(h)`, SI: the fitted compliances' block of the calibration's covariance, zero for a
    /// parameter not fitted.
    pub covariance: DMatrix<f64>,
    /// Whether the calibration fitted each (the others keep the setup's nominal stiffness).
    pub fitted: Vec<bool>,
}

/// The compliance of a calibration that fits compliances: with known masses
/// ([`stiffid_metrology::calibration::gravity::Gravity::Masses`]) the drives' under gravity, with loaded readings
/// ([`ErrorModel::with_loads`]) every parameter of the setup's model. Each parameter the
/// readings determine at its fitted value, every other (a vertical joint 1, the virtual springs
/// without loaded readings, a merged compliance) at the setup's nominal stiffness with zero
/// variance.
///
/// # Errors
/// Why there is none, in words: the setup gives no nominal stiffness, or a fitted compliance is
/// not positive (no spring).
pub(crate) fn fitted_compliance(
    setup: &Setup,
    model: &ErrorModel,
    fit: &Fit,
) -> std::result::Result<FittedCompliance, String> {
    let Some(mut h) = setup.model_nominal_compliance() else {
        return Err("the setup gives no nominal stiffness (nominal_stiffness_nm_per_rad) for the parameters the calibration does not fit".into());
    };
    let n = h.len();
    let parameters = setup.model().parameters();
    // (index in the fitted parameters, index in the setup's model) of each fitted compliance.
    let of = |c: usize| match (model.parameters()[c].target, model.compliance_columns()) {
        (_, Some(columns)) => columns.iter().position(|&k| k == c),
        (Target::Gravity(Term::Compliance { joint }), None) => Some(joint),
        _ => None,
    };
    let fitted_here: Vec<(usize, usize)> = (fit.fitted.iter().enumerate())
        .filter_map(|(i, &c)| of(c).map(|m| (i, m)))
        .collect();
    let (mut covariance, mut fitted) = (DMatrix::zeros(n, n), vec![false; n]);
    for &(i, m) in &fitted_here {
        let value = fit.estimate.values[fit.fitted[i]];
        let linear = parameters[m].unit.is_stiffness();
        if linear && !(value.is_finite() && value > 0.0) {
            return Err(format!(
                "{}'s compliance is fitted at {value:.4e} (SI), not positive: no spring",
                parameters[m].name
            ));
        }
        h[m] = value;
        fitted[m] = true;
        for &(k, other) in &fitted_here {
            covariance[(m, other)] = fit.covariance[(i, k)];
        }
    }
    Ok(FittedCompliance {
        parameters,
        h,
        covariance,
        fitted,
    })
}

/// The gravity terms of `model` at their values in `fit` (fitted or held), the tool of mass
/// `tool` in them (its mass, kg, and centre of mass, m, flange frame); `None` without gravity terms. The calibrated robot file carries them
/// (`[gravity]`, [`stiffid_core::robot::weight_file`]).
pub(super) fn own_weight(
    model: &ErrorModel,
    fit: &Fit,
    tool: (Option<f64>, Option<nalgebra::Vector3<f64>>),
) -> Option<stiffid_core::model::OwnWeight> {
    let g = model.gravity();
    let values = fit.estimate.values.rows(model.gravity_start(), g.len());
    (!g.is_empty()).then(|| stiffid_core::model::OwnWeight {
        gravity: stiffid_core::common::choice::Choice::name(g.kind()).into(),
        terms: (g.terms().iter().map(|t| t.name()))
            .zip(values.iter().copied())
            .collect(),
        tool_mass: tool.0,
        tool_centre: tool.0.and(tool.1),
    })
}
