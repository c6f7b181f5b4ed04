//! The document of the identify job ([`crate::app::identify`]) for the six drive springs: `stiffid identify --json`, the
//! stiffness file of `--out`, Python's `identify(...).to_dict()`.

use crate::app::document::parameters::{stiffness, ParameterStiffness};
use crate::app::document::{finite, finite_each, mm, units};
use crate::app::identify::drives::Report;
use crate::app::measurements::Origin;
use nalgebra::{DVector, Vector3};
use serde::Serialize;
use stiffid_core::common::warning::WarningKind;
use stiffid_core::io::stiffness::{PredictionSection, RegionSection};
use stiffid_core::model::prediction::Calibration;
use stiffid_core::model::Model;
use stiffid_core::model::PostureRange;
use stiffid_core::Coordinates;
use stiffid_identify::{Adequacy, Identification, RobustFit, Uncertainty};

/// The relative standard error of a stiffness (its standard error over its magnitude) above
/// which the document calls it poorly determined (`poorly_determined`): the stiffness is then
/// far from linear in the compliance over its interval, the delta-method interval is unreliable
/// and the interval from the compliance's (`ci95_from_compliance_nm_per_rad`) is the one to trust.
pub(crate) const POORLY_DETERMINED: f64 = 0.25;

/// Whether each stiffness of `id` is poorly determined: its standard error in `u` above
/// [`POORLY_DETERMINED`] times its magnitude (`false` for a stiffness or an error that is not a
/// number).
pub(crate) fn poorly_determined(id: &Identification, u: &Uncertainty) -> [bool; 6] {
    std::array::from_fn(|j| u.stiffness_std_error[j] / id.stiffness[j].abs() > POORLY_DETERMINED)
}

/// How many of the largest residuals the document lists (`largest_residuals`).
pub(crate) const LARGEST_RESIDUALS: usize = 5;

/// The relative standard error of each stiffness of `id` in `u`: the standard error over the
/// stiffness's magnitude, %, `None` unless finite.
fn std_error_pct(id: &Identification, u: &Uncertainty) -> [Option<f64>; 6] {
    std::array::from_fn(|j| finite(100.0 * (u.stiffness_std_error[j] / id.stiffness[j].abs())))
}

/// The identify document. Units in the key names; intervals `[lower, upper]`; `null` for a number
/// that is not finite (an unbounded end, an infinite stiffness) or when there are no degrees of
/// freedom.
///
/// A view of the report ([`Report::document`]), built as it is written: its names are the
/// report's, its lengths the report's in SI, written in the units their keys name by the unit
/// adapters ([`units`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "identify-drives")]
#[cfg_attr(
    feature = "schema",
    schemars(
        description = "The identify document. Units in the key names; intervals `[lower, upper]`; `null` for a number\nthat is not finite (an unbounded end, an infinite stiffness) or when there are no degrees of\nfreedom."
    )
)]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("identify-drives")))]
pub struct Document<'a> {
    /// The setup as given.
    pub setup: &'a str,
    /// The measurements (a file's name, or `arrays`).
    pub data: &'a str,
    /// Where the springs sit: in the drives (`axis`) or on the kinematic joints.
    pub springs: Coordinates,
    /// The fit: `least-squares`, `nonnegative-least-squares`, `huber` or `tukey`.
    pub method: &'static str,
    /// Rows of the stacked system (3 per measurement).
    pub rows: usize,
    /// Distinct postures in the data.
    pub postures: usize,
    /// Every parameter of the model (the six drives) with its name, kind, unit and stiffness:
    /// with `compliance_covariance_si`, what a stiffness file holds
    /// ([`stiffid_core::io::stiffness`]).
    pub parameters: Vec<ParameterStiffness>,
    /// `Cov(h)` of the compliance of every parameter, SI, row-major (here the six drives, equal
    /// to `compliance_covariance_rad2_per_nm2`); `null` without degrees of freedom.
    pub compliance_covariance_si: Option<Vec<Vec<f64>>>,
    /// The identified joint stiffness, Nm/rad.
    pub stiffness_nm_per_rad: [Option<f64>; 6],
    /// The identified joint compliance (the unknowns of Eq. 14), rad/Nm.
    pub compliance_rad_per_nm: [f64; 6],
    /// Whether each compliance is positive (a physical spring).
    pub physical: [bool; 6],
    /// With a non-negative fit: which compliances sit at their bound 0; else `null`.
    pub active_bounds: Option<[bool; 6]>,
    /// With a non-negative fit: why its active-set steps stopped, `converged` (the bounded
    /// minimum) or `iteration-limit` (a warning says so); left out for another fit.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub nonnegative_stop_reason: Option<stiffid_core::common::stop::Stop>,
    /// Where the intervals below come from (`residual variance`).
    pub intervals_from: &'static str,
    /// Standard error of each stiffness (delta method), Nm/rad.
    pub std_error_nm_per_rad: Option<[Option<f64>; 6]>,
    /// The relative standard error of each stiffness: `std_error_nm_per_rad` over the
    /// stiffness's magnitude, %; `null` unless finite, or without degrees of freedom.
    pub std_error_pct: Option<[Option<f64>; 6]>,
    /// The relative standard error above which a stiffness is poorly determined (25 %), %.
    pub poorly_determined_above_pct: f64,
    /// Whether each stiffness is poorly determined: `std_error_nm_per_rad` above
    /// 0.25 times its magnitude; measure postures
    /// that load these joints more. `null` without degrees of freedom.
    pub poorly_determined: Option<[bool; 6]>,
    /// 95% confidence interval of each stiffness, symmetric in the stiffness, Nm/rad.
    pub ci95_nm_per_rad: Option<[[Option<f64>; 2]; 6]>,
    /// 95% confidence interval of each stiffness, the compliance's interval inverted, Nm/rad.
    pub ci95_from_compliance_nm_per_rad: Option<[[Option<f64>; 2]; 6]>,
    /// Standard error of each compliance, rad/Nm.
    pub compliance_std_error_rad_per_nm: Option<[f64; 6]>,
    /// 95% confidence interval of each compliance, rad/Nm.
    pub compliance_ci95_rad_per_nm: Option<[[f64; 2]; 6]>,
    /// `Cov(h)` of the compliance, (rad/Nm)^2, row-major.
    pub compliance_covariance_rad2_per_nm2: Option<[[f64; 6]; 6]>,
    /// Rows minus unknowns.
    pub degrees_of_freedom: Option<usize>,
    /// Student's t quantile of the 95% intervals.
    pub t_quantile: Option<f64>,
    /// Standard deviation of the residuals: m, written in mm.
    #[serde(rename = "residual_std_mm", serialize_with = "units::mm_option")]
    pub residual_std: Option<f64>,
    /// The setup's tracker noise on one row's coordinate that the model check uses, a
    /// displacement's (a loaded minus an unloaded reading: `sqrt(2)` times `reading_sd_mm`), or
    /// with offsets fitted one reading's (`reading_sd_mm`): m, written in mm.
    #[serde(rename = "noise_std_mm", serialize_with = "units::mm")]
    pub noise_std: f64,
    /// `residual_std_mm / noise_std_mm`: about 1 if the model is adequate.
    pub noise_ratio: Option<f64>,
    /// `dof s^2 / sigma^2`: the residual variance against the tracker noise variance.
    pub chi2_statistic: Option<f64>,
    /// `P(X >= chi2_statistic)` for `X ~ chi2(dof)`: small when the residuals exceed the noise.
    pub chi2_p_value: Option<f64>,
    /// Whether `chi2_p_value < 0.01`: the model error dominates the tracker noise.
    pub model_error_dominates: Option<bool>,
    /// The intervals computed from the setup's tracker noise instead of the residuals.
    pub tracker_noise: Option<Intervals>,
    /// A warning when most joints are far off the setup's nominal stiffness the same way (a unit
    /// mistake?).
    pub unit_warning: Option<&'a str>,
    /// `cond_2(Psi)` of the observation matrix, SI units.
    pub cond_psi: f64,
    /// RMS of the residuals: m, written in mm.
    #[serde(rename = "residual_rms_mm", serialize_with = "units::mm")]
    pub residual_rms: f64,
    /// Every measurement's residual (measured - fitted), in the data's order.
    pub residuals: Vec<Residual<'a>>,
    /// The 5 measurements with the longest residuals (or all of them if fewer), the longest first.
    pub largest_residuals: Vec<Residual<'a>>,
    /// With a robust fit: the reweighting.
    pub robust: Option<Robust<'a>>,
    /// With cross-validation: the cross-validation over postures.
    pub cross_validation: Option<CrossValidation<'a>>,
    /// With raw readings under load steps: each posture's linearity, zero-load offset and
    /// hysteresis (`stiffid_identify::steps`).
    pub load_steps: Option<Vec<LoadStep<'a>>>,
    /// With offsets fitted beside the compliances: one per posture and measuring point.
    pub offsets: Option<Vec<PointOffset<'a>>>,
    /// With cross-validation: the held-out residuals that prediction intervals are built from
    /// (the stiffness file's `prediction`, [`stiffid_core::io::stiffness::PredictionSection`]).
    pub prediction: Option<PredictionSection>,
    /// The region of axis angles the data's postures span, widened by a margin: what
    /// `predict`, `validate` and `compensate` flag a posture outside of (the stiffness file's
    /// `region`, [`stiffid_core::io::stiffness::RegionSection`]).
    pub region: Option<RegionSection>,
}

/// How one posture's deflection follows the load steps. P-values test each effect against the
/// setup's tracker noise; a flag is a p-value below 0.01.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct LoadStep<'a> {
    /// The posture's label.
    pub posture: &'a str,
    /// Distinct non-zero loads on the rising branch.
    pub levels: usize,
    /// Readings of the posture, the unloaded references excepted.
    pub readings: usize,
    /// Deflection per load (RMS over the measuring points of the slopes' lengths), mm/kN;
    /// `null` with fewer than two non-zero loads.
    pub slope_mm_per_kn: Option<f64>,
    /// The straight lines' deflection at zero load, RMS over the measuring points: m, written in
    /// mm.
    #[serde(rename = "zero_load_offset_mm", serialize_with = "units::mm_option")]
    pub zero_load_offset: Option<f64>,
    /// `R^2` of the straight lines.
    pub r_squared: Option<f64>,
    /// RMS length of falling minus rising readings at the same step, `null` without falling
    /// readings: m, written in mm.
    #[serde(rename = "hysteresis_mm", serialize_with = "units::mm_option")]
    pub hysteresis: Option<f64>,
    /// P-value of the zero-load offset.
    pub offset_p_value: Option<f64>,
    /// P-value of the residuals about the straight lines.
    pub linearity_p_value: Option<f64>,
    /// P-value of the hysteresis.
    pub hysteresis_p_value: Option<f64>,
    /// Whether the zero-load offset exceeds the tracker noise.
    pub offset_flagged: bool,
    /// Whether the deflection departs from a straight line beyond the tracker noise.
    pub nonlinear: bool,
    /// Whether the hysteresis exceeds the tracker noise.
    pub hysteresis_flagged: bool,
}

/// The offset of one measuring point in one posture, fitted beside the compliances.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct PointOffset<'a> {
    /// The posture's label.
    pub posture: &'a str,
    /// The measuring point (1-based).
    pub point: usize,
    /// The offset, base frame: m, written in mm.
    #[serde(rename = "offset_mm", serialize_with = "units::mm3")]
    #[cfg_attr(feature = "schema", schemars(with = "[f64; 3]"))]
    pub offset: Vector3<f64>,
}

/// Standard errors and intervals computed from a known variance.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Intervals {
    /// Standard error of each stiffness, Nm/rad.
    pub std_error_nm_per_rad: [Option<f64>; 6],
    /// 95% confidence interval of each stiffness, Nm/rad.
    pub ci95_nm_per_rad: [[Option<f64>; 2]; 6],
    /// 95% confidence interval of each stiffness from the compliance's, Nm/rad.
    pub ci95_from_compliance_nm_per_rad: [[Option<f64>; 2]; 6],
    /// The relative standard error of each stiffness: `std_error_nm_per_rad` over the
    /// stiffness's magnitude, %; `null` unless finite.
    pub std_error_pct: [Option<f64>; 6],
    /// Standard error of each compliance, rad/Nm.
    pub compliance_std_error_rad_per_nm: [f64; 6],
    /// 95% confidence interval of each compliance, rad/Nm.
    pub compliance_ci95_rad_per_nm: [[f64; 2]; 6],
    /// The normal quantile of these 95% intervals.
    pub quantile: f64,
}

/// One measurement's residual.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Residual<'a> {
    /// The posture's label (a file's; for arrays its number, 1-based).
    pub posture: &'a str,
    /// The measuring point (1-based).
    pub point: usize,
    /// The line in the file (left out for arrays).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[cfg_attr(feature = "schema", schemars(with = "u64"))]
    pub line: Option<u64>,
    /// Measured minus fitted displacement, x, y, z: m, written in mm.
    #[serde(rename = "residual_mm", serialize_with = "units::mm3")]
    #[cfg_attr(feature = "schema", schemars(with = "[f64; 3]"))]
    pub residual: Vector3<f64>,
    /// The length of `residual_mm`, mm.
    pub norm_mm: f64,
    /// The measured displacement, base frame, x, y, z, mm: `predicted_mm + residual_mm`.
    pub measured_mm: [f64; 3],
    /// The displacement the fit predicts, base frame, x, y, z (with fitted offsets, its point's
    /// offset included): m, written in mm.
    #[serde(rename = "predicted_mm", serialize_with = "units::mm3")]
    #[cfg_attr(feature = "schema", schemars(with = "[f64; 3]"))]
    pub predicted: Vector3<f64>,
}

impl<'a> Residual<'a> {
    /// Measurement `i`'s residual of `residuals` and prediction of `predicted` (m, three per
    /// measurement), labelled from `origin`.
    pub(crate) fn new(
        origin: &'a Origin,
        i: usize,
        residuals: &DVector<f64>,
        predicted: &DVector<f64>,
    ) -> Self {
        let residual: Vector3<f64> = residuals.fixed_rows::<3>(3 * i).into();
        let predicted: Vector3<f64> = predicted.fixed_rows::<3>(3 * i).into();
        let (r, p) = (residual.map(mm), predicted.map(mm));
        Residual {
            posture: origin.label(i),
            point: origin.points[i] + 1,
            line: origin.lines.as_ref().map(|l| l[i]),
            residual,
            norm_mm: r.norm(),
            measured_mm: (p + r).into(),
            predicted,
        }
    }

    /// Every measurement's residual ([`Residual::new`]).
    pub(crate) fn all(
        origin: &'a Origin,
        residuals: &DVector<f64>,
        predicted: &DVector<f64>,
    ) -> Vec<Self> {
        (0..residuals.len() / 3)
            .map(|i| Residual::new(origin, i, residuals, predicted))
            .collect()
    }
}

/// The robust fit's reweighting.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Robust<'a> {
    /// `huber` or `tukey`.
    pub loss: &'static str,
    /// The tuning constant, MAD scales.
    pub tuning_constant: f64,
    /// The robust residual scale: m, written in mm.
    #[serde(rename = "scale_mm", serialize_with = "units::mm")]
    pub scale: f64,
    /// Reweighting iterations.
    pub iterations: usize,
    /// Whether the weights converged.
    pub converged: bool,
    /// Why the reweighting stopped: `converged` or `iteration-limit` (a warning says so).
    pub stop_reason: stiffid_core::common::stop::Stop,
    /// Every row with a weight below 1.
    pub down_weighted: Vec<Row<'a>>,
}

/// One down-weighted row.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Row<'a> {
    /// The posture's label.
    pub posture: &'a str,
    /// The measuring point (1-based).
    pub point: usize,
    /// The line in the file (left out for arrays).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[cfg_attr(feature = "schema", schemars(with = "u64"))]
    pub line: Option<u64>,
    /// `x`, `y` or `z`.
    pub coordinate: char,
    /// Its final weight, 0 to 1.
    pub weight: f64,
    /// Its residual: m, written in mm.
    #[serde(rename = "residual_mm", serialize_with = "units::mm")]
    pub residual: f64,
}

/// The cross-validation over postures.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct CrossValidation<'a> {
    /// Number of folds.
    pub folds: usize,
    /// Mean over the folds of each stiffness, Nm/rad.
    pub stiffness_mean_nm_per_rad: [Option<f64>; 6],
    /// Standard deviation over the folds, Nm/rad.
    pub stiffness_std_nm_per_rad: [Option<f64>; 6],
    /// Smallest over the folds, Nm/rad.
    pub stiffness_min_nm_per_rad: [Option<f64>; 6],
    /// Largest over the folds, Nm/rad.
    pub stiffness_max_nm_per_rad: [Option<f64>; 6],
    /// `stiffness_std_nm_per_rad` as a percentage of the full fit's stiffness (its magnitude),
    /// %; `null` unless finite.
    pub stiffness_std_pct: [Option<f64>; 6],
    /// RMS prediction error of the left-out measurements (Eq. 22): m, written in mm.
    #[serde(rename = "rms_delta_b_mm", serialize_with = "units::mm")]
    pub rms_delta_b: f64,
    /// RMS of the measured displacements: m, written in mm.
    #[serde(rename = "rms_measured_mm", serialize_with = "units::mm")]
    pub rms_measured: f64,
    /// `1 - rms_delta_b_mm / rms_measured_mm`.
    pub explained: f64,
    /// The standard error of `explained` over the postures (delta method of the ratio, the
    /// postures as independent units).
    pub explained_std_error: f64,
    /// `explained`, %.
    pub explained_pct: f64,
    /// `explained_std_error`, %.
    pub explained_std_error_pct: f64,
    /// Folds whose removal moves a stiffness by more than its standard error in the full fit.
    pub influential_postures: Vec<Influential<'a>>,
    /// Every fold.
    pub per_fold: Vec<Fold<'a>>,
}

/// One fold.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Fold<'a> {
    /// The postures left out (labels).
    pub postures: Vec<&'a str>,
    /// The stiffness fitted without them, Nm/rad.
    pub stiffness_nm_per_rad: [Option<f64>; 6],
    /// RMS prediction error of the left-out measurements: m, written in mm.
    #[serde(rename = "rms_delta_b_mm", serialize_with = "units::mm")]
    pub rms_delta_b: f64,
    /// Prediction error of each left-out measurement (Eq. 22): m, written in mm.
    #[serde(rename = "delta_b_mm", serialize_with = "units::mm_each")]
    #[cfg_attr(feature = "schema", schemars(with = "Vec<f64>"))]
    pub delta_b: &'a [f64],
}

/// An influential fold.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Influential<'a> {
    /// The postures left out (labels).
    pub postures: &'a [String],
    /// The joints (1-based) it moves.
    pub joints: Vec<usize>,
}

impl Intervals {
    fn new(id: &Identification, u: &Uncertainty) -> Self {
        Intervals {
            std_error_nm_per_rad: finite_each(u.stiffness_std_error),
            ci95_nm_per_rad: u.stiffness_ci95.map(|i| i.map(finite)),
            ci95_from_compliance_nm_per_rad: u
                .stiffness_ci95_from_compliance
                .map(|i| i.map(finite)),
            std_error_pct: std_error_pct(id, u),
            compliance_std_error_rad_per_nm: u.compliance_std_error.into(),
            compliance_ci95_rad_per_nm: u.compliance_ci95,
            quantile: u.t_quantile,
        }
    }
}

impl<'a> Document<'a> {
    /// The view of `report` ([`Report::document`]).
    pub(crate) fn new(report: &'a Report) -> Self {
        let id = &report.identification;
        let u = id.uncertainty.as_ref();
        let a = report.adequacy.as_ref();
        let noise = a.map(|a| Intervals::new(id, &a.from_noise));
        Document {
            setup: &report.setup,
            data: &report.data_name,
            springs: report.springs,
            method: report.fit.name(),
            rows: id.rows,
            postures: id.postures,
            parameters: stiffness(
                &Model::drives(report.springs).parameters(),
                &DVector::from_column_slice(id.compliance.as_slice()),
            ),
            compliance_covariance_si: u.map(|u| {
                u.compliance_covariance
                    .row_iter()
                    .map(|r| r.iter().copied().collect())
                    .collect()
            }),
            stiffness_nm_per_rad: finite_each(id.stiffness),
            compliance_rad_per_nm: id.compliance.into(),
            physical: id.physical(),
            active_bounds: id.active_bounds,
            nonnegative_stop_reason: id.nonnegative_stop,
            intervals_from: "residual variance",
            std_error_nm_per_rad: u.map(|u| finite_each(u.stiffness_std_error)),
            std_error_pct: u.map(|u| std_error_pct(id, u)),
            poorly_determined_above_pct: 100.0 * POORLY_DETERMINED,
            poorly_determined: u.map(|u| poorly_determined(id, u)),
            ci95_nm_per_rad: u.map(|u| u.stiffness_ci95.map(|i| i.map(finite))),
            ci95_from_compliance_nm_per_rad: u
                .map(|u| u.stiffness_ci95_from_compliance.map(|i| i.map(finite))),
            compliance_std_error_rad_per_nm: u.map(|u| u.compliance_std_error.into()),
            compliance_ci95_rad_per_nm: u.map(|u| u.compliance_ci95),
            compliance_covariance_rad2_per_nm2: u.map(|u| {
                std::array::from_fn(|r| std::array::from_fn(|c| u.compliance_covariance[(r, c)]))
            }),
            degrees_of_freedom: u.map(|u| u.dof),
            t_quantile: u.map(|u| u.t_quantile),
            residual_std: u.map(|u| u.residual_variance.sqrt()),
            noise_std: a.map_or(report.noise.displacement_sd(), |a| a.noise_variance.sqrt()),
            noise_ratio: a.map(|a| a.noise_ratio),
            chi2_statistic: a.map(|a| a.chi2),
            chi2_p_value: a.map(|a| a.p_value),
            model_error_dominates: a.map(Adequacy::model_error_dominates),
            tracker_noise: noise,
            unit_warning: report
                .warnings
                .iter()
                .find(|w| w.kind == WarningKind::Units)
                .map(|w| w.message.as_str()),
            cond_psi: id.cond_psi,
            residual_rms: id.residual_rms,
            residuals: residuals(report),
            largest_residuals: largest_residuals(report),
            robust: robust(report),
            cross_validation: cross_validation(report),
            load_steps: load_steps(report),
            offsets: offsets(report),
            prediction: prediction(
                report.prediction.as_ref(),
                report.cross_validation.as_ref(),
                &report.origin,
            ),
            region: region(&report.origin),
        }
    }
}

/// The stiffness file's `region`: the range of the postures of `origin`
/// ([`stiffid_core::model::region`]).
pub(crate) fn region(origin: &Origin) -> Option<RegionSection> {
    PostureRange::of(&origin.angles).map(|r| RegionSection::new(&r))
}

/// The stiffness file's `prediction` of a calibration and its cross-validation, the folds'
/// postures named as in `origin`.
pub(crate) fn prediction(
    calibration: Option<&Calibration>,
    cv: Option<&stiffid_identify::CrossValidation>,
    origin: &Origin,
) -> Option<PredictionSection> {
    let (calibration, cv) = calibration.zip(cv)?;
    let labels = cv.folds.iter().map(|f| origin.labels_of(&f.postures));
    Some(PredictionSection::new(calibration, labels.collect()))
}

fn load_steps(report: &Report) -> Option<Vec<LoadStep<'_>>> {
    let rows = report.load_steps.as_ref()?.iter().map(|l| LoadStep {
        posture: report.origin.labels.get(l.posture),
        levels: l.levels,
        readings: l.readings,
        slope_mm_per_kn: l.slope_m_per_n.map(|v| v * 1e6),
        zero_load_offset: l.offset_m,
        r_squared: l.r_squared,
        hysteresis: l.hysteresis_m,
        offset_p_value: l.offset_p_value,
        linearity_p_value: l.linearity_p_value,
        hysteresis_p_value: l.hysteresis_p_value,
        offset_flagged: l.offset_flagged(),
        nonlinear: l.nonlinear(),
        hysteresis_flagged: l.hysteresis_flagged(),
    });
    Some(rows.collect())
}

fn offsets(report: &Report) -> Option<Vec<PointOffset<'_>>> {
    let origin = &report.origin;
    let rows = report.offsets.as_ref()?.iter().map(|o| PointOffset {
        posture: origin.labels.get(o.posture),
        point: o.point + 1,
        offset: o.offset,
    });
    Some(rows.collect())
}

/// The residual of measurement `i` of `report`.
fn residual(report: &Report, i: usize) -> Residual<'_> {
    let id = &report.identification;
    Residual::new(&report.origin, i, &id.residuals, &id.predicted)
}

fn residuals(report: &Report) -> Vec<Residual<'_>> {
    let id = &report.identification;
    Residual::all(&report.origin, &id.residuals, &id.predicted)
}

/// The [`LARGEST_RESIDUALS`] longest residuals of `report`, the longest first.
fn largest_residuals(report: &Report) -> Vec<Residual<'_>> {
    let residuals = &report.identification.residuals;
    let norm = |i: usize| residuals.fixed_rows::<3>(3 * i).norm();
    let n = residuals.len() / 3;
    let shown = LARGEST_RESIDUALS.min(n);
    let mut order: Vec<usize> = (0..n).collect();
    if shown > 0 {
        order.select_nth_unstable_by(shown - 1, |&a, &b| norm(b).total_cmp(&norm(a)));
    }
    order.truncate(shown);
    order.sort_by(|&a, &b| norm(b).total_cmp(&norm(a)));
    order.into_iter().map(|i| residual(report, i)).collect()
}

fn robust(report: &Report) -> Option<Robust<'_>> {
    let id = &report.identification;
    Some(Robust::new(
        id.robust.as_ref()?,
        &report.origin,
        &id.residuals,
    ))
}

impl<'a> Robust<'a> {
    /// The reweighting `fit` of the measurements of `origin`, with the unweighted `residuals`
    /// (m, three per measurement).
    pub(crate) fn new(fit: &RobustFit, origin: &'a Origin, residuals: &DVector<f64>) -> Self {
        Robust {
            loss: fit.loss.name(),
            tuning_constant: fit.loss.tuning_constant(),
            scale: fit.scale,
            iterations: fit.iterations,
            converged: fit.converged(),
            stop_reason: fit.stop,
            down_weighted: fit
                .down_weighted()
                .into_iter()
                .map(|row| Row {
                    posture: origin.label(row / 3),
                    point: origin.points[row / 3] + 1,
                    line: origin.lines.as_ref().map(|l| l[row / 3]),
                    coordinate: ['x', 'y', 'z'][row % 3],
                    weight: fit.weights[row],
                    residual: residuals[row],
                })
                .collect(),
        }
    }
}

/// The first six values (the drives), each `null` unless finite.
fn six(values: &[f64]) -> [Option<f64>; 6] {
    std::array::from_fn(|j| finite(values[j]))
}

/// The labels of `postures` (numbered as in `origin`).
pub(crate) fn labels<'a>(origin: &'a Origin, postures: &[usize]) -> Vec<&'a str> {
    let label = |p: &usize| origin.label(origin.first_of_posture[*p]);
    postures.iter().map(label).collect()
}

fn cross_validation(report: &Report) -> Option<CrossValidation<'_>> {
    let cv = report.cross_validation.as_ref()?;
    Some(CrossValidation {
        folds: cv.folds.len(),
        stiffness_mean_nm_per_rad: six(cv.stiffness_mean.as_slice()),
        stiffness_std_nm_per_rad: six(cv.stiffness_std.as_slice()),
        stiffness_min_nm_per_rad: six(cv.stiffness_range[0].as_slice()),
        stiffness_max_nm_per_rad: six(cv.stiffness_range[1].as_slice()),
        stiffness_std_pct: std::array::from_fn(|j| {
            finite(100.0 * cv.stiffness_std[j] / report.identification.stiffness[j].abs())
        }),
        rms_delta_b: cv.rms_delta_b,
        rms_measured: cv.rms_measured,
        explained: cv.explained(),
        explained_std_error: cv.explained_std_error,
        explained_pct: 100.0 * cv.explained(),
        explained_std_error_pct: 100.0 * cv.explained_std_error,
        influential_postures: report
            .influential
            .iter()
            .map(|(postures, joints)| Influential {
                postures,
                joints: joints.iter().map(|j| j + 1).collect(),
            })
            .collect(),
        per_fold: cv
            .folds
            .iter()
            .map(|f| Fold {
                postures: labels(&report.origin, &f.postures),
                stiffness_nm_per_rad: six(f.stiffness.as_slice()),
                rms_delta_b: f.rms_delta_b,
                delta_b: &f.delta_b,
            })
            .collect(),
    })
}
