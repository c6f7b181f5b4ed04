//! The document of the validate job ([`crate::app::validate`]): `stiffid validate --json`,
//! Python's `validate(...)`. The report is the document ([`super::Report`]), written through
//! the borrowed view [`Document`] ([`super::Report::document`]), built as it is written.

use crate::app::document::parameters::{stiffness, ParameterStiffness};
use crate::app::document::{interval_mm, mm};
use crate::app::validate::Report;
use serde::Serialize;
use stiffid_core::io::stiffness::RegionSection;

/// Measured against predicted displacements (Eq. 22), mm.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "validate")]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("validate")))]
pub struct Document<'a> {
    /// The setup as given.
    pub setup: &'a str,
    /// The measurements (a file's name, or `arrays`).
    pub data: &'a str,
    /// The stiffness validated: every parameter of the setup's model, in its unit.
    pub parameters: Vec<ParameterStiffness>,
    /// Every measurement, in the data's order.
    pub checks: Vec<Check<'a>>,
    /// Mean of `delta_b` over the measurements, mm.
    pub mean_delta_b_mm: f64,
    /// Largest `delta_b`, mm.
    pub max_delta_b_mm: f64,
    /// RMS of `delta_b`, mm.
    pub rms_delta_b_mm: f64,
    /// Mean length of the measured displacements, mm.
    pub mean_measured_mm: f64,
    /// Largest measured displacement, mm.
    pub max_measured_mm: f64,
    /// RMS of the measured displacements, mm.
    pub rms_measured_mm: f64,
    /// `1 - rms_delta_b_mm / rms_measured_mm`.
    pub explained: f64,
    /// `explained`, %.
    pub explained_pct: f64,
    /// With a stiffness file that holds held-out residuals (`identify --cross-validate`): the
    /// coverage of the prediction intervals; else `null`.
    pub prediction_intervals: Option<PredictionIntervals>,
    /// The region of axis angles the stiffness was identified from; `null` when the stiffness
    /// records none (values given directly, a stiffness file written before files carried it).
    pub region: Option<RegionSection>,
    /// The postures outside that region (their checks' `extrapolates`); `null` as `region`.
    pub extrapolated_postures: Option<usize>,
}

/// How well the prediction intervals covered the measurements.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct PredictionIntervals {
    /// `jackknife+` (leave one posture out) or `cv+` (K folds).
    pub method: &'static str,
    /// The level asked (`--level`).
    pub level: f64,
    /// The share of the measured displacement coordinates inside their intervals.
    pub coverage: f64,
    /// `coverage`, %.
    pub coverage_pct: f64,
    /// Measured coordinates inside their intervals.
    pub covered: usize,
    /// Measured coordinates (three per measurement).
    pub coordinates: usize,
}

/// One measurement against its prediction.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Check<'a> {
    /// The posture's label (a file's; for arrays its number, 1-based).
    pub posture: &'a str,
    /// The measuring point (1-based).
    pub point: usize,
    /// The line in the file (left out for arrays).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[cfg_attr(feature = "schema", schemars(with = "u64"))]
    pub line: Option<u64>,
    /// Measured displacement x, y, z, base frame, mm.
    pub measured_mm: [f64; 3],
    /// Predicted displacement x, y, z, base frame, mm.
    pub predicted_mm: [f64; 3],
    /// `|measured - predicted|` (Eq. 22), mm.
    pub delta_b_mm: f64,
    /// The prediction interval `[lower, upper]` of x, y, z, base frame, mm (`null` ends:
    /// unbounded, too few held-out residuals for the level); `null` without held-out residuals.
    pub interval_mm: Option<[[Option<f64>; 2]; 3]>,
    /// Whether the posture lies outside the region the stiffness was identified from (an axis
    /// beyond the identification postures' range widened by its margin): the prediction
    /// extrapolates; `null` when the stiffness records no region.
    pub extrapolates: Option<bool>,
}

impl Report {
    /// The document this report is written as: its view in mm (what it serialises to).
    pub fn document(&self) -> Document<'_> {
        let report = self;
        let v = &report.validation;
        let origin = &report.origin;
        Document {
            setup: &report.setup,
            data: &report.data_name,
            parameters: stiffness(&report.parameters, &report.compliance.h),
            checks: v
                .checks
                .iter()
                .enumerate()
                .map(|(i, c)| Check {
                    posture: origin.label(i),
                    point: c.point + 1,
                    line: origin.lines.as_ref().map(|l| l[i]),
                    measured_mm: c.measured.map(mm).into(),
                    predicted_mm: c.predicted.map(mm).into(),
                    delta_b_mm: mm(c.delta_b),
                    interval_mm: c.interval.map(interval_mm),
                    extrapolates: (report.outside_region.as_ref())
                        .map(|o| !o[origin.postures[i]].is_empty()),
                })
                .collect(),
            mean_delta_b_mm: mm(v.mean),
            max_delta_b_mm: mm(v.max),
            rms_delta_b_mm: mm(v.rms),
            mean_measured_mm: mm(v.measured[0]),
            max_measured_mm: mm(v.measured[1]),
            rms_measured_mm: mm(v.measured[2]),
            explained: v.explained,
            explained_pct: 100.0 * v.explained,
            prediction_intervals: v.prediction.as_ref().map(|p| PredictionIntervals {
                method: p.method,
                level: p.level,
                coverage: p.coverage(),
                coverage_pct: 100.0 * p.coverage(),
                covered: p.covered,
                coordinates: p.coordinates,
            }),
            region: RegionSection::of(&report.compliance.region),
            extrapolated_postures: (report.outside_region.as_ref())
                .map(|o| o.iter().filter(|axes| !axes.is_empty()).count()),
        }
    }
}
