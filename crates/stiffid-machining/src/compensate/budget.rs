//! The error budget of a compensated point: what the compensation leaves, named by source and
//! combined into one bound at the user's level (docs/model.md, "The error budget").
//!
//! - `left`: the compensation's residual (the Newton steps' `|p_nominal - p_loaded(q_c)|`; zero
//!   in the forward model, at most 0.1 um).
//! - `compensation`: the error of the predicted deflection the compensation removes. With a
//!   stiffness file's deflection calibration ([`stiffid_core::model::prediction::Deflection`]) the
//!   error `e = d_true - d` has the covariance `C = R S R^T + rho^2 |d|^2 I` (`R` the translation
//!   rows of the observation matrix at the point, `S` the folds' jackknife covariance, `rho` the
//!   model's held-out error); with a compliance covariance alone `C = Cov(d)` (its translation
//!   block). The part is the `level` quantile of `|e|` for `e ~ N(0, C)`
//!   (`length_quantile`); with the deflection calibration scaled by `kappa / z`, the held-out
//!   studentised scores' quantile over the normal's (`z = Phi^-1((1 + level) / 2)`), so that it
//!   carries the shape of the held-out errors. A stiffness file with held-out residuals but no
//!   deflection calibration gives the length of the per-coordinate half-widths of its
//!   measurement interval (conservative: it holds the tracker's noise).
//! - `calibration`: the calibrated robot's held-out position error, the `level` conformal
//!   quantile of the lengths its file carries ([`stiffid_core::robot::HeldOut`]); the same at every
//!   point (the errors do not say where they grow).
//! - `force`: the sensitivity to the force model: a wrench off by the fraction `f` (default
//!   [`DEFAULT_FORCE_TOLERANCE`], +-20%) moves the loaded tool by `f |d|` (the deflection is
//!   linear in the wrench), which the compensation does not remove.
//! - `model_form`: the spread of the deflection over the models the data support: with a
//!   stiffness file's `model_form` ([`stiffid_core::model::ModelForm`], the posture bootstrap of the
//!   model comparison), the `level` percentile ([`percentile`]) of `|t_s - t|` over every
//!   resampled parameter set `s` of every supported model, `t_s` the TCP translation the set
//!   predicts under the point's wrench and `t` the one the compensation removes: what the
//!   compensation leaves when the truth is one of the models the data support. A set of the
//!   compensation's own model scatters by its parameters' uncertainty too, which the
//!   `compensation` part also counts: the sum is conservative. Absent (`None`) without a
//!   `model_form`.
//!
//! The bound is `left + force + model_form + sqrt(compensation^2 + calibration^2)`: the two
//! random, independent parts at the same level combined in quadrature (JCGM 100:2008, the GUM,
//! 5.1.2 and 6.2), the bounded systematic ones added to it whole (Phillips, Eberhardt and Parry
//! 1997, "Guidelines for expressing the uncertainty of measurement results containing
//! uncorrected bias", J. Res. NIST 102(5), the `U + |delta|` rule). An absent part counts as 0
//! and is named absent.

use nalgebra::{DMatrix, Matrix3, Vector3, Vector6};
use statrs::distribution::{ChiSquared, ContinuousCDF, Normal};
use stiffid_core::model::prediction::Deflection;
use stiffid_core::model::{Compliance, ModelForm};
use stiffid_core::observation::deflection::PointDeflection;
use stiffid_core::robot::kinematics::Frames;
use stiffid_identify::compare::bootstrap::percentile;

/// The default relative error of the process force model: +-20%.
pub const DEFAULT_FORCE_TOLERANCE: f64 = 0.2;

/// One point's error budget, m (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Budget {
    /// The compensation's residual, m.
    pub left: f64,
    /// The predicted deflection's error at the level, m; `None` without a covariance or a
    /// prediction calibration.
    pub compensation: Option<f64>,
    /// The calibrated robot's held-out position error at the level, m; `None` when the robot
    /// carries none.
    pub calibration: Option<f64>,
    /// The force model's part, `f |d|`, m.
    pub force: f64,
    /// The spread over the models the data support, m; `None`: not carried by the stiffness.
    pub model_form: Option<f64>,
    /// The combined bound, m (module docs); infinite when a part is (too few held-out values
    /// for the level).
    pub bound: f64,
}

/// The names of a budget's parts, in the documents' order.
pub const PARTS: [&str; 5] = ["left", "compensation", "calibration", "force", "model_form"];

impl Budget {
    /// The budget of these parts (m), the bound combined (module docs).
    pub(crate) fn new(
        left: f64,
        compensation: Option<f64>,
        calibration: Option<f64>,
        force: f64,
        model_form: Option<f64>,
    ) -> Self {
        let random = compensation
            .unwrap_or(0.0)
            .hypot(calibration.unwrap_or(0.0));
        Budget {
            left,
            compensation,
            calibration,
            force,
            model_form,
            bound: left + force + model_form.unwrap_or(0.0) + random,
        }
    }

    /// Each part (m) in the order of [`PARTS`], `None` for an absent one.
    pub fn parts(&self) -> [Option<f64>; 5] {
        [
            Some(self.left),
            self.compensation,
            self.calibration,
            Some(self.force),
            self.model_form,
        ]
    }

    /// The part that contributes most to the bound: its name ([`PARTS`]) and value (m).
    pub fn dominant(&self) -> (&'static str, f64) {
        PARTS
            .iter()
            .zip(self.parts())
            .filter_map(|(n, v)| v.map(|v| (*n, v)))
            .fold(("left", f64::NEG_INFINITY), |a, b| match b.1 > a.1 {
                true => b,
                false => a,
            })
    }
}

/// A TCP's deflection under a wrench ([`PointDeflection`], which it dereferences to) and the
/// model-form part of its budget.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Deflected {
    /// The deflection under the compensation's model.
    pub point: PointDeflection,
    /// The model-form part at the level, m ([`model_form`]); `None` without a `model_form`.
    pub model_form: Option<f64>,
}

impl std::ops::Deref for Deflected {
    type Target = PointDeflection;
    fn deref(&self) -> &PointDeflection {
        &self.point
    }
}

/// The model-form part at `level` (module docs): the `level` percentile of `|t_s - t|` over the
/// sets of `form` at the posture `frames`, under `wrench` (base frame) at the tool point `tcp`
/// (flange frame, m), `t` (m, base frame) the translation the compensation removes; `None`
/// when `form` holds no set.
pub(crate) fn model_form(
    form: &ModelForm,
    frames: &Frames,
    tcp: &Vector3<f64>,
    wrench: &Vector6<f64>,
    t: &Vector3<f64>,
    level: f64,
) -> Option<f64> {
    let mut e: Vec<f64> = (form.translations(frames, tcp, wrench).iter())
        .map(|s| (s - t).norm())
        .collect();
    if e.is_empty() {
        return None;
    }
    e.sort_by(f64::total_cmp);
    Some(percentile(&e, level))
}

/// The `level` quantile of `|e|` for `e ~ N(0, c)` (`c` 3x3, symmetric positive semi-definite):
/// `|e|^2` is a weighted sum of chi-squares `sum l_i chi^2_1` (`l_i` the eigenvalues of `c`),
/// approximated by `a chi^2_nu` with its first two moments, `a = sum l^2 / sum l`,
/// `nu = (sum l)^2 / sum l^2` (Patnaik 1949, "The non-central chi-square and F-distributions and
/// their applications", Biometrika 36): exact for one non-zero eigenvalue and for equal ones.
/// 0 for a zero `c`.
pub(crate) fn length_quantile(c: &Matrix3<f64>, level: f64) -> f64 {
    let l = c.symmetric_eigenvalues().map(|v| v.max(0.0));
    let (s1, s2) = (l.sum(), l.map(|v| v * v).sum());
    if !(s1 > 0.0 && s2 > 0.0) {
        return 0.0;
    }
    let nu = s1 * s1 / s2;
    match ChiSquared::new(nu) {
        Ok(chi) => (chi.inverse_cdf(level) * s2 / s1).sqrt(),
        Err(_) => f64::INFINITY,
    }
}

/// The standard normal's quantile `Phi^-1(p)`.
fn normal_quantile(p: f64) -> f64 {
    Normal::standard().inverse_cdf(p)
}

/// The compensation's part at `level` (module docs) of the deflection `d` under the compliance
/// `compliance`; `None` without a covariance or a prediction calibration.
pub(crate) fn compensation(
    d: &PointDeflection,
    compliance: &Compliance,
    level: f64,
) -> Option<f64> {
    if let Some(p) = &compliance.prediction {
        return Some(match &p.deflection {
            Some(deflection) => calibrated(d, &compliance.h, deflection, level),
            None => {
                let i = d.interval(p, &compliance.h, level);
                let mu = d.displacement;
                (0..3)
                    .map(|c| (i[c][0] - mu[c]).abs().max((i[c][1] - mu[c]).abs()))
                    .map(|h| h * h)
                    .sum::<f64>()
                    .sqrt()
            }
        });
    }
    let covariance = compliance.covariance.as_ref()?;
    let c = d.covariance(covariance);
    Some(length_quantile(
        &c.fixed_view::<3, 3>(0, 0).into_owned(),
        level,
    ))
}

/// The part with a deflection calibration: the Gaussian length quantile of
/// `C = R S R^T + rho^2 |mu|^2 I`, scaled by `kappa / z`.
fn calibrated(
    d: &PointDeflection,
    h: &nalgebra::DVector<f64>,
    deflection: &Deflection,
    level: f64,
) -> f64 {
    let rows: DMatrix<f64> = d.translation_rows();
    let mu = &rows * h;
    let s = &rows * &deflection.covariance * rows.transpose();
    let model = (deflection.model_error * mu.norm()).powi(2);
    let c = Matrix3::from_fn(|r, k| s[(r, k)] + if r == k { model } else { 0.0 });
    let kappa = deflection.kappa(level);
    length_quantile(&c, level) * kappa / normal_quantile(0.5 + level / 2.0)
}
