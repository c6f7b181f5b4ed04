//! The optional sections of a stiffness file: the gravity terms of a calibration and the
//! held-out residuals that calibrate prediction intervals.

use super::{invalid, stiffness_unit};
use crate::common::limits::JointBox;
use crate::common::limits::{self};
use crate::model::prediction::{self, Calibration, HeldOut};
use crate::model::region::{PostureRange, Region, MAX_MARGIN_DEG};
use crate::model::ParameterKind;
use crate::Result;
use nalgebra::{DVector, Vector6};
use serde::{Deserialize, Serialize};

pub(crate) use crate::robot::weight_file::MAX_GRAVITY_TERMS;

/// The gravity terms a calibration fitted ([`crate::model::OwnWeight`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct GravitySection {
    /// The gravity model: `masses` (the robot's link masses, the terms the joint compliances),
    /// `lumped`, `lumped-links` or `arm` (compliance times mass moment).
    pub model: String,
    /// Each term, in the model's order; at most 144.
    pub terms: Vec<GravityTerm>,
}

/// One gravity term.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct GravityTerm {
    /// Its name: `gravity.c2` (a compliance) or `gravity.c2.link3.mx` (compliance times a mass
    /// moment).
    pub name: String,
    /// Its value, SI: rad/(N m) for a compliance, rad kg/(N m) for a mass, rad kg/N for a first
    /// moment; finite.
    pub value_si: f64,
}

impl GravitySection {
    /// Checks the count and that every value is finite.
    pub(super) fn check(&self) -> Result<()> {
        limits::check_count("gravity.terms", self.terms.len(), 1, MAX_GRAVITY_TERMS)?;
        match self.terms.iter().position(|t| !t.value_si.is_finite()) {
            Some(i) => Err(invalid(
                format!("gravity.terms[{}].value_si", i + 1),
                "expected a finite number".into(),
            )),
            None => Ok(()),
        }
    }

    pub(super) fn own_weight(&self) -> crate::model::OwnWeight {
        crate::model::OwnWeight {
            gravity: self.model.clone(),
            terms: (self.terms.iter())
                .map(|t| (t.name.clone(), t.value_si))
                .collect(),
            tool_mass: None,
            tool_centre: None,
        }
    }
}

/// The held-out residuals of an identification cross-validated over postures: what the
/// jackknife+ (or CV+) prediction intervals of `predict`, `compensate` and `validate` are built
/// from ([`crate::model::prediction`], Barber et al. 2021).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct PredictionSection {
    /// `jackknife+` (one fold per posture) or `cv+` (fewer folds): written for the reader,
    /// recomputed from `postures` and the folds when read.
    pub method: String,
    /// The postures the folds held out.
    pub postures: usize,
    /// `sigma_0`, the scale's noise floor: the standard deviation of one displacement coordinate
    /// from the setup's tracker noise, mm; finite, >= 0.
    pub noise_floor_mm: f64,
    /// The 95% quantile of the held-out scores (the `ceil(0.95 N)`-th smallest of the `N` scores
    /// pooled over the folds): 95% of the held-out errors are within this share of the
    /// predicted displacement plus `noise_floor_mm`; `null` without scores. Written for the
    /// reader, ignored when read.
    #[serde(default)]
    pub score_q95: Option<f64>,
    /// `score_q95` in %. Written for the reader, ignored when read.
    #[serde(default, alias = "score_q95_percent")]
    pub score_q95_pct: Option<f64>,
    /// `rho` of the deflection intervals ([`prediction::Deflection::model_error`], P4) in %: the
    /// model's held-out error relative to the predicted displacement, the tracker noise and the
    /// estimate's variance taken out; in [0, 10 000]. With `deflection_scores`; a file without
    /// them gives the measurement intervals (wider) for the deflection.
    #[serde(default, alias = "model_error_percent")]
    pub model_error_pct: Option<f64>,
    /// The studentised held-out scores of the deflection intervals
    /// ([`prediction::Deflection::scores`]), one per held-out coordinate; finite, >= 0.
    #[serde(default)]
    pub deflection_scores: Option<Vec<f64>>,
    /// One per fold, at most 100 000, with at most 3 000 000 scores in all.
    pub folds: Vec<FoldSection>,
}

/// One fold of [`PredictionSection`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct FoldSection {
    /// The postures the fold held out (labels).
    pub postures: Vec<String>,
    /// The compliance of every parameter fitted without them, SI (rad/Nm, m/N), in the order of
    /// `parameters`; finite.
    pub compliance_si: Vec<f64>,
    /// The score of each held-out coordinate: `|measured - predicted|` over `|predicted| +
    /// noise_floor_mm`, the prediction the fold's (three per measurement, x, y, z, at least one
    /// measurement per posture held out); finite, >= 0.
    pub scores: Vec<f64>,
}

impl PredictionSection {
    /// The section of `calibration`, its folds' postures named by `labels`.
    pub fn new(calibration: &Calibration, labels: Vec<Vec<String>>) -> Self {
        PredictionSection {
            method: calibration.method().into(),
            postures: calibration.postures,
            noise_floor_mm: calibration.noise_floor * 1e3,
            score_q95: calibration.score_quantile(0.95),
            score_q95_pct: calibration.score_quantile(0.95).map(|q| 100.0 * q),
            model_error_pct: (calibration.deflection.as_ref()).map(|d| 100.0 * d.model_error),
            deflection_scores: (calibration.deflection.as_ref()).map(|d| d.scores.clone()),
            folds: calibration
                .folds
                .iter()
                .zip(labels)
                .map(|(f, postures)| FoldSection {
                    postures,
                    compliance_si: f.compliance.iter().copied().collect(),
                    scores: f.scores.clone(),
                })
                .collect(),
        }
    }

    /// The calibration it holds.
    pub fn calibration(&self) -> Calibration {
        let folds: Vec<HeldOut> = (self.folds.iter())
            .map(|f| HeldOut {
                compliance: DVector::from_column_slice(&f.compliance_si),
                scores: f.scores.clone(),
            })
            .collect();
        Calibration {
            postures: self.postures,
            noise_floor: self.noise_floor_mm * 1e-3,
            deflection: self.deflection(&folds),
            folds,
        }
    }

    /// The deflection intervals' data, when the file has them.
    fn deflection(&self, folds: &[HeldOut]) -> Option<prediction::Deflection> {
        let (rho, scores) = (self.model_error_pct?, self.deflection_scores.as_ref()?);
        let mut scores = scores.clone();
        scores.sort_by(f64::total_cmp);
        Some(prediction::Deflection {
            model_error: rho / 100.0,
            scores,
            covariance: prediction::jackknife_covariance(folds, self.postures),
        })
    }

    /// Checks `model_error_pct` and `deflection_scores`: both or neither, within their
    /// ranges, at most [`prediction::MAX_SCORES`] scores.
    fn check_deflection(&self) -> Result<()> {
        let field = "prediction.model_error_pct";
        match (self.model_error_pct, &self.deflection_scores) {
            (None, None) => Ok(()),
            (Some(r), _) if !(0.0..=1e4).contains(&r) => Err(invalid(
                field.into(),
                format!(
                    "{}: expected a share in [0, 10000] %",
                    crate::common::words::number(r)
                ),
            )),
            (Some(_), Some(s)) if s.len() <= prediction::MAX_SCORES && !s.is_empty() => {
                match s.iter().position(|v| !(v.is_finite() && *v >= 0.0)) {
                    Some(i) => Err(invalid(
                        format!("prediction.deflection_scores[{}]", i + 1),
                        format!(
                            "{}: expected a finite number >= 0",
                            crate::common::words::number(s[i])
                        ),
                    )),
                    None => Ok(()),
                }
            }
            (Some(_), Some(s)) => Err(invalid(
                "prediction.deflection_scores".into(),
                format!(
                    "{} scores: expected 1 to {}",
                    s.len(),
                    prediction::MAX_SCORES
                ),
            )),
            _ => Err(invalid(
                field.into(),
                "expected model_error_pct and deflection_scores together, or neither".into(),
            )),
        }
    }

    /// Checks the counts and numbers against the parameters of `kinds`: each fold's compliance
    /// a stiffness within its kind's range (as the file's own stiffness), the noise floor within
    /// [`limits::READING_SD_MM`] (or 0).
    pub(super) fn check(&self, kinds: &[ParameterKind]) -> Result<()> {
        let n = kinds.len();
        limits::check_count(
            "prediction.folds",
            self.folds.len(),
            2,
            prediction::MAX_FOLDS,
        )?;
        let field = "prediction.noise_floor_mm";
        let floor = self.noise_floor_mm;
        if !(floor == 0.0 || limits::READING_SD_MM.contains(floor)) {
            return Err(invalid(
                field.into(),
                format!(
                    "{}: expected 0 or a tracker's noise within {}",
                    crate::common::words::number(floor),
                    limits::READING_SD_MM
                ),
            ));
        }
        self.check_deflection()?;
        if self.postures < self.folds.len() {
            return Err(invalid(
                "prediction.postures".into(),
                format!(
                    "{} postures for {} folds: expected at least one posture per fold",
                    self.postures,
                    self.folds.len()
                ),
            ));
        }
        let mut total = 0usize;
        for (k, f) in self.folds.iter().enumerate() {
            let field = format!("prediction.folds[{}]", k + 1);
            if f.compliance_si.len() != n || f.compliance_si.iter().any(|v| !v.is_finite()) {
                return Err(invalid(
                    format!("{field}.compliance_si"),
                    format!("expected {n} finite numbers, one per parameter"),
                ));
            }
            for (j, (h, kind)) in f.compliance_si.iter().zip(kinds).enumerate() {
                let (unit, range) = stiffness_unit(*kind);
                limits::check(
                    &format!("{field}.compliance_si[{}] as a stiffness", j + 1),
                    &[unit.per_si() / h],
                    range,
                )?;
            }
            if f.scores.is_empty() || f.scores.iter().any(|v| !(v.is_finite() && *v >= 0.0)) {
                return Err(invalid(
                    format!("{field}.scores"),
                    "expected at least one finite number >= 0".into(),
                ));
            }
            let (scores, held_out) = (f.scores.len(), f.postures.len());
            if scores % 3 != 0 || held_out == 0 || scores < 3 * held_out {
                return Err(invalid(
                    format!("{field}.scores"),
                    format!("{scores} scores for {held_out} postures held out: expected three per measurement (x, y, z), at least one measurement per posture"),
                ));
            }
            total = total.saturating_add(f.scores.len());
        }
        limits::check_count("prediction scores", total, 1, prediction::MAX_SCORES)
    }
}

/// The region of axis angles the stiffness was identified from ([`crate::model::region`]): a
/// posture with an axis outside `[lower_deg - margin_deg, upper_deg + margin_deg]` extrapolates,
/// and `predict`, `validate` and `compensate` flag it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct RegionSection {
    /// The postures the stiffness was identified from (at least 1).
    pub postures: usize,
    /// Per axis, the smallest angle of those postures, deg; within
    /// [`crate::common::limits::ANGLE_DEG`] (-10 000 to 10 000).
    pub lower_deg: [f64; 6],
    /// Per axis, the largest, deg; within [`crate::common::limits::ANGLE_DEG`], at least
    /// `lower_deg`.
    pub upper_deg: [f64; 6],
    /// The margin that widens every axis' range at both ends, deg, within [0, 360] (written as
    /// the default margin, 5).
    pub margin_deg: f64,
}

impl RegionSection {
    /// The section of `range`.
    pub fn new(range: &PostureRange) -> Self {
        RegionSection {
            postures: range.postures,
            lower_deg: range.range.lower.map(f64::to_degrees).into(),
            upper_deg: range.range.upper.map(f64::to_degrees).into(),
            margin_deg: range.margin.to_degrees(),
        }
    }

    /// The section of `region`; `None` when it records no postures.
    pub fn of(region: &Region) -> Option<Self> {
        match region {
            Region::Postures(r) => Some(Self::new(r)),
            _ => None,
        }
    }

    /// The range it holds, SI.
    pub(crate) fn range(&self) -> PostureRange {
        let rad = |v: &[f64; 6]| Vector6::from_column_slice(v).map(f64::to_radians);
        PostureRange {
            range: JointBox::new(rad(&self.lower_deg), rad(&self.upper_deg)),
            margin: self.margin_deg.to_radians(),
            postures: self.postures,
        }
    }

    /// Checks the count, that every angle is finite with each lower end at most its upper one,
    /// and the margin's range.
    pub(super) fn check(&self) -> Result<()> {
        if self.postures == 0 {
            return Err(invalid(
                "region.postures".into(),
                "0: expected at least 1 posture".into(),
            ));
        }
        limits::check("region.lower_deg", &self.lower_deg, &limits::ANGLE_DEG)?;
        limits::check("region.upper_deg", &self.upper_deg, &limits::ANGLE_DEG)?;
        for i in 0..6 {
            let (lo, hi) = (self.lower_deg[i], self.upper_deg[i]);
            if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
                return Err(invalid(
                    format!("region.lower_deg[{0}], region.upper_deg[{0}]", i + 1),
                    format!(
                        "{} and {}: expected finite angles, the lower at most the upper",
                        crate::common::words::number(lo),
                        crate::common::words::number(hi)
                    ),
                ));
            }
        }
        let m = self.margin_deg;
        if !(0.0..=MAX_MARGIN_DEG).contains(&m) {
            return Err(invalid(
                "region.margin_deg".into(),
                format!(
                    "{}: expected within [0, {MAX_MARGIN_DEG}] deg",
                    crate::common::words::number(m)
                ),
            ));
        }
        Ok(())
    }
}
