//! The held-out readings' part of the calibration document ([`super::document::Document`]'s
//! `validation` and `cross_validation`): their errors and prediction intervals.

use super::Held;
use crate::app::document::units;
use nalgebra::Vector3;
use serde::Serialize;
use stiffid_core::io::readings::point_name;
use stiffid_core::model::prediction::Interval;
use stiffid_metrology::calibration::validation::Validation;

/// Held-out errors.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct ValidationDocument<'a> {
    /// The readings (`cross-validation` for leave-one-posture-out).
    pub data: &'a str,
    /// RMS of the 3D position error of every held-out reading: m, written in mm.
    #[serde(rename = "rms_mm", serialize_with = "units::mm")]
    pub rms: f64,
    /// The largest: m, written in mm.
    #[serde(rename = "max_mm", serialize_with = "units::mm")]
    pub max: f64,
    /// RMS of the 3D position error of the held-out readings whose posture lies within the
    /// fitted postures' axis ranges (`outside_range` null): m, written in mm; `null` without such
    /// readings.
    #[serde(rename = "within_range_rms_mm", serialize_with = "units::mm_option")]
    pub within_range_rms: Option<f64>,
    /// The same of the readings whose posture lies beyond them by more than 1 deg
    /// (`outside_range` set), where the calibration extrapolates: m, written in mm; `null`
    /// without such readings.
    #[serde(rename = "beyond_range_rms_mm", serialize_with = "units::mm_option")]
    pub beyond_range_rms: Option<f64>,
    /// The held-out readings whose posture lies beyond the fitted postures' axis ranges by more
    /// than 1 deg (`outside_range` set).
    pub beyond_range_readings: usize,
    /// The nominal robot's RMS on the same readings: m, written in mm; the tracker registered on
    /// them for readings in the tracker's frame (on the fitted readings, with a warning
    /// `left-out`, where they are fewer than 3 positions not on one line); as it is for readings
    /// in the base frame (`measured_in` `base`: nothing registered).
    #[serde(rename = "nominal_rms_mm", serialize_with = "units::mm")]
    pub nominal_rms: f64,
    /// The prediction intervals of the held-out readings' errors and how well they covered
    /// them (`--validate`, with at most 5000 fitted postures); `null` for the cross-validation.
    pub intervals: Option<IntervalsDocument>,
    /// The share of the held-out coordinates inside their prediction intervals (`intervals`'
    /// `coverage`); `null` without intervals.
    pub coverage: Option<f64>,
    /// Every held-out reading's error.
    pub errors: Vec<PointError<'a>>,
}

/// The prediction intervals of held-out readings' errors: jackknife+ over the fitted postures,
/// built from their leave-one-posture-out errors; where too few held-out values give the
/// jackknife+ no finite end at the level, the fit's Gaussian bound.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct IntervalsDocument {
    /// `jackknife+`; `jackknife+ and the fit's Gaussian bound` when some ends come from the fit
    /// (`from_fit`); `the fit's Gaussian bound` when every end does.
    pub method: &'static str,
    /// The held-out coordinates whose interval ends come from the fit's Gaussian bound: the
    /// jackknife+ over `folds` postures has too few held-out values for a finite end at `level`
    /// (it needs `held_out_needed`). That bound takes each coordinate's error as normal with the
    /// variance of the fitted postures' leave-one-posture-out errors plus the fit's covariance
    /// carried to the reading: a Gaussian assumption, which heavier tails break.
    pub from_fit: usize,
    /// The held-out values (three per fitted reading) the jackknife+ needs for a finite end at
    /// `level`: 19 at 95 %, 333 at 99.7 %.
    pub held_out_needed: usize,
    /// How the fit's Gaussian bound is built, where it is used; `null` otherwise.
    pub assumption: Option<&'static str>,
    /// The intervals' level (`--level`, default 0.95).
    pub level: f64,
    /// The folds (fitted postures) they are built from.
    pub folds: usize,
    /// The share of the held-out coordinates inside their intervals: near `level` when the
    /// held-out postures are like the fitted ones.
    pub coverage: f64,
    /// `coverage`, %.
    pub coverage_pct: f64,
    /// Held-out coordinates inside their intervals.
    pub covered: usize,
    /// Held-out coordinates (three per reading).
    pub coordinates: usize,
    /// The median over the held-out readings of the intervals' mean width over x, y and z: m,
    /// written in mm.
    #[serde(rename = "median_width_mm", serialize_with = "units::mm_option")]
    pub median_width: Option<f64>,
}

/// One held-out reading's error.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct PointError<'a> {
    /// The posture's label.
    pub posture: &'a str,
    /// The measuring point (1-based), or the table reflector's number (`point_name`).
    pub point: usize,
    /// The point as the readings name it: `1`, `2`, ... a measuring point of the tool (`point`),
    /// `T1`, `T2`, ... a reflector on the positioner's table (numbered apart from the tool's).
    pub point_name: String,
    /// Predicted minus read, base frame: m, written in mm.
    #[serde(rename = "error_mm", serialize_with = "units::mm3")]
    #[cfg_attr(feature = "schema", schemars(with = "[f64; 3]"))]
    pub error: Vector3<f64>,
    /// Its length: m, written in mm.
    #[serde(rename = "error_norm_mm", serialize_with = "units::mm")]
    pub error_norm: f64,
    /// The prediction interval `[lower, upper]` of each coordinate of `error_mm`: m, written in mm
    /// (`null` ends: too few fitted readings for the level); `null` without intervals.
    #[serde(rename = "interval_mm", serialize_with = "units::interval_mm")]
    #[cfg_attr(feature = "schema", schemars(with = "Option<[[Option<f64>; 2]; 3]>"))]
    pub interval: Option<Interval>,
    /// Whether `interval_mm` holds: `false` where the posture lies outside the fitted postures'
    /// axis ranges (`outside_range`; the intervals are built from the fitted postures and say
    /// nothing there), `true` within; `null` without intervals.
    pub interval_holds: Option<bool>,
    /// How far the posture lies outside the fitted postures' axis ranges, when more than 1 deg
    /// (`--validate`); `null` within them.
    pub outside_range: Option<OutsideRange>,
}

/// A held-out posture outside the fitted postures' axis ranges.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct OutsideRange {
    /// The largest distance of an axis angle beyond its fitted range: rad, written in deg.
    #[serde(rename = "distance_deg", serialize_with = "units::deg")]
    pub distance: f64,
    /// The joints beyond their fitted range by more than 1 deg (1-based, ascending).
    pub joints: Vec<usize>,
}

/// The section of held-out readings `h`: an interval holds unless [`Held::outside`] names it.
pub fn held(h: &Held) -> ValidationDocument<'_> {
    let intervals = h.coverage.as_ref().map(|c| {
        let mut widths: Vec<f64> = (h.intervals.iter().flatten())
            .map(|i| i.iter().map(|c| c[1] - c[0]).sum::<f64>() / 3.0)
            .filter(|w| w.is_finite())
            .collect();
        widths.sort_by(f64::total_cmp);
        IntervalsDocument {
            method: match (h.from_fit, c.coordinates) {
                (0, _) => "jackknife+",
                (f, n) if f == n => "the fit's Gaussian bound",
                _ => "jackknife+ and the fit's Gaussian bound",
            },
            from_fit: h.from_fit,
            held_out_needed: stiffid_core::model::prediction::held_out_needed(c.level),
            assumption: (h.from_fit > 0).then_some(super::fit_bound::ASSUMPTION),
            level: c.level,
            folds: c.folds,
            coverage: c.coverage(),
            coverage_pct: 100.0 * c.coverage(),
            covered: c.covered,
            coordinates: c.coordinates,
            median_width: widths.get(widths.len() / 2).copied(),
        }
    });
    let mut errors = errors(&h.calibrated, &h.labels);
    for (e, p) in errors.iter_mut().zip(&h.calibrated.errors) {
        e.outside_range = h.outside.get(&p.posture).map(|o| OutsideRange {
            distance: o.distance,
            joints: o.joints.iter().map(|j| j + 1).collect(),
        });
    }
    for (e, i) in errors.iter_mut().zip(h.intervals.iter().flatten()) {
        e.interval = Some(*i);
        e.interval_holds = Some(e.outside_range.is_none());
    }
    let beyond = errors.iter().filter(|e| e.outside_range.is_some()).count();
    ValidationDocument {
        data: &h.name,
        rms: h.calibrated.rms,
        max: h.calibrated.max,
        within_range_rms: rms_where(&errors, false),
        beyond_range_rms: rms_where(&errors, true),
        beyond_range_readings: beyond,
        nominal_rms: h.nominal.rms,
        coverage: intervals.as_ref().map(|i| i.coverage),
        intervals,
        errors,
    }
}

/// The RMS of the error lengths of `errors` beyond the fitted range (`beyond`) or within it, m;
/// `None` without such readings.
fn rms_where(errors: &[PointError], beyond: bool) -> Option<f64> {
    let (mut sum, mut n) = (0.0, 0usize);
    for e in errors
        .iter()
        .filter(|e| e.outside_range.is_some() == beyond)
    {
        sum += e.error_norm * e.error_norm;
        n += 1;
    }
    (n > 0).then(|| (sum / n as f64).sqrt())
}

/// The label of posture `k` of `labels`, empty beyond them.
pub(super) fn label(labels: &[String], k: usize) -> &str {
    labels.get(k).map_or("", String::as_str)
}

/// Every reading of `v`, its posture labelled from `labels`, without intervals.
fn errors<'a>(v: &Validation, labels: &'a [String]) -> Vec<PointError<'a>> {
    (v.errors.iter())
        .map(|e| PointError {
            posture: label(labels, e.posture),
            point: e.point + 1,
            point_name: point_name(e.point, e.table),
            error: e.error,
            error_norm: e.error.norm(),
            interval: None,
            interval_holds: None,
            outside_range: None,
        })
        .collect()
}
