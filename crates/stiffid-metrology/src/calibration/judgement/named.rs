//! A gravity model the user names (`--gravity masses`, `lumped`, ...), judged as its rung of the
//! ladder: fitted exactly as the ladder fits it, beside the geometry alone, both scored by the
//! same groups of postures held out (the ladder's). Where its held-out error diverged (as
//! the ladder skips a rung) or where its fit deflects a joint beyond the physically possible
//! ([`beyond_sag`], which skips a rung of the ladder too), the named model is refused, saying why
//! and naming the terms the readings leave to their bound
//! ([`crate::calibration::fit::GravityPrior`]), rather than fitted and its predictions left to
//! reach metres. A named model is asked for: it is not turned down for losing to the geometry by
//! what the ladder's one-standard-error rule weighs, for its predictions' spread where the robot
//! is used (a spread against the geometry's misses the geometry's own bias there: on a heavy arm
//! fitted on a narrow sweep, `arm` held out over the joint ranges 1.4 mm off where the geometry
//! is 3.4 mm off, with twice its spread), nor for an ill-conditioned fit (the calibration warns).

use crate::calibration::error_model::Target;
use crate::calibration::fit::{Fit, Options};
use crate::calibration::gravity::{spanning, Gravity};
use crate::calibration::ErrorModel;
use stiffid_core::common::choice::Choice;
use stiffid_core::common::error::JobOption;
use stiffid_core::Error;

/// The largest joint deflection under the robot's own weight (and its tool's) a fit may put
/// anywhere within the joint limits, rad: 20 mrad (1.15 deg). An industrial arm sags by a few
/// milliradians at most under its own weight and rated payload (a 165 kg payload-class arm about
/// 2 mrad at joint 2); a fit that puts more on a joint follows a misfit along what its postures
/// cannot see, and its predictions away from them are no robot's.
pub(crate) const SAG_LIMIT: f64 = 0.02;

/// Why the gravity terms of `model` at `values` (SI, a fit's) are beyond the physically possible: the joint whose
/// deflection under the weight exceeds `SAG_LIMIT` somewhere within the joint limits (the
/// largest over the [`crate::calibration::gravity::spanning`] postures) and how far; `None`
/// within it.
pub fn beyond_sag(model: &ErrorModel, values: &nalgebra::DVector<f64>) -> Option<String> {
    let g = model.gravity();
    if g.is_empty() {
        return None;
    }
    let values = values.rows(model.gravity_start(), g.len());
    let mut largest = (0, 0.0f64, nalgebra::Vector6::zeros());
    for q in spanning(model.robot().limits()) {
        let dq = g.deflection(&values, &q);
        let j = dq.iamax();
        let v = dq[j].abs();
        if v > largest.1 {
            largest = (j, v, q);
        }
    }
    let (j, v, q) = largest;
    (v > SAG_LIMIT).then(|| {
        let deg: Vec<String> = q.iter().map(|a| format!("{:.1}", a.to_degrees())).collect();
        format!(
            "its fit deflects joint {} by {:.1} mrad under the robot's weight at axis angles ({}) deg within the joint limits, beyond the {:.0} mrad any arm sags",
            j + 1,
            v * 1e3,
            deg.join(", "),
            SAG_LIMIT * 1e3
        )
    })
}

/// A term's posterior standard deviation, as a share of its prior's, above which the readings
/// leave it to its bound (the readings' information on it a third of the prior's or less).
pub(crate) const LEFT_TO_BOUND: f64 = 0.87;

/// The refusal of the named gravity model `gravity`: its rungs' `reasons`, and the terms its
/// fit (`model`, `fit`, with `options`) leaves to their bound ([`left_to_bound`]).
pub(crate) fn refusal(
    gravity: Gravity,
    reasons: &str,
    fitted: Option<(&ErrorModel, &Fit)>,
    options: &Options,
) -> Error {
    let left = fitted.map_or_else(Vec::new, |(m, f)| left_to_bound(m, f, options));
    let terms = match left.is_empty() {
        true => String::new(),
        false => format!(
            " The readings leave {} to {} bound (each term's posterior standard deviation above {LEFT_TO_BOUND} of its prior's).",
            left.join(", "),
            if left.len() == 1 { "its" } else { "their" }
        ),
    };
    Error::InvalidOption {
        option: JobOption::Gravity,
        message: format!(
            "{}: the fitted postures do not determine it, and --gravity auto would skip it: {reasons}.{terms} Read postures that sweep the joints these terms turn over their range, give a tighter --gravity-bound-mrad, or use --gravity auto",
            gravity.name()
        ),
    }
}

/// The names of the gravity terms of `model` whose posterior standard deviation in `fit` exceeds
/// [`LEFT_TO_BOUND`] of their prior's: a term held by the prior alone has its prior's, in the
/// fit's covariance scaled by the residuals' noise over the noise the prior was weighed against.
pub(crate) fn left_to_bound(model: &ErrorModel, fit: &Fit, options: &Options) -> Vec<String> {
    let Some(prior) = options.gravity else {
        return Vec::new();
    };
    let weighed = fit.gravity_noise.unwrap_or(prior.noise);
    let deflection = fit.gravity_deflection.unwrap_or(prior.deflection);
    let covariance_noise = options.priors.map_or(fit.sigma, |p| p.noise);
    let peaks = model.gravity().peaks();
    let start = model.gravity_start();
    (fit.fitted.iter())
        .filter_map(|&c| {
            let Target::Gravity(term) = model.parameters()[c].target else {
                return None;
            };
            let sd = fit.sd[c]?;
            let prior_sd = deflection / peaks[c - start] * covariance_noise / weighed;
            (prior_sd > 0.0 && sd > LEFT_TO_BOUND * prior_sd).then(|| term.name())
        })
        .collect()
}
