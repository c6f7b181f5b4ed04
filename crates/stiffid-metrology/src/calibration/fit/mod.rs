//! The calibration fit: Levenberg-Marquardt over the identifiable parameters, with standard
//! deviations.
//!
//! The parameters kept by [`crate::calibration::identifiability`] at the start (the merged stay
//! nominal) minimise `|r(x)|^2`, `r` the residuals of `ErrorModel::residuals`, by
//! Levenberg-Marquardt (Marquardt 1963) in the scaled parameters `x_s = x / s`
//! ([`ErrorModel::column_scales`]): each iteration factors `[J_s | r]` by Householder QR once
//! (`J_s` the scaled Jacobian) and bidiagonalises `R = W B Z^T` once, then solves
//! `[R; sqrt(lambda) I] dx_s = -[Q^T r; 0]` for each trial `lambda` from that bidiagonal form by
//! Eldén's rotations (never the normal equations), accepts the step when the cost falls (and
//! divides `lambda` by 10) or multiplies `lambda` by 10 and tries again. The frame's perturbation is folded into the frame
//! after every step ([`Estimate::recentre`]).
//!
//! Standard deviations: the covariance of the fitted parameters is `sigma^2 (J^T J)^-1` at the
//! solution, `sigma^2 = |r|^2 / (3n - p)` the noise variance per coordinate estimated from the
//! residuals (`n` readings, `p` parameters fitted). With priors ([`Priors`]: the nominal
//! tolerances), every joint error is fitted, each with the prior row `(x - x_0) sigma_t /
//! sigma_p` (`sigma_t` the tracker noise per coordinate, `sigma_p` the tolerance), a weakly
//! determined combination gets a value pulled towards nominal, and the covariance is
//! `sigma_t^2 (J_a^T J_a)^-1` of the augmented Jacobian: the posterior of a Gaussian prior and
//! noise (Tikhonov regularisation as Bayesian estimation).
//!
//! *Thin readings.* The bound on the gravity terms ([`GravityPrior`]) weighs its prior rows
//! against a noise per coordinate. The tracker's stated noise is right when the model holds the
//! robot's error; when it does not (an axis's encoder eccentricity, which only maps hold), the
//! residuals scatter by several times the tracker's noise, and a prior weighed against the
//! tracker's alone lets the gravity terms chase that misfit on a few dozen postures, then
//! extrapolate it to others. So a model with gravity terms and no maps is fitted again with the
//! prior weighed against the noise of its residuals, `sigma^2 = |r|^2 / (3n - p_e)` (`p_e` the
//! effective parameters, [`Fit::effective_parameters`]), while that exceeds the noise the prior was
//! weighed against by more than 5 % (a fixed point of the noise, at most 4 fits; each from the same
//! start): the prior's Gaussian with the noise the readings show, which leaves it as stated where
//! the model fits to the tracker's noise (every noise-free or well-modelled campaign: the fit is
//! unchanged there). [`Fit::gravity_noise`] gives the noise used; [`fit_at_stated_noise`] fits
//! without it.
//!
//! *The prior's strength chosen by the readings.* The stated bound is the weakest prior a fit
//! takes: a misfit no model term holds, seen on a few dozen postures, is one the gravity terms can
//! follow within the stated bound, and a model that no held-out judgement screens has nothing
//! else to hold it. [`fit_choosing_strength`] chooses the prior's strength by
//! cross-validation over the postures, as the maps choose their ridge: the postures dealt into
//! five groups, each group predicted by the fit of the others linearised at this fit, at the
//! prior's weight times `10^(k/2)` (`k = 0..STRENGTHS`, the deflection divided alike); the
//! strongest whose held-out squared error the best's does not lower by more than one standard
//! error of the paired per-posture differences and 2 % (a one-standard-error rule) is fitted
//! anew from the same start ([`Fit::gravity_deflection`]). Where the readings determine the
//! terms the stronger priors predict the held-out groups worse and the stated bound stays; where
//! they do not, the terms are held towards their nominal values (0 for a lumped term, the
//! setup's compliance for known masses) and the model predicts as the geometry alone does. Each
//! candidate is one least-squares solve by SVD of the training rows' triangular factor stacked
//! on the prior rows (never the normal equations). Every fit converges on its step and its cost
//! as above and says why it stopped ([`stop_warning`]).

use super::error_model::{ErrorModel, Estimate, Kind, MeasuredIn, Observation, Target};
use super::identifiability::{self, Identifiability};
use super::reflections::{bidiagonal_ridge, Bidiagonal};
use crate::register::Correspondence;
use nalgebra::{DMatrix, DVector};
use stiffid_core::common::stop::Stop;
use stiffid_core::common::warning::{Warning, WarningKind};
use stiffid_core::math::householder;
use stiffid_core::math::linalg::CappedSvd;
use stiffid_core::{Error, Result};

mod campaign;
mod leave_one_out;
mod noise;
mod strength;

pub(super) use leave_one_out::leave_one_out_linearised;
use noise::fit_with;
pub use noise::{fit_at_stated_noise, fit_choosing_strength};

/// Most Levenberg-Marquardt iterations.
pub const MAX_ITERATIONS: usize = 100;

/// Most readings a calibration fits.
const MAX_READINGS: usize = 100_000;

/// The scaled step length below which the fit has converged.
pub(crate) const STEP_TOLERANCE: f64 = 1e-13;

/// A warning ([`WarningKind::NotConverged`]) when the fit stopped at its limit of `iterations`
/// ([`Stop::IterationLimit`]) with the cost still falling: the calibration may still move.
///
/// The fit's stop reasons: [`Stop::Converged`], an accepted step shorter than 1e-13 (scaled, times
/// one plus the number of parameters fitted); [`Stop::Stalled`], an accepted step lowered the cost
/// by at most `1e-15` of it; [`Stop::DampingExhausted`], no damping of 30 tried (each ten times the
/// last) lowered the cost: both minima within rounding; [`Stop::IterationLimit`],
/// [`MAX_ITERATIONS`] taken with the cost still falling.
pub fn stop_warning(stop: Stop, iterations: usize) -> Option<Warning> {
    (stop == Stop::IterationLimit).then(|| {
        Warning::new(
            WarningKind::NotConverged,
            format!(
                "the calibration's Levenberg-Marquardt fit stopped at its limit of {iterations} iterations with the residuals still falling: its parameters may still move; read more varied postures or give tolerances"
            ),
        )
    })
}

/// Nominal tolerances of the joint errors, as Gaussian priors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Priors {
    /// Standard deviation of a length error, m.
    pub length: f64,
    /// Standard deviation of an angle error, rad.
    pub angle: f64,
    /// The tracker's noise per coordinate, m (the priors' weight against the readings).
    pub noise: f64,
}

/// A bound on what the gravity terms deflect, as Gaussian priors centred on their nominal
/// values: each term's prior standard deviation is the value that deflects its joint by
/// `deflection` at the largest torque it meets anywhere in the robot's joint limits
/// (`crate::calibration::gravity::Terms::peaks`): each term's row `(x - x_0) sigma_t y / d`
/// (`y` its peak regressor, `d` the deflection, `sigma_t` the noise), a Gaussian prior as
/// [`Priors`] are. Where the readings determine a term the prior does not move it (a deflection
/// of 1 mrad moves a point 1 m away by 1 mm, forty times a tracker's noise, at every reading);
/// where they do not (postures that sweep the weight's joints over a few degrees), it
/// holds the term near its nominal value instead of letting it grow along what the fitted
/// postures cannot see, and the fit's covariance says how far it stays open
/// (`crate::calibration::spread`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GravityPrior {
    /// The prior standard deviation of each term's deflection at its largest torque, rad.
    pub deflection: f64,
    /// The tracker's noise per coordinate, m (the prior's weight against the readings).
    pub noise: f64,
}

/// The deflection of [`GravityPrior`] that the calibration uses by default (`--gravity-bound-mrad`): 3 mrad (0.17 deg), a heavy
/// robot's sag at its joint 2 and more (about 2 mrad for a 165 kg payload-class arm at its
/// nominal stiffness under its own weight, far less for a light one).
pub(crate) const GRAVITY_DEFLECTION: f64 = 3e-3;

/// What the fit needs besides the model and the readings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// The characteristic length of the column scaling, m.
    pub length: f64,
    /// Priors on the joint errors, if any.
    pub priors: Option<Priors>,
    /// The ridge `mu` on the error maps' coefficients ([`ErrorModel::with_maps`]), dimensionless:
    /// each coefficient gets the row `sqrt(mu n) L (x - x_0)` (`n` the readings, `L` the
    /// characteristic length), a penalty of `mu` per reading on a coefficient that moves a point
    /// at `L` by 1 m. 0 without maps.
    pub ridge: f64,
    /// The bound on the gravity terms, if any.
    pub gravity: Option<GravityPrior>,
}

/// The fitted calibration.
#[derive(Debug, Clone)]
pub struct Fit {
    /// The estimate (re-centred: the frame's six values are zero, the frame holds them).
    pub estimate: Estimate,
    /// What the readings determine, at the start.
    pub identifiability: Identifiability,
    /// The fitted parameters' indices, ascending: the identified, or with priors every joint
    /// error too.
    pub fitted: Vec<usize>,
    /// The standard deviation of each parameter (SI); `None` for a parameter not fitted. The
    /// frame's are those of its base-frame perturbation.
    pub sd: Vec<Option<f64>>,
    /// The covariance of the fitted parameters (SI, `fitted` order).
    pub covariance: DMatrix<f64>,
    /// The precision its prior rows add to the inverse of [`Fit::covariance`] (SI, `fitted`
    /// order, the diagonal): `w^2 / sigma_t^2` of a parameter with the prior row weight `w`
    /// ([`Priors`], [`GravityPrior`], the maps' ridge), 0 for one without; what the readings
    /// determine is the rest of the inverse (`calibration::spread`).
    pub prior_precision: DVector<f64>,
    /// The residuals at the solution, 3 per reading, base frame, m.
    pub residuals: DVector<f64>,
    /// The effective number of fitted parameters: the trace of the hat matrix
    /// `J (J_a^T J_a)^-1 J^T` (`J` the readings' rows of the Jacobian, `J_a` with the priors' and
    /// the maps' ridge rows below them), between 0 and `fitted.len()`: as many as are fitted
    /// without priors nor ridge, fewer where they hold parameters (Hastie, Tibshirani and
    /// Friedman, *The Elements of Statistical Learning*, 2nd ed., eq. 3.50).
    pub effective_parameters: f64,
    /// RMS of the residuals' lengths, m.
    pub rms: f64,
    /// The noise per coordinate estimated from the residuals, m.
    pub sigma: f64,
    /// Iterations taken.
    pub iterations: usize,
    /// Why the iterations stopped ([`stop_warning`] lists the reasons).
    pub stop: Stop,
    /// The noise per coordinate the gravity prior was weighed against, m, where it was the
    /// residuals' rather than the one [`GravityPrior::noise`] states (module docs, *Thin
    /// readings*); `None` where it was the stated one.
    pub gravity_noise: Option<f64>,
    /// The deflection the gravity prior bounds its terms by, rad, where cross-validation over
    /// the postures chose it tighter than [`GravityPrior::deflection`] (module docs, *Thin
    /// readings*); `None` where it is the stated one.
    pub gravity_deflection: Option<f64>,
}

/// Fits `model` to `observations` from `start` (module docs).
///
/// # Errors
/// [`Error::InvalidField`] (`readings`) with no reading, more than 100 000, a
/// non-finite reading, or fewer coordinates than fitted parameters plus one;
/// [`Error::InvalidField`] (`options`) for a non-positive length or prior; those of
/// [`ErrorModel::jacobian`] and [`identifiability::analyse`]; [`Error::NotFinite`] when the fit
/// diverges.
pub fn fit(
    model: &ErrorModel,
    observations: &[Observation],
    start: &Estimate,
    options: &Options,
) -> Result<Fit> {
    fit_within(model, observations, start, options, MAX_ITERATIONS)
}

/// [`fit`] with at most `limit` iterations (a fit cut there stops with
/// [`Stop::IterationLimit`], which [`stop_warning`] reports).
///
/// # Errors
/// Those of [`fit`].
pub fn fit_within(
    model: &ErrorModel,
    observations: &[Observation],
    start: &Estimate,
    options: &Options,
    limit: usize,
) -> Result<Fit> {
    fit_with(model, observations, start, options, (limit, true, false))
}

/// One fit of [`fit_with`], the prior's weights as `options` give them.
fn fit_once(
    model: &ErrorModel,
    observations: &[Observation],
    start: &Estimate,
    options: &Options,
    limit: usize,
) -> Result<Fit> {
    check(observations, options)?;
    let scales = model.column_scales_of(options.length, observations);
    let priorities: Vec<u8> = model.parameters().iter().map(|p| p.priority).collect();
    // A carrier's error motions at zero (ErrorModel::structural): what the readings determine
    // is the cell's structure, not the micrometres of its error motions.
    let j = model.jacobian_of(&model.structural(&start.values), observations)?;
    // The maps' coefficients (the last parameters) are regularised, not analysed: every one is
    // fitted under the ridge.
    let analysed = model.map_start().unwrap_or(j.ncols());
    let identifiability = identifiability::analyse(
        &j.columns(0, analysed).into_owned(),
        &scales.rows(0, analysed).into_owned(),
        &priorities[..analysed],
    )?;
    let fitted: Vec<usize> = (0..model.parameters().len())
        .filter(|&c| {
            identifiability.identified.contains(&c)
                || (options.priors.is_some() && model.parameters()[c].kind == Kind::Joint)
                || c >= analysed
        })
        .collect();
    let coordinates = 3 * observations.len();
    let regularised = regularised(model, options);
    if !regularised && coordinates <= fitted.len() {
        return Err(Error::InvalidField {
            field: "readings".into(),
            message: format!(
                "{} readings give {coordinates} coordinates for {} identifiable parameters: read more postures",
                observations.len(),
                fitted.len()
            ),
        });
    }
    let problem = Problem {
        model,
        observations,
        fitted: &fitted,
        scales: DVector::from_iterator(fitted.len(), fitted.iter().map(|&c| scales[c])),
        priors: regularised.then(|| prior_weights(model, &fitted, options, observations.len())),
        noise: options.priors.map(|p| p.noise),
        nominal: model.nominal(),
    };
    let (estimate, iterations, stop) = problem.minimise(start.recentre(), limit)?;
    problem.finish(estimate, identifiability, iterations, stop)
}

/// The start of a fit: the nominal values, and the frame registered on the nominal positions
/// ([`crate::register::fit`], Umeyama) of the arm's measuring points for tracker
/// readings, the identity for base-frame ones; the reflectors fixed in the cell started
/// from their readings (the mean of `P(e)^-1 T t` over each one's).
///
/// # Errors
/// Those of [`ErrorModel::positions`] and [`crate::register::fit`] (fewer than 3 readings,
/// collinear points).
pub fn start(model: &ErrorModel, observations: &[Observation]) -> Result<Estimate> {
    let mut values = model.nominal();
    let frame = start_at(model, observations, &values)?;
    model.start_tables(&mut values, &frame, observations);
    Ok(Estimate { frame, values })
}

/// The measurement frame registered on the positions the model predicts at `values` (SI)
/// ([`crate::register::fit`]) for tracker readings, the identity for base-frame ones: the
/// tracker registered anew on held-out readings of another series.
///
/// # Errors
/// As [`start`].
pub fn start_at(
    model: &ErrorModel,
    observations: &[Observation],
    values: &DVector<f64>,
) -> Result<nalgebra::Isometry3<f64>> {
    Ok(match model.measured_in() {
        MeasuredIn::Base => nalgebra::Isometry3::identity(),
        MeasuredIn::Tracker => {
            // Registered on the arm's points: the table's reflectors are not known yet.
            let arm: Vec<Observation>;
            let observations = match observations.iter().any(|o| o.table) {
                false => observations,
                true => {
                    arm = observations.iter().filter(|o| !o.table).cloned().collect();
                    &arm
                }
            };
            let b = model.predict(values, observations)?;
            let pairs: Vec<Correspondence> = (observations.iter().zip(b))
                .map(|(o, base)| Correspondence {
                    base,
                    tracker: o.measured,
                })
                .collect();
            let registered = crate::register::fit(&pairs).map_err(|e| unregistered(e, &pairs));
            registered?.base_from_tracker
        }
    })
}

/// The registration's refusal (`points`) in the readings' words: the tracker is registered on
/// the tool's measuring points read (`pairs`), a reflector's `T` rows placed after it.
fn unregistered(e: Error, pairs: &[Correspondence]) -> Error {
    match e {
        Error::InvalidField { field, message } if field == "points" => Error::InvalidField {
            field: "readings".into(),
            message: format!(
                "the tracker is registered on the readings of the tool's measuring points (point 1, 2, ..; the reflectors' T rows are placed after it), {} here: {message}; read the measuring points at 3 or more postures whose points do not lie on one line",
                pairs.len()
            ),
        },
        other => other,
    }
}

fn check(observations: &[Observation], options: &Options) -> Result<()> {
    let invalid = |field: &str, message: String| Error::InvalidField {
        field: field.into(),
        message,
    };
    if observations.is_empty() || observations.len() > MAX_READINGS {
        return Err(invalid(
            "readings",
            format!(
                "expected 1 to {MAX_READINGS} unloaded readings, got {}",
                observations.len()
            ),
        ));
    }
    if let Some(o) = observations
        .iter()
        .find(|o| !(o.q.iter().chain(o.measured.iter()).all(|v| v.is_finite())))
    {
        return Err(invalid(
            "readings",
            format!("posture {}: expected finite numbers", o.posture + 1),
        ));
    }
    let positive = |v: f64| v.is_finite() && v > 0.0;
    if !positive(options.length) {
        return Err(invalid(
            "options",
            "expected a positive characteristic length".into(),
        ));
    }
    if !(options.ridge.is_finite() && options.ridge >= 0.0) {
        return Err(invalid("options", "expected a ridge of 0 or more".into()));
    }
    if let Some(g) = options.gravity
        && !(positive(g.deflection) && positive(g.noise))
    {
        return Err(invalid(
            "options",
            "expected a positive gravity deflection and noise".into(),
        ));
    }
    if let Some(p) = options.priors
        && !(positive(p.length) && positive(p.angle) && positive(p.noise))
    {
        return Err(invalid(
            "options",
            "expected positive prior tolerances and noise".into(),
        ));
    }
    Ok(())
}

/// Whether the fit of `model` with `options` has prior rows: priors on the joint errors, maps (their
/// ridge) or a bound on gravity terms.
fn regularised(model: &ErrorModel, options: &Options) -> bool {
    options.priors.is_some()
        || model.map_start().is_some()
        || (options.gravity.is_some() && !model.gravity().is_empty())
}

/// The weight of each fitted parameter's prior row (per SI unit): `sigma_t / sigma_p` of a joint
/// error with priors, `sqrt(mu n) L` of a map's coefficient ([`Options::ridge`], `n` readings),
/// `sigma_t y / d` of a gravity term with [`Options::gravity`] (`y` its peak regressor, `d` the
/// deflection), 0 for any other parameter.
fn prior_weights(
    model: &ErrorModel,
    fitted: &[usize],
    options: &Options,
    readings: usize,
) -> DVector<f64> {
    let ridge = (options.ridge * readings as f64).sqrt() * options.length;
    let peaks = model.gravity().peaks();
    let start = model.gravity_start();
    DVector::from_iterator(
        fitted.len(),
        fitted
            .iter()
            .map(|&c| match (model.parameters()[c].target, options.priors) {
                (Target::Joint { component, .. }, Some(p)) if component.is_angle() => {
                    p.noise / p.angle
                }
                (Target::Joint { .. }, Some(p)) => p.noise / p.length,
                (Target::Map { .. } | Target::Backlash { .. }, _) => ridge,
                (Target::Gravity(_), _) => options
                    .gravity
                    .map_or(0.0, |g| g.noise * peaks[c - start] / g.deflection),
                _ => 0.0,
            }),
    )
}

struct Problem<'a> {
    model: &'a ErrorModel,
    observations: &'a [Observation],
    fitted: &'a [usize],
    scales: DVector<f64>,
    priors: Option<DVector<f64>>,
    /// The priors' tracker noise, m.
    noise: Option<f64>,
    nominal: DVector<f64>,
}

impl Problem<'_> {
    /// The residuals with the prior rows.
    fn residuals(&self, e: &Estimate) -> Result<DVector<f64>> {
        let r = self.model.residuals(e, self.observations)?;
        Ok(match &self.priors {
            None => r,
            Some(w) => {
                let n = r.len();
                let mut all = r.resize_vertically(n + w.len(), 0.0);
                for (i, &c) in self.fitted.iter().enumerate() {
                    all[n + i] = w[i] * (e.values[c] - self.nominal[c]);
                }
                all
            }
        })
    }

    /// The scaled Jacobian of the fitted parameters with the prior rows.
    fn jacobian(&self, e: &Estimate) -> Result<DMatrix<f64>> {
        let full = self.model.jacobian_of(&e.values, self.observations)?;
        let mut j = full.select_columns(self.fitted.iter());
        for (c, s) in self.scales.iter().enumerate() {
            j.column_mut(c).scale_mut(*s);
        }
        Ok(match &self.priors {
            None => j,
            Some(w) => {
                let (m, n) = j.shape();
                let mut all = j.resize_vertically(m + n, 0.0);
                for i in 0..n {
                    all[(m + i, i)] = w[i] * self.scales[i];
                }
                all
            }
        })
    }

    /// The change of the values (SI) of the scaled step `dx_scaled`.
    fn change(&self, dx_scaled: &DVector<f64>) -> DVector<f64> {
        let mut change = DVector::zeros(self.nominal.len());
        for (i, &c) in self.fitted.iter().enumerate() {
            change[c] = dx_scaled[i] * self.scales[i];
        }
        change
    }

    fn step(&self, e: &Estimate, dx_scaled: &DVector<f64>) -> Estimate {
        Estimate {
            frame: e.frame,
            values: &e.values + self.change(dx_scaled),
        }
        .recentre()
    }

    fn minimise(&self, mut e: Estimate, limit: usize) -> Result<(Estimate, usize, Stop)> {
        let mut r = self.residuals(&e)?;
        let mut cost = r.norm_squared();
        let mut lambda = 1e-9;
        let n = self.fitted.len();
        for iteration in 1..=limit {
            let j = self.jacobian(&e)?;
            let (rt, qtr) = factor(&j, &r);
            let damped = Damped::new(rt, &qtr)?;
            let mut accepted = false;
            for _ in 0..30 {
                let dx = damped.step(lambda);
                let trial = self.step(&e, &dx);
                let r_trial = self.residuals(&trial)?;
                let c = r_trial.norm_squared();
                if !c.is_finite() {
                    return Err(Error::NotFinite {
                        what: "the calibration's residuals".into(),
                    });
                }
                if c <= cost {
                    let small = dx.norm() < STEP_TOLERANCE * (1.0 + n as f64);
                    let stalled = cost - c <= 1e-15 * cost;
                    e = trial;
                    r = r_trial;
                    cost = c;
                    lambda = (lambda / 10.0).max(1e-12);
                    accepted = true;
                    if small {
                        return Ok((e, iteration, Stop::Converged));
                    }
                    if stalled {
                        return Ok((e, iteration, Stop::Stalled));
                    }
                    break;
                }
                lambda *= 10.0;
            }
            if !accepted {
                return Ok((e, iteration, Stop::DampingExhausted));
            }
        }
        Ok((e, limit, Stop::IterationLimit))
    }

    fn finish(
        &self,
        estimate: Estimate,
        identifiability: Identifiability,
        iterations: usize,
        stop: Stop,
    ) -> Result<Fit> {
        let r_all = self.residuals(&estimate)?;
        let data = 3 * self.observations.len();
        let residuals = r_all.rows(0, data).into_owned();
        let ssr = residuals.norm_squared();
        let n = self.fitted.len();
        let sigma = match self.priors {
            None => (ssr / (data - n).max(1) as f64).sqrt(),
            Some(_) => (ssr / data.saturating_sub(identifiability.rank).max(1) as f64).sqrt(),
        };
        let j = self.jacobian(&estimate)?;
        let (rt, _) = factor(&j, &DVector::zeros(j.nrows()));
        let svd = rt.capped_svd(false, true).ok_or_else(not_converged)?;
        let v_t = svd.v_t.ok_or_else(not_converged)?;
        let s = &svd.singular_values;
        let effective_parameters = effective_parameters(&j.rows(0, data), &v_t, s);
        let inverse = DMatrix::from_diagonal(&s.map(|v| 1.0 / (v * v)));
        let unit = v_t.transpose() * inverse * &v_t;
        let noise2 = self.noise.map_or(sigma * sigma, |t| t * t);
        let covariance = DMatrix::from_fn(n, n, |a, b| {
            unit[(a, b)] * self.scales[a] * self.scales[b] * noise2
        });
        let prior_precision =
            (self.priors.as_ref()).map_or_else(|| DVector::zeros(n), |w| w.map(|v| v * v / noise2));
        let mut sd = vec![None; self.model.parameters().len()];
        for (i, &c) in self.fitted.iter().enumerate() {
            sd[c] = Some(covariance[(i, i)].sqrt());
        }
        let readings = self.observations.len();
        let rms = (ssr / readings as f64).sqrt();
        Ok(Fit {
            estimate,
            identifiability,
            fitted: self.fitted.to_vec(),
            sd,
            covariance,
            prior_precision,
            residuals,
            effective_parameters,
            rms,
            sigma,
            iterations,
            stop,
            gravity_noise: None,
            gravity_deflection: None,
        })
    }
}

/// The trace of the hat matrix from the SVD `U S V^T` of the augmented Jacobian `J_a`:
/// `sum_i |J v_i|^2 / s_i^2` over its nonzero singular values, `J` (`readings`) its rows of the
/// readings; each term is in [0, 1] since `s_i^2 = |J v_i|^2 + |P v_i|^2` with `P` the prior rows.
fn effective_parameters(
    readings: &nalgebra::DMatrixView<'_, f64>,
    v_t: &DMatrix<f64>,
    s: &DVector<f64>,
) -> f64 {
    let jv = readings * v_t.transpose();
    (jv.column_iter().zip(s.iter()))
        .filter(|&(_, &sv)| sv > 0.0)
        .map(|(c, &sv)| (c.norm_squared() / (sv * sv)).min(1.0))
        .sum()
}

/// `R` (`n x n`) and `Q^T r` (`n`) of the QR factorisation of `j` (`m x n`, `m >= n`), from one
/// Householder pass over `[j | r]` (`householder::qr`: blocks of columns, four at a time).
fn factor(j: &DMatrix<f64>, r: &DVector<f64>) -> (DMatrix<f64>, DVector<f64>) {
    let (m, n) = j.shape();
    let mut a = j.clone().insert_column(n, 0.0);
    a.column_mut(n).copy_from(r);
    let k = n.min(m);
    householder::qr(a.as_mut_slice(), m, k);
    let rt = DMatrix::from_fn(k, n, |i, c| if i <= c { a[(i, c)] } else { 0.0 });
    (rt, a.column(n).rows(0, k).into_owned())
}

/// The damped steps of one iteration from one bidiagonalisation of the triangular factor,
/// `R = W B Z^T` (`R` with zero rows below where it has fewer rows than columns): the least-squares
/// solution of `[R; sqrt(lambda) I] dx = -[Q^T r; 0]` is `dx = -Z z`, `z` the ridge solution of
/// `B z = W^T Q^T r` at `lambda`, by Givens rotations in `O(n)` per `lambda` (Eldén, "Algorithms
/// for the regularization of ill-conditioned least squares problems", BIT 17, 1977: the maps'
/// ridge steps' method, [`super::maps::linear`]): orthogonal transformations throughout, never
/// the normal equations, and no singular vectors formed.
struct Damped {
    bidiagonal: Bidiagonal,
    /// `W^T Q^T r` (the first `n` entries).
    projected: Vec<f64>,
}

impl Damped {
    fn new(rt: DMatrix<f64>, qtr: &DVector<f64>) -> Result<Self> {
        let n = rt.ncols();
        if n == 0 || rt.iter().chain(qtr.iter()).any(|v| !v.is_finite()) {
            return Err(Error::NotFinite {
                what: "the calibration's Jacobian or residuals".into(),
            });
        }
        let square = rt.resize_vertically(n, 0.0);
        let bidiagonal = Bidiagonal::new(square.as_slice().to_vec(), n);
        let mut projected: Vec<f64> = qtr.iter().copied().collect();
        projected.resize(n, 0.0);
        bidiagonal.left_tr(&mut projected);
        Ok(Damped {
            bidiagonal,
            projected,
        })
    }

    /// The step at damping `lambda`.
    fn step(&self, lambda: f64) -> DVector<f64> {
        let b = &self.bidiagonal;
        let mut z = bidiagonal_ridge(&b.diagonal, &b.upper, &self.projected, lambda);
        b.right(&mut z);
        -DVector::from_vec(z)
    }
}

fn not_converged() -> Error {
    Error::NotFinite {
        what: "the calibration's SVD did not converge".into(),
    }
}

#[cfg(test)]
mod damped_tests;
