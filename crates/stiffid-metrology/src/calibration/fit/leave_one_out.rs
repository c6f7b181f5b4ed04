//! The folds of leave-one-posture-out, linearised at the full fit.

use super::{not_converged, prior_weights, regularised, Fit, GravityPrior, Options, Problem};
use crate::calibration::error_model::{ErrorModel, Estimate, Observation};
use nalgebra::{DMatrix, DVector};
use stiffid_core::math::linalg::CappedSvd;
use stiffid_core::{Error, Result};

/// Leave-one-posture-out linearised at the fit `fit` of `observations` (with the options it was
/// fitted with, the maps' ridge rows among them): per posture, in increasing order, the estimate
/// of the fit without it, the full fit moved by the change that dropping the posture makes in
/// the linearised problem. With `A = U S V^T` the scaled Jacobian of the fitted parameters and
/// its prior rows, `U_p` the rows of posture `p`, `r_p` its residuals and `H = U_p U_p^T` its
/// leverage, the change is `dx = V S^-1 U_p^T (I - H)^-1 r_p` (Sherman-Morrison-Woodbury on the
/// kept rows' normal equations, never formed): exact to second order in the change of the
/// parameters, as the maps' choice is, and taken from the full fit even where its iterations
/// stopped short in a weakly determined direction (the folds differ from the full fit by what
/// their posture changes, not by the rest of the full fit's own descent). Each fold comes with
/// its estimate (re-centred) and the change of the values from the full fit's (SI, the frame's
/// perturbation in the frame's six values), whose product with the Jacobian at the full fit is
/// the linearised change of any prediction.
///
/// # Errors
/// Those of [`ErrorModel::residuals`] and [`ErrorModel::jacobian_of`]; [`Error::NotFinite`] when
/// the SVD does not converge; [`Error::InvalidField`] (`readings`) when a posture alone
/// determines a parameter (its leverage 1: without it the fit is undetermined).
pub(in crate::calibration) fn leave_one_out_linearised(
    model: &ErrorModel,
    observations: &[Observation],
    fit: &Fit,
    options: &Options,
) -> Result<Vec<(usize, Estimate, DVector<f64>)>> {
    // The prior as the fit weighed it.
    let options = &Options {
        gravity: (options.gravity).map(|g| GravityPrior {
            noise: fit.gravity_noise.unwrap_or(g.noise),
            deflection: fit.gravity_deflection.unwrap_or(g.deflection),
        }),
        ..*options
    };
    let scales = model.column_scales_of(options.length, observations);
    let fitted = &fit.fitted;
    let regularised = regularised(model, options);
    let problem = Problem {
        model,
        observations,
        fitted,
        scales: DVector::from_iterator(fitted.len(), fitted.iter().map(|&c| scales[c])),
        priors: regularised.then(|| prior_weights(model, fitted, options, observations.len())),
        noise: options.priors.map(|p| p.noise),
        nominal: model.nominal(),
    };
    let a = problem.jacobian(&fit.estimate)?;
    let r = problem.residuals(&fit.estimate)?;
    let svd = a.capped_svd(true, true).ok_or_else(not_converged)?;
    let (u, v_t) = (
        svd.u.ok_or_else(not_converged)?,
        svd.v_t.ok_or_else(not_converged)?,
    );
    let s = &svd.singular_values;
    let largest = s.iter().copied().fold(0.0, f64::max);
    let kept: Vec<usize> = (0..s.len()).filter(|&i| s[i] > 1e-12 * largest).collect();
    let u = u.select_columns(kept.iter());
    // V S^-1, the kept singular values.
    let vs = DMatrix::from_fn(v_t.ncols(), kept.len(), |row, c| {
        v_t[(kept[c], row)] / s[kept[c]]
    });
    let mut postures: Vec<usize> = observations.iter().map(|o| o.posture).collect();
    postures.sort_unstable();
    postures.dedup();
    postures
        .iter()
        .map(|&p| {
            let rows: Vec<usize> = (observations.iter().enumerate())
                .filter(|(_, o)| o.posture == p)
                .flat_map(|(i, _)| 3 * i..3 * i + 3)
                .collect();
            let u_p = u.select_rows(rows.iter());
            let r_p = DVector::from_iterator(rows.len(), rows.iter().map(|&i| r[i]));
            let kept_rows = DMatrix::identity(rows.len(), rows.len()) - &u_p * u_p.transpose();
            let z = kept_rows
                .lu()
                .solve(&r_p)
                .filter(|z| z.iter().all(|v| v.is_finite()));
            let z = z.ok_or_else(|| Error::InvalidField {
                field: "readings".into(),
                message: format!(
                    "posture {} alone determines a parameter: without it the calibration is undetermined; read more postures",
                    p + 1
                ),
            })?;
            let dx = &vs * u_p.tr_mul(&z);
            Ok((
                p,
                problem.step(&fit.estimate, &dx),
                problem.change(&dx),
            ))
        })
        .collect()
}
