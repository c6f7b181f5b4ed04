//! Prediction intervals that cover what the model misses: jackknife+ and CV+ over the postures
//! (Barber, Candes, Ramdas and Tibshirani, "Predictive inference with the jackknife+", Annals of
//! Statistics 49(1), 2021, Sections 2 and 4).
//!
//! The confidence intervals of the stiffness (`stiffid_identify::Uncertainty`) are conditional on the
//! model: a compliance the model lacks biases the stiffness and no covariance shows it. The
//! prediction error, unlike the stiffness, is measurable on postures the fit has not seen, so the
//! intervals a user acts on are built from it.
//!
//! ## The calibration (from a cross-validation over postures)
//! Fold `k` of a cross-validation (`stiffid_identify::cross_validation`;
//! `stiffid_identify::prediction::calibrate`) fits the compliance `h_(-k)`
//! without its postures and predicts each of their measurements: `mu_(-k) = Psi_i h_(-k)` (m,
//! three coordinates). Each held-out coordinate `c` gives the score
//!
//! ```text
//! R = |delta_m,c - mu_(-k),c| / s(mu_(-k)),    s(mu) = |mu| + sigma_0          (P1)
//! ```
//!
//! the error relative to the size of the predicted displacement, `sigma_0` the noise floor (the
//! standard deviation of one displacement coordinate from the setup's tracker noise), so that a
//! residual carries to another posture, point and load: a model error grows with the deflection,
//! the tracker noise does not. [`Calibration`] keeps, per fold, `h_(-k)` and the scores of its
//! held-out coordinates (`N` scores in all).
//!
//! ## The interval
//! For a new prediction (any posture, point and wrench: `Psi_x`, the three translation rows of
//! the observation matrix there), each fold predicts `mu_(-k)(x) = Psi_x h_(-k)` and each score
//! `R` of that fold gives the two values `mu_(-k),c(x) -+ R s(mu_(-k)(x))`. With `alpha = 1 -
//! level`, the interval of coordinate `c` is
//!
//! ```text
//! [ q-_alpha{ mu_(-k),c(x) - R s(mu_(-k)(x)) },  q+_alpha{ mu_(-k),c(x) + R s(mu_(-k)(x)) } ]   (P2)
//! ```
//!
//! `q+` the `ceil((1 - alpha)(N + 1))`-th smallest of the `N` upper values (`+inf` beyond `N`),
//! `q-` the `floor(alpha (N + 1))`-th smallest of the lower values (`-inf` below 1): Barber et
//! al.'s Eq. (6), the jackknife+ with leave-one-posture-out folds, CV+ with `K` folds.
//!
//! ## The guarantee
//! If the postures (each with its points and loads) are exchangeable, a new posture drawn like the
//! measured ones, the jackknife+ interval of a score's unit covers the new measurement with
//! probability at least `1 - 2 alpha` (Theorem 1) and, in practice and in our simulations, about
//! `1 - alpha`; CV+ with `K` folds of `n` postures at least `1 - 2 alpha - min(2 (1 - 1/K) /
//! (n/K + 1), (1 - K/n) / (K + 1))` (Theorem 4). This holds
//! whatever the model misses: it needs no correct model and no Gaussian noise. The scores pool the
//! coordinates of every point of a posture; the coverage is then that of a coordinate drawn at
//! random among the measured ones, which the simulations check (`tests/it/prediction.rs`). It does
//! not hold for postures unlike the measured ones (outside their range of angles or loads).

use crate::common::error::JobOption;
use crate::{Error, Result};
use nalgebra::{DMatrix, DVector, Vector3};

/// The most folds a calibration holds.
pub(crate) const MAX_FOLDS: usize = 100_000;
/// The most scores (held-out coordinates) a calibration holds.
pub(crate) const MAX_SCORES: usize = 3_000_000;
/// The level accepted: `[0.5, 0.999]`.
pub(crate) const LEVEL: crate::common::limits::Range =
    crate::common::limits::Range::new(0.5, 0.999, "");
/// The default level of the prediction intervals.
pub const DEFAULT_LEVEL: f64 = 0.95;

/// One fold of a calibration: the fit without its postures and the scores (P1) of their
/// held-out coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct HeldOut {
    /// `h_(-k)`: the compliance of every parameter fitted without the fold's postures, SI.
    pub compliance: DVector<f64>,
    /// The score (P1) of every held-out coordinate (three per measurement), non-negative.
    pub scores: Vec<f64>,
}

/// What prediction intervals are built from (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Calibration {
    /// The number of postures the folds held out.
    pub postures: usize,
    /// `sigma_0` of the scale (P1), m.
    pub noise_floor: f64,
    /// What the deflection intervals (P3) are built from; `None` for a calibration that did not
    /// keep it (its deflection intervals are then its measurement intervals, wider).
    pub deflection: Option<Deflection>,
    /// One per fold (one per posture for the jackknife+).
    pub folds: Vec<HeldOut>,
}

/// A prediction interval `[lower, upper]` of each translation coordinate x, y, z, m; an end is
/// infinite when there are too few scores for the level.
pub type Interval = [[f64; 2]; 3];

impl Calibration {
    /// `jackknife+` (one fold per posture) or `cv+`.
    pub fn method(&self) -> &'static str {
        match self.folds.len() == self.postures {
            true => "jackknife+",
            false => "cv+",
        }
    }

    /// The empirical `level` quantile of the scores (P1) pooled over the folds: the
    /// `ceil(level N)`-th smallest of the `N` scores, so that a share `level` of the held-out
    /// errors are within it times the predicted displacement plus the noise floor; `None`
    /// without scores.
    pub(crate) fn score_quantile(&self, level: f64) -> Option<f64> {
        let mut scores: Vec<f64> = self
            .folds
            .iter()
            .flat_map(|f| f.scores.iter().copied())
            .collect();
        scores.sort_by(f64::total_cmp);
        let n = scores.len();
        (n > 0).then(|| scores[((level * n as f64).ceil() as usize).clamp(1, n) - 1])
    }

    /// The number of parameters of the folds' compliance.
    pub(crate) fn parameters(&self) -> usize {
        self.folds.first().map_or(0, |f| f.compliance.len())
    }

    /// The interval (P2) at `level` of the translation `rows * h` (`rows`: 3 x n, the translation
    /// rows of the observation matrix at the point and wrench predicted, SI).
    ///
    /// # Panics
    /// If `rows` does not have one column per parameter.
    pub fn interval(&self, rows: &DMatrix<f64>, level: f64) -> Interval {
        // Each fold's prediction `mu_(-k)` and scale, without allocating per fold: a path's
        // every point asks for an interval.
        let folds: Vec<(Vector3<f64>, f64, &[f64])> = self
            .folds
            .iter()
            .map(|f| {
                let mu = Vector3::from_fn(|c, _| rows.row(c).tr_dot(&f.compliance));
                (mu, mu.norm() + self.noise_floor, f.scores.as_slice())
            })
            .collect();
        interval_of(&folds, level)
    }
}

impl Calibration {
    /// The interval (P3) at `level` of the true translation `rows * h`, what a compensation by
    /// the prediction leaves (`rows`: 3 x n as for [`Calibration::interval`]; `h` the full fit's
    /// compliance, SI): per coordinate `mu ± kappa sqrt(v + rho^2 |mu|^2)`, `v` the jackknife
    /// variance of the prediction ([`jackknife_covariance`]), `rho` and `kappa` from
    /// [`Calibration::deflection`] ([`Deflection::kappa`]). Without it, the measurement
    /// interval [`Calibration::interval`] (wider: it holds the noise).
    ///
    /// # Panics
    /// If `rows` does not have one column per parameter of `h` and of the folds.
    pub fn deflection_interval(
        &self,
        rows: &DMatrix<f64>,
        h: &DVector<f64>,
        level: f64,
    ) -> Interval {
        let Some(deflection) = &self.deflection else {
            return self.interval(rows, level);
        };
        let mu = Vector3::from_fn(|c, _| rows.row(c).tr_dot(h));
        let covariance = &deflection.covariance;
        let kappa = deflection.kappa(level);
        let model = (deflection.model_error * mu.norm()).powi(2);
        std::array::from_fn(|c| {
            let row = rows.row(c);
            let v = (row * covariance).dot(&row);
            let half = kappa * (v.max(0.0) + model).sqrt();
            [mu[c] - half, mu[c] + half]
        })
    }
}

/// What the deflection intervals (P3) are built from: the model's error and the studentised
/// held-out scores.
#[derive(Debug, Clone, PartialEq)]
pub struct Deflection {
    /// `rho`: the model's held-out error relative to the predicted displacement, the tracker
    /// noise and the estimate's own variance taken out (method of moments), >= 0.
    pub model_error: f64,
    /// The held-out scores `|e| / sqrt(v + rho^2 |mu|^2 + sigma_0^2)` of every held-out
    /// coordinate, sorted; finite, >= 0.
    pub scores: Vec<f64>,
    /// `S`, the jackknife covariance of the folds' compliance ([`jackknife_covariance`]), SI,
    /// p x p: kept so that a path's every point does not form it again.
    pub covariance: DMatrix<f64>,
}

impl Deflection {
    /// From the held-out `errors` (m, one per coordinate: measured minus the fold's prediction),
    /// the folds' `predicted` displacement lengths there (m), the jackknife `variances` of those
    /// predictions (m^2, from `covariance`, [`jackknife_covariance`]) and the noise of one
    /// coordinate `noise_sd` (m):
    ///
    /// ```text
    /// rho^2 = max(0, sum (e^2 - v - sigma_0^2)) / sum |mu|^2                             (P4)
    /// ```
    ///
    /// the share of the held-out squared error that neither the tracker noise nor the estimate
    /// explains, per squared predicted displacement, and the scores. `None` without a
    /// coordinate or a displacement.
    pub fn from_held_out(
        errors: &[f64],
        predicted: &[f64],
        variances: &[f64],
        noise_sd: f64,
        covariance: DMatrix<f64>,
    ) -> Option<Self> {
        let sigma2 = noise_sd * noise_sd;
        let excess: f64 = (errors.iter().zip(variances))
            .map(|(e, v)| e * e - v - sigma2)
            .sum();
        let scale: f64 = predicted.iter().map(|m| m * m).sum();
        let rho = (scale > 0.0).then(|| (excess.max(0.0) / scale).sqrt())?;
        let mut scores: Vec<f64> = (errors.iter().zip(predicted).zip(variances))
            .map(|((e, m), v)| e.abs() / (v + (rho * m).powi(2) + sigma2).sqrt())
            .filter(|r| r.is_finite())
            .collect();
        scores.sort_by(f64::total_cmp);
        (!scores.is_empty()).then_some(Deflection {
            model_error: rho,
            scores,
            covariance,
        })
    }

    /// `kappa` at `level`: the `ceil(level (N + 1))`-th smallest of the `N` scores (the split
    /// conformal quantile, Lei et al. 2018), infinite beyond `N`. With the noise in the scores'
    /// scale and not in the interval's, it carries the held-out errors' shape to the true
    /// deflection.
    pub fn kappa(&self, level: f64) -> f64 {
        let [_, hi] = ranks(self.scores.len(), level);
        hi.map_or(f64::INFINITY, |k| self.scores[k - 1])
    }
}

/// The delete-`d` jackknife covariance of the folds' compliance (one fold per `d = n / K` of
/// `n = postures` postures, `K` folds): `(n - d) / (d K) sum_k (h_k - mean)(h_k - mean)^T`
/// (Shao and Wu, "A general theory for jackknife variance estimation", Annals of Statistics
/// 17(3), 1989); `(n - 1) / n sum_k ...` when each fold holds out one posture (Efron and Stein
/// 1981). A prediction `psi h` has the variance `psi S psi^T`. Zero without folds.
pub fn jackknife_covariance(folds: &[HeldOut], postures: usize) -> DMatrix<f64> {
    let p = folds.first().map_or(0, |f| f.compliance.len());
    if folds.is_empty() {
        return DMatrix::zeros(p, p);
    }
    let k = folds.len() as f64;
    let mean = folds
        .iter()
        .fold(DVector::zeros(p), |a, f| a + &f.compliance)
        / k;
    let mut sum = DMatrix::zeros(p, p);
    for f in folds {
        let d = &f.compliance - &mean;
        sum.ger(1.0, &d, &d, 1.0);
    }
    let (n, d) = (postures as f64, postures as f64 / k);
    sum * ((n - d) / (d * k))
}

/// The interval (P2) at `level` from each fold's prediction `mu_(-k)` of the three
/// coordinates, the scale `s` its scores are relative to and its scores `R` (P1): the
/// jackknife+ (one fold per posture) or CV+ of any model whose folds predict a point; an end is
/// infinite when there are too few scores for the level.
pub fn interval_of(folds: &[(Vector3<f64>, f64, &[f64])], level: f64) -> Interval {
    let n = folds.iter().map(|f| f.2.len()).sum();
    let [k_lo, k_hi] = ranks(n, level);
    let mut values = Vec::with_capacity(n);
    let mut end = |c: usize, sign: f64, k: usize| {
        values.clear();
        for (mu, s, scores) in folds {
            values.extend(scores.iter().map(|r| mu[c] + sign * r * s));
        }
        smallest(&mut values, k)
    };
    std::array::from_fn(|c| {
        [
            k_lo.map_or(f64::NEG_INFINITY, |k| end(c, -1.0, k)),
            k_hi.map_or(f64::INFINITY, |k| end(c, 1.0, k)),
        ]
    })
}

/// The 1-based ranks of `q-` and `q+` (P2) among `n` values at `level`; `None` for an infinite end.
pub(crate) fn ranks(n: usize, level: f64) -> [Option<usize>; 2] {
    // A hair below the product, so that 0.9 * 10 = 9.000000000000002 gives 9, not 10.
    let slack = 1e-9;
    let hi = (level * (n + 1) as f64 - slack).ceil() as usize;
    let lo = ((1.0 - level) * (n + 1) as f64 + slack).floor() as usize;
    [(lo >= 1).then_some(lo), (hi <= n && hi >= 1).then_some(hi)]
}

/// The fewest held-out values that give a finite upper bound at `level` (split conformal and
/// jackknife+, `ranks`: `ceil(level (n + 1)) <= n`, so `n >= level / (1 - level)`): 19 at
/// 95%, 333 at 99.7%.
pub fn held_out_needed(level: f64) -> usize {
    (level / (1.0 - level) - 1e-9).ceil().max(1.0) as usize
}

/// The `k`-th smallest (1-based) of `values`, reordering them.
fn smallest(values: &mut [f64], k: usize) -> f64 {
    *values.select_nth_unstable_by(k - 1, f64::total_cmp).1
}

/// Checks a level of prediction intervals, named `field`.
///
/// # Errors
/// [`Error::InvalidField`] naming `field` unless `level` is in 0.5 to 0.999.
pub fn check_level(field: &str, level: f64) -> Result<()> {
    match LEVEL.contains(level) {
        true => Ok(()),
        false => Err(Error::InvalidField {
            field: field.into(),
            message: format!(
                "{}: expected a level in {LEVEL}, e.g. 0.95",
                crate::common::words::number(level)
            ),
        }),
    }
}

/// The level of a job's prediction intervals: `level` as given, else [`DEFAULT_LEVEL`].
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::Level`]) for a level outside 0.5 to 0.999, or for one
/// given where the compliance carries no prediction calibration (`calibrated` false): no
/// interval would use it.
pub fn requested_level(level: Option<f64>, calibrated: bool) -> Result<f64> {
    match level {
        None => Ok(DEFAULT_LEVEL),
        Some(_) if !calibrated => Err(Error::InvalidOption {
            option: JobOption::Level,
            message: "only with a stiffness file that holds prediction data (identify --cross-validate writes it): without it there is no prediction interval to give a level".into(),
        }),
        Some(l) => check_level("level", l)
            .map(|_| l)
            .map_err(|e| e.for_option(JobOption::Level)),
    }
}

/// Whether each coordinate of `value` (m) lies in its interval.
pub fn inside(interval: &Interval, value: &[f64; 3]) -> [bool; 3] {
    std::array::from_fn(|c| interval[c][0] <= value[c] && value[c] <= interval[c][1])
}
