//! The gravity prior's strength chosen by cross-validation over the postures (the module docs'
//! *Thin readings*).

use super::{factor, not_converged, prior_weights, Fit, Options, Problem};
use crate::calibration::acceptance::lowers;
use crate::calibration::error_model::{ErrorModel, Observation, Target};
use nalgebra::{DMatrix, DVector};
use stiffid_core::math::linalg::CappedSvd;
use stiffid_core::Result;

/// The candidate strengths: the gravity prior's weight times `10^(k/2)`, `k = 0..STRENGTHS`
/// (its deflection divided alike: from the stated bound to ten thousand times tighter, where
/// the terms stay at their nominal values).
pub(crate) const STRENGTHS: usize = 9;

/// The groups the postures are dealt into (posture `i`, in ascending order, in group `i mod
/// GROUPS`), as the ladder's.
const GROUPS: usize = 5;

/// The fewest distinct postures with which the strength is chosen (fewer: the stated bound).
const FEWEST_POSTURES: usize = 10;

/// The factor by which the gravity prior's weight is multiplied, chosen by cross-validation
/// over the postures linearised at `fit` (fitted to `observations` with `options`, the prior as
/// the fit weighed it): each group of postures predicted by the linearised fit of the others at
/// each of [`STRENGTHS`] strengths, the joint errors' priors kept as they are; the strongest
/// whose held-out squared error the best's does not lower by more than one standard error of
/// the paired per-posture differences and 2 % (a one-standard-error rule, by the calibration's
/// acceptance rule `lowers`). 1 with fewer than [`FEWEST_POSTURES`] distinct postures.
///
/// # Errors
/// Those of [`ErrorModel::residuals`] and [`ErrorModel::jacobian_of`]; [`stiffid_core::Error::NotFinite`]
/// when an SVD does not converge.
pub(super) fn chosen(
    model: &ErrorModel,
    observations: &[Observation],
    fit: &Fit,
    options: &Options,
) -> Result<f64> {
    let mut postures: Vec<usize> = observations.iter().map(|o| o.posture).collect();
    postures.sort_unstable();
    postures.dedup();
    if postures.len() < FEWEST_POSTURES {
        return Ok(1.0);
    }
    let scales = model.column_scales_of(options.length, observations);
    let fitted = &fit.fitted;
    let problem = Problem {
        model,
        observations,
        fitted,
        scales: DVector::from_iterator(fitted.len(), fitted.iter().map(|&c| scales[c])),
        priors: Some(prior_weights(model, fitted, options, observations.len())),
        noise: None,
        nominal: model.nominal(),
    };
    let a = problem.jacobian(&fit.estimate)?;
    let r = problem.residuals(&fit.estimate)?;
    let data = 3 * observations.len();
    let n = fitted.len();
    let gravity: Vec<bool> = (fitted.iter())
        .map(|&c| matches!(model.parameters()[c].target, Target::Gravity(_)))
        .collect();
    let group = |o: &Observation| postures.binary_search(&o.posture).unwrap_or(0) % GROUPS;
    // errors[k][i]: the held-out squared error of posture `postures[i]` at strength `k`.
    let mut errors = vec![vec![0.0; postures.len()]; STRENGTHS];
    for g in 0..GROUPS {
        let (train, held): (Vec<usize>, Vec<usize>) =
            (0..data).partition(|&row| group(&observations[row / 3]) != g);
        let (rt, qtr) = factor(
            &a.select_rows(train.iter()),
            &DVector::from_iterator(train.len(), train.iter().map(|&i| r[i])),
        );
        for (k, errors) in errors.iter_mut().enumerate() {
            let weight = 10f64.powf(k as f64 / 2.0);
            let rows = rt.nrows();
            let mut m = rt.clone().resize_vertically(rows + n, 0.0);
            let mut rhs = qtr.clone().resize_vertically(rows + n, 0.0);
            for i in 0..n {
                let w = if gravity[i] { weight } else { 1.0 };
                m[(rows + i, i)] = w * a[(data + i, i)];
                rhs[rows + i] = w * r[data + i];
            }
            let change = &a * solve(m, &rhs)?;
            for &row in &held {
                let e = r[row] + change[row];
                let p = postures.binary_search(&observations[row / 3].posture);
                errors[p.unwrap_or(0)] += e * e;
            }
        }
    }
    let total = |k: usize| errors[k].iter().sum::<f64>();
    let best = (0..STRENGTHS)
        .min_by(|&x, &y| total(x).total_cmp(&total(y)))
        .unwrap_or(0);
    let strongest = (0..STRENGTHS)
        .rev()
        .find(|&k| k == best || !lowers((&errors[k], total(k)), (&errors[best], total(best)), 1.0));
    Ok(10f64.powf(strongest.unwrap_or(0) as f64 / 2.0))
}

/// The least-squares `dx` of `m dx = -rhs` by SVD, the singular values below `1e-12` of the
/// largest dropped (never the normal equations).
fn solve(m: DMatrix<f64>, rhs: &DVector<f64>) -> Result<DVector<f64>> {
    let svd = m.capped_svd(true, true).ok_or_else(not_converged)?;
    let (u, v_t) = (
        svd.u.ok_or_else(not_converged)?,
        svd.v_t.ok_or_else(not_converged)?,
    );
    let s = &svd.singular_values;
    let largest = s.iter().copied().fold(0.0, f64::max);
    let projected = u.tr_mul(rhs);
    let weights = DVector::from_iterator(
        s.len(),
        (s.iter().zip(projected.iter())).map(|(&s, &g)| match s > 1e-12 * largest {
            true => -g / s,
            false => 0.0,
        }),
    );
    Ok(v_t.tr_mul(&weights))
}
