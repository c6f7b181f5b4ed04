//! Whether to believe an identification: the model check against the tracker noise, and the
//! unit check against the nominal stiffness.
//!
//! ## Model adequacy
//! If the model is right and the measurement errors are independent Gaussian with the setup's
//! variance `sigma^2` on every displacement coordinate (twice that of one reading,
//! [`stiffid_core::setup::Noise::displacement_variance`]), `dof s^2 / sigma^2` follows a chi-square distribution
//! with `dof = m - 6` degrees of freedom (`s^2` the residual variance). A large value, with a small
//! upper-tail p-value, says the residuals are larger than the tracker noise can explain: the model
//! (rigid links, one spring per joint, exact kinematics and wrench) limits the fit, not the
//! tracker, and intervals computed from `sigma^2` would be too narrow. The intervals from `s^2`
//! (the usual ones of [`crate::Uncertainty`]) then hold as far as the model error
//! behaves like noise; both are given. `noise_ratio = s / sigma`. A small lower-tail p-value says
//! the opposite: residuals far below the tracker noise (noise-free or simulated data, or a noise
//! variance set too large).
//!
//! ## Unit check
//! A displacement column in m instead of mm, or a force in kN instead of N, scales every
//! identified stiffness by 1000. When most joints (`UNIT_JOINTS` of 6) are off the setup's
//! nominal stiffness by more than [`UNIT_FACTOR`] in the same direction, a unit is the likely cause.

use crate::{Identification, Uncertainty};
use nalgebra::Vector6;
use statrs::distribution::{ChiSquared, ContinuousCDF};

/// p-value below which the model error dominates the tracker noise.
pub const SIGNIFICANCE: f64 = 0.01;

/// The 0.975 quantile of the standard normal distribution: the 95% intervals of a known variance.
pub(crate) const Z975: f64 = 1.959_963_984_540_054;

/// A stiffness this many times off its nominal value (either way) counts as off.
pub const UNIT_FACTOR: f64 = 30.0;

/// How many of the six joints must be off, the same way, for the unit warning.
pub(crate) const UNIT_JOINTS: usize = 4;

/// The residuals against the setup's tracker noise (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Adequacy {
    /// `sigma^2`, the setup's noise variance of one displacement coordinate, m^2 (twice that of
    /// one reading, [`stiffid_core::setup::Noise::displacement_variance`]).
    pub noise_variance: f64,
    /// Degrees of freedom of the test (those of the residual variance).
    pub dof: usize,
    /// `s / sigma`: the residual standard deviation in units of the tracker noise (about 1 if the
    /// model is adequate).
    pub noise_ratio: f64,
    /// `dof s^2 / sigma^2`.
    pub chi2: f64,
    /// `P(X >= chi2)` for `X ~ chi2(dof)`: small when the residuals exceed the noise.
    pub p_value: f64,
    /// Standard errors and 95% intervals with the known variance `sigma^2` (normal quantile
    /// `Z975`): what the data would give if the model were exact.
    pub from_noise: Uncertainty,
}

/// The model check's verdict (module docs), for every fit of every model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    /// The residuals are what the tracker noise explains.
    Consistent,
    /// The residuals exceed the tracker noise (upper-tail p below [`SIGNIFICANCE`]): the model
    /// error dominates, the parameter intervals are conditional on the model, the prediction
    /// intervals (from held-out errors) are not.
    ModelError,
    /// The residuals are far below the tracker noise (lower-tail p below [`SIGNIFICANCE`]):
    /// noise-free or simulated data, or a tracker noise set too large.
    BelowNoise,
}

impl Verdict {
    /// The verdict of `rss / sigma^2 = chi2` with `dof` degrees of freedom; `None` without
    /// degrees of freedom or for a statistic that is not finite.
    pub(crate) fn of(chi2: f64, dof: usize) -> Option<Verdict> {
        let c = ChiSquared::new(dof as f64).ok()?;
        if !chi2.is_finite() {
            return None;
        }
        Some(match (c.sf(chi2), c.cdf(chi2)) {
            (upper, _) if upper < SIGNIFICANCE => Verdict::ModelError,
            (_, lower) if lower < SIGNIFICANCE => Verdict::BelowNoise,
            _ => Verdict::Consistent,
        })
    }

    /// The verdict in a few words, for a table.
    pub fn short(self) -> &'static str {
        match self {
            Verdict::Consistent => "noise",
            Verdict::ModelError => "model error",
            Verdict::BelowNoise => "below noise",
        }
    }
}

impl Adequacy {
    /// The verdict of this check.
    pub fn verdict(&self) -> Option<Verdict> {
        Verdict::of(self.chi2, self.dof)
    }

    /// Whether the model error dominates: `p_value <` [`SIGNIFICANCE`].
    pub fn model_error_dominates(&self) -> bool {
        self.p_value < SIGNIFICANCE
    }
}

impl Identification {
    /// The chi-square check of the residuals against a tracker noise variance `noise_variance`
    /// (m^2, > 0); `None` without degrees of freedom or for a non-positive or non-finite variance.
    pub fn adequacy(&self, noise_variance: f64) -> Option<Adequacy> {
        let u = self.uncertainty.as_ref()?;
        if !(noise_variance.is_finite() && noise_variance > 0.0) {
            return None;
        }
        let ratio2 = u.residual_variance / noise_variance;
        let chi2 = u.dof as f64 * ratio2;
        let p_value = ChiSquared::new(u.dof as f64).ok()?.sf(chi2);
        Some(Adequacy {
            noise_variance,
            dof: u.dof,
            noise_ratio: ratio2.sqrt(),
            chi2,
            p_value,
            from_noise: Uncertainty::with_quantile(
                &self.compliance,
                &self.unit_covariance,
                noise_variance,
                u.dof,
                Z975,
            ),
        })
    }

    /// The unit check against the nominal stiffness `nominal` (Nm/rad); `None` when fewer than
    /// `UNIT_JOINTS` joints are off by more than [`UNIT_FACTOR`] the same way.
    pub fn unit_check(&self, nominal: &Vector6<f64>) -> Option<UnitCheck> {
        let ratios = self.stiffness.component_div(nominal);
        let off = |stiffer: bool| -> Vec<usize> {
            (0..6)
                .filter(|&j| {
                    let r = ratios[j];
                    r.is_finite()
                        && r > 0.0
                        && match stiffer {
                            true => r > UNIT_FACTOR,
                            false => r < 1.0 / UNIT_FACTOR,
                        }
                })
                .collect()
        };
        [true, false].into_iter().find_map(|stiffer| {
            let joints = off(stiffer);
            (joints.len() >= UNIT_JOINTS).then(|| {
                let log_mean =
                    joints.iter().map(|&j| ratios[j].ln()).sum::<f64>() / joints.len() as f64;
                UnitCheck {
                    ratios,
                    joints,
                    stiffer,
                    typical_ratio: log_mean.exp(),
                }
            })
        })
    }
}

/// Most joints far off the nominal stiffness the same way: probably a unit (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct UnitCheck {
    /// Identified over nominal stiffness, per joint.
    pub ratios: Vector6<f64>,
    /// The joints off by more than [`UNIT_FACTOR`], 0-based.
    pub joints: Vec<usize>,
    /// Whether they came out stiffer (displacements too small or forces too large, e.g.
    /// displacements in m) or softer (e.g. forces in kN) than nominal.
    pub stiffer: bool,
    /// Geometric mean of their ratios (about 1000 or 1/1000 for a unit mix-up).
    pub typical_ratio: f64,
}
