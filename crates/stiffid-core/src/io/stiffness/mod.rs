//! Stiffness files: JSON with the stiffness of every parameter of a model and, optionally, the
//! covariance of the compliance, as `stiffid identify --out` writes them (the identify document's
//! other keys, [`DOCUMENT_KEYS`], are ignored; any other key is refused).
//!
//! Every parameter named, with its kind and unit (the drives and rotational springs in Nm/rad,
//! translational springs in N/mm; [`crate::model`]), and the covariance `Cov(h)` of the
//! compliance over all of them in SI units (rad/Nm, m/N):
//!
//! ```json
//! {"parameters": [{"name": "k1", "kind": "drive", "unit": "Nm/rad", "stiffness": 950000}, ...,
//!                 {"name": "tool_y", "kind": "translation", "unit": "N/mm", "stiffness": 42000}],
//!  "compliance_covariance_si": [[...n numbers...], ...n rows...]}
//! ```
//!
//! The six drives alone, as files written before models had virtual springs, are still read:
//!
//! ```json
//! {"stiffness_nm_per_rad": [950000, 3000000, 900000, 250000, 200000, 150000],
//!  "compliance_covariance_rad2_per_nm2": [[...6 numbers...], ...6 rows...]}
//! ```
//!
//! With `parameters`, `stiffness_nm_per_rad` (as identify writes it beside them) must be the
//! drives' stiffness in `parameters`; its covariance is ignored.
//!
//! From `identify --cross-validate`, the key `prediction` holds what prediction intervals are
//! built from ([`crate::model::prediction`]): per fold, the compliance fitted without its
//! postures and the scores of their held-out coordinates ([`PredictionSection`]); `predict`,
//! `compensate` and `validate` give intervals with it. A file is used with a
//! setup whose model has the same parameters in the same order ([`StiffnessFile::compliance`]).
//!
//! The key `region` ([`RegionSection`], written by `identify` and `calibrate --stiffness-out`)
//! holds the range of every axis over the postures the stiffness was identified from and the
//! margin that widens it ([`crate::model::region`]): `predict`, `validate` and `compensate` flag
//! a posture outside it. A file without it is read, and nothing is checked
//! ([`crate::model::Region::Unrecorded`]).
//!
//! The key `model_form` ([`ModelFormSection`], written by `identify --compare-models --bootstrap
//! N --stiffness-out`) holds the models the data support and their resampled parameter sets:
//! `compensate` takes their spread as its error budget's model-form part. A file without it is
//! read, and the part is absent.
//!
//! A parameter `identify` could not separate from others carries `"identified": false` (the
//! file's `unidentifiable` writes the combinations out): its stiffness is one of infinitely many
//! that fit the data, so [`StiffnessFile::compliance`] refuses the file rather than predict with it.

mod covariance;
mod duplicates;
mod model_form;
mod sections;

pub(crate) use covariance::check_covariance;
pub use covariance::check_covariance_of;
pub use model_form::FormLaw;
pub use model_form::{FormModelSection, FormSpring, ModelFormSection};
pub use sections::{FoldSection, GravitySection, GravityTerm};
pub use sections::{PredictionSection, RegionSection};

use crate::common::limits::{self, MAX_PARAMETERS, STIFFNESS_NM_PER_RAD, STIFFNESS_N_PER_MM};
use crate::model::{Compliance, Model, ParameterKind, Region};
use crate::{Error, Result};
use nalgebra::{DMatrix, Matrix6, Vector6};
use serde::{Deserialize, Serialize};

/// The keys of the identify documents (`stiffid identify --json`, over the drives or over a model
/// with virtual springs) that a stiffness file may hold beside [`StiffnessFile`]'s: read and ignored. Any other key is refused ([`parse`]): a misspelt key would otherwise be dropped
/// silently.
pub const DOCUMENT_KEYS: &[&str] = &[
    "setup",
    "data",
    "springs",
    "method",
    "rows",
    "postures",
    "compliance_rad_per_nm",
    "physical",
    "active_bounds",
    "nonnegative_stop_reason",
    "intervals_from",
    "std_error_nm_per_rad",
    "std_error_pct",
    "poorly_determined_above_pct",
    "poorly_determined",
    "ci95_nm_per_rad",
    "ci95_from_compliance_nm_per_rad",
    "compliance_std_error_rad_per_nm",
    "compliance_ci95_rad_per_nm",
    "degrees_of_freedom",
    "t_quantile",
    "residual_std_mm",
    "noise_std_mm",
    "noise_ratio",
    "chi2_statistic",
    "chi2_p_value",
    "model_error_dominates",
    "tracker_noise",
    "unit_warning",
    "cond_psi",
    "residual_rms_mm",
    "residuals",
    "largest_residuals",
    "robust",
    "cross_validation",
    "load_steps",
    "offsets",
    "rank",
    "scaled_cond",
    "model_check",
    "warnings",
];

/// The keys of [`DOCUMENT_KEYS`] as files written before every percentage's key ended in `_pct`
/// spelt them: read and ignored alike, so those files still read.
pub(crate) const FORMER_KEYS: &[&str] = &["std_error_percent", "poorly_determined_above_percent"];

/// What a stiffness file holds, as its JSON keys (the identify document's others,
/// [`DOCUMENT_KEYS`], are ignored).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct StiffnessFile {
    /// Optional: what wrote the file, first where it is written: `stiffness` (a stiffness file
    /// `calibrate --stiffness-out` or `identify --stiffness-out` writes), `identify-drives` or
    /// `identify-springs` (an identify document, read as a stiffness file); another document's
    /// kind is refused naming it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kind: Option<FileKind>,
    /// Every parameter of the model, drives first (`k1` .. `k6`), then the virtual springs in the
    /// order of the setup's `[model]`; required unless `stiffness_nm_per_rad` is given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub parameters: Option<Vec<ParameterStiffness>>,
    /// Optional, with `parameters`: the covariance `Cov(h)` of the compliance `h = 1/k` of every
    /// parameter, SI (rad/Nm, m/N), row-major n x n; finite, symmetric, non-negative diagonal.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub compliance_covariance_si: Option<Vec<Vec<f64>>>,
    /// The six drives alone (without `parameters`): the joint stiffness `k_i`, Nm/rad, joints
    /// 1..6; each within [`limits::STIFFNESS_NM_PER_RAD`].
    #[cfg_attr(
        feature = "schema",
        schemars(
            description = "The six drives alone (without `parameters`): the joint stiffness `k_i`, Nm/rad, joints 1..6.",
            inner(range(min = STIFFNESS_NM_PER_RAD.min, max = STIFFNESS_NM_PER_RAD.max))
        )
    )]
    #[serde(
        default,
        deserialize_with = "stiffness",
        skip_serializing_if = "Option::is_none"
    )]
    pub stiffness_nm_per_rad: Option<[f64; 6]>,
    /// Optional, with `stiffness_nm_per_rad`: the covariance `Cov(h)` of the compliance
    /// `h_i = 1/k_i`, (rad/Nm)^2, row-major 6x6 (paper eq. 12); finite, symmetric, non-negative
    /// diagonal.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[serde(deserialize_with = "crate::common::exact::option_matrix")]
    pub compliance_covariance_rad2_per_nm2: Option<[[f64; 6]; 6]>,
    /// Optional, with `parameters`, ignored by the readers: which parameters a calibration
    /// fitted (the others are the setup's nominal), as `calibrate --stiffness-out` writes it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fitted: Option<Vec<bool>>,
    /// Optional, with `parameters`: the held-out residuals of a cross-validation over postures,
    /// what prediction intervals are built from.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub prediction: Option<PredictionSection>,
    /// Optional, with `parameters`: the combinations of parameters the data could not separate,
    /// written out (as `identify` writes them; read for the error about an unidentified
    /// parameter).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unidentifiable: Option<Vec<String>>,
    /// Optional: the robot's own weight as `stiffid calibrate --gravity` fitted it (the
    /// calibrated robot is the robot without its sag; `compensate` adds the sag).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gravity: Option<GravitySection>,
    /// Optional: the region of axis angles the stiffness was identified from (as `identify`
    /// and `calibrate --stiffness-out` write it); `predict`, `validate` and `compensate` flag a
    /// posture outside it. A file without it is read, and nothing is checked (said once).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub region: Option<RegionSection>,
    /// Optional: the models the data support and their resampled parameter sets (as `identify
    /// --compare-models --bootstrap N --stiffness-out` writes them); `compensate`'s model-form
    /// part. A file without it is read, and the part is absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub model_form: Option<ModelFormSection>,
}

/// What wrote a stiffness file ([`StiffnessFile::kind`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "kebab-case")]
pub enum FileKind {
    /// A stiffness file (`calibrate --stiffness-out`, `identify --stiffness-out`).
    Stiffness,
    /// The document of `identify` over the six drives.
    IdentifyDrives,
    /// The document of `identify` over a model with virtual springs.
    IdentifySprings,
}

/// One parameter's stiffness in a stiffness file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct ParameterStiffness {
    /// `k1` .. `k6` for the drives, the virtual spring's name otherwise.
    pub name: String,
    /// `drive`, `rotation` or `translation`.
    pub kind: ParameterKind,
    /// `Nm/rad` (drives, rotations) or `N/mm` (translations).
    pub unit: String,
    /// The stiffness in `unit`; `null` (infinitely stiff, as a non-negative fit writes a
    /// compliance at its bound) is refused by the readers.
    pub stiffness: Option<f64>,
    /// Optional: `false` when the data could not separate the parameter from others (as
    /// `identify` writes it over a model); such a file is refused by
    /// [`StiffnessFile::compliance`]. Absent: identified.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub identified: Option<bool>,
    /// Optional, ignored: the 95% interval `identify` writes beside the stiffness, in `unit`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ci95: Option<[Option<f64>; 2]>,
}

/// Six stiffness values, exactly; a `null` (an infinitely stiff joint, as `identify
/// --nonnegative` writes a compliance at its bound) refused with what to do.
fn stiffness<'de, D: serde::Deserializer<'de>>(
    d: D,
) -> std::result::Result<Option<[f64; 6]>, D::Error> {
    let Some(k): Option<[Option<f64>; 6]> = crate::common::exact::option(d)? else {
        return Ok(None);
    };
    match k.iter().position(Option::is_none) {
        None => Ok(Some(k.map(|v| v.unwrap_or_default()))),
        Some(j) => Err(serde::de::Error::custom(null_message(
            &format!("stiffness_nm_per_rad[{}]", j + 1),
            "Nm/rad",
        ))),
    }
}

fn null_message(field: &str, unit: &str) -> String {
    format!(
        "{field} is null: an infinitely stiff spring (a non-negative fit with its compliance at the bound 0), which no prediction can use; write a finite stiffness there (a large one for a stiff spring, within the limit in {unit})"
    )
}

/// What [`parse`] expects, for errors.
const EXPECTED: &str = "JSON with the key parameters (name, kind, unit, stiffness of each) and optionally compliance_covariance_si (n x n), or stiffness_nm_per_rad (six numbers, Nm/rad) and optionally compliance_covariance_rad2_per_nm2 (6x6)";

/// Parses and checks the text of a stiffness file (a byte-order mark opening it, as editors on
/// Windows write, is skipped).
///
/// # Errors
/// [`Error::Json`] (line, column) for text that is not JSON with these keys and shapes;
/// [`Error::InvalidField`] naming the key (and index) for: neither `parameters` nor
/// `stiffness_nm_per_rad`, more than `MAX_PARAMETERS` parameters, a parameter whose unit is not
/// its kind's or whose stiffness is null or outside [`limits::STIFFNESS_NM_PER_RAD`] /
/// [`limits::STIFFNESS_N_PER_MM`], a covariance of the wrong shape or that is not finite,
/// symmetric with a non-negative diagonal (`check_covariance`).
///
/// # Examples
/// ```
/// let text = r#"{"setup": "any", "stiffness_nm_per_rad": [9.5e5, 3e6, 9e5, 2.5e5, 2e5, 1.5e5]}"#;
/// let file = stiffid_core::io::stiffness::parse(text).unwrap();
/// let model = stiffid_core::model::Model::default();
/// let c = file.compliance(&model).unwrap();
/// assert_eq!(c.h[1], 1.0 / 3e6);
/// assert!(c.covariance.is_none());
/// ```
pub fn parse(text: &str) -> Result<StiffnessFile> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let json = |e: serde_json::Error| {
        let message = e.to_string();
        let position = format!(" at line {} column {}", e.line(), e.column());
        Error::Json {
            line: e.line(),
            column: e.column(),
            message: message.strip_suffix(&position).unwrap_or(&message).into(),
            expected: EXPECTED,
        }
    };
    // Not an object: the struct's reading below says where.
    let keys: std::collections::BTreeMap<String, serde::de::IgnoredAny> =
        serde_json::from_str(text).unwrap_or_default();
    let ours = [
        "kind",
        "fitted",
        "parameters",
        "compliance_covariance_si",
        "stiffness_nm_per_rad",
        "compliance_covariance_rad2_per_nm2",
        "prediction",
        "unidentifiable",
        "gravity",
        "region",
        "model_form",
    ];
    let known =
        |k: &str| ours.contains(&k) || DOCUMENT_KEYS.contains(&k) || FORMER_KEYS.contains(&k);
    if let Some(key) = (keys.keys()).find(|k| !known(k)) {
        return Err(invalid(
            limits::short(key),
            format!("unknown key: expected {EXPECTED} (and the other keys of identify's document)"),
        ));
    }
    let file: StiffnessFile = serde_json::from_str(text).map_err(json)?;
    if let Some(g) = &file.gravity {
        g.check()?;
    }
    if let Some(r) = &file.region {
        r.check()?;
    }
    if let Some(m) = &file.model_form {
        m.check()?;
    }
    match &file.parameters {
        Some(parameters) => {
            check_parameters(parameters, &file.compliance_covariance_si)?;
            if let Some(k) = &file.stiffness_nm_per_rad {
                check_drives_agree(parameters, k)?;
            }
            if let Some(rows) = &file.compliance_covariance_rad2_per_nm2 {
                duplicates::check_covariances(parameters, &file.compliance_covariance_si, rows)?;
            }
            if let Some(p) = &file.prediction {
                p.check(&parameters.iter().map(|p| p.kind).collect::<Vec<_>>())?;
            }
        }
        None => {
            let k = file
                .stiffness_nm_per_rad
                .ok_or_else(|| Error::InvalidField {
                    field: "parameters".into(),
                    message: format!("missing: expected {EXPECTED}"),
                })?;
            limits::check("stiffness_nm_per_rad", &k, &STIFFNESS_NM_PER_RAD)?;
            if file.compliance_covariance_si.is_some() {
                return Err(invalid(
                    "compliance_covariance_si".into(),
                    "without parameters it would be ignored: the covariance of the drives alone \
                     is compliance_covariance_rad2_per_nm2 (6x6); give that, or parameters"
                        .into(),
                ));
            }
            if let Some(rows) = file.compliance_covariance_rad2_per_nm2 {
                check_covariance(&Matrix6::from_fn(|r, c| rows[r][c]))?;
            }
            if let Some(p) = &file.prediction {
                p.check(&[ParameterKind::Drive; 6])?;
            }
        }
    }
    duplicates::check_compliance(text, &file)?;
    Ok(file)
}

fn invalid(field: String, message: String) -> Error {
    Error::InvalidField { field, message }
}

/// The unit of a parameter's stiffness in a stiffness file and its range.
fn stiffness_unit(kind: ParameterKind) -> (crate::model::Unit, &'static limits::Range) {
    match kind {
        ParameterKind::Translation => (crate::model::Unit::NPerMm, &STIFFNESS_N_PER_MM),
        _ => (crate::model::Unit::NmPerRad, &STIFFNESS_NM_PER_RAD),
    }
}

/// Refuses a file whose `stiffness_nm_per_rad` (written beside `parameters` by identify) is not
/// the stiffness of its drives in `parameters`, to 1e-9: one file, one stiffness.
fn check_drives_agree(parameters: &[ParameterStiffness], k: &[f64; 6]) -> Result<()> {
    let drives = parameters.iter().filter(|p| p.kind == ParameterKind::Drive);
    for (j, (p, k)) in drives.zip(k).enumerate() {
        let theirs = p.stiffness.unwrap_or(f64::NAN);
        let agree = (k - theirs).abs() <= 1e-9 * theirs.abs();
        if !agree {
            return Err(invalid(
                format!("stiffness_nm_per_rad[{}]", j + 1),
                format!(
                    "{} where parameters gives {} '{}' {}: the file contradicts itself; keep one",
                    crate::common::words::number(*k),
                    p.kind.name(),
                    limits::short(&p.name),
                    crate::common::words::number(theirs)
                ),
            ));
        }
    }
    Ok(())
}

fn check_parameters(parameters: &[ParameterStiffness], cov: &Option<Vec<Vec<f64>>>) -> Result<()> {
    limits::check_count("parameters", parameters.len(), 6, MAX_PARAMETERS)?;
    for (i, p) in parameters.iter().enumerate() {
        let field = format!("parameters[{}]", i + 1);
        let (unit, range) = stiffness_unit(p.kind);
        let unit = unit.symbol();
        if p.unit != unit {
            return Err(invalid(
                format!("{field}.unit"),
                format!(
                    "'{}' for the {} '{}': expected '{unit}'",
                    limits::short(&p.unit),
                    p.kind.name(),
                    limits::short(&p.name)
                ),
            ));
        }
        let Some(k) = p.stiffness else {
            return Err(invalid(
                format!("{field}.stiffness"),
                null_message(&format!("the stiffness of '{}'", p.name), unit),
            ));
        };
        limits::check(&format!("{field}.stiffness"), &[k], range)?;
    }
    let Some(rows) = cov else { return Ok(()) };
    let n = parameters.len();
    if rows.len() != n || rows.iter().any(|r| r.len() != n) {
        return Err(invalid(
            "compliance_covariance_si".into(),
            format!("expected {n} rows of {n} numbers, one per parameter"),
        ));
    }
    check_covariance_of(
        &DMatrix::from_fn(n, n, |r, c| rows[r][c]),
        "compliance_covariance_si",
    )
}

impl StiffnessFile {
    /// The compliance of every parameter (SI) and its covariance, checked against `model`: the
    /// file's parameters must be the model's, in order (name and kind); a file of the six drives
    /// alone fits only a model of the drives alone.
    ///
    /// # Errors
    /// [`Error::InvalidField`] naming the first parameter that differs (`parameters[7]`), or
    /// `parameters` when the counts differ or the file has the drives alone.
    pub fn compliance(&self, model: &Model) -> Result<Compliance> {
        let Some(parameters) = &self.parameters else {
            return self.drives_compliance(model);
        };
        let expected = model.parameters();
        let names = |v: Vec<String>| v.join(", ");
        if parameters.len() != expected.len() {
            return Err(invalid(
                "parameters".into(),
                format!(
                    "the file has {} parameters ({}) but the setup's model has {} ({}): use the setup the file was identified with, or identify again with this one",
                    parameters.len(),
                    names(parameters.iter().map(|p| limits::short(&p.name)).collect()),
                    expected.len(),
                    names(expected.into_iter().map(|p| p.name).collect())
                ),
            ));
        }
        for (i, (p, e)) in parameters.iter().zip(&expected).enumerate() {
            if p.name != e.name || p.kind != e.kind {
                return Err(invalid(
                    format!("parameters[{}]", i + 1),
                    format!(
                        "'{}' ({}) where the setup's model has '{}' ({}): use the setup the file was identified with, or identify again with this one",
                        limits::short(&p.name),
                        p.kind.name(),
                        e.name,
                        e.kind.name()
                    ),
                ));
            }
        }
        let unidentified: Vec<String> = (parameters.iter())
            .filter(|p| p.identified == Some(false))
            .map(|p| format!("'{}'", limits::short(&p.name)))
            .collect();
        if let Some(i) = parameters.iter().position(|p| p.identified == Some(false)) {
            let combinations = match self.unidentifiable.as_deref().unwrap_or_default() {
                [] => String::new(),
                c => format!(" (the data cannot separate {})", c.join("; ")),
            };
            return Err(invalid(
                format!("parameters[{}].identified", i + 1),
                format!(
                    "false: identify could not identify {}{combinations}; its stiffness is one of infinitely many that fit the data, and a prediction with it would carry a standard deviation that means nothing: measure postures that load these parameters differently and identify again, or leave the virtual springs concerned out of the setup's [model]",
                    unidentified.join(", ")
                ),
            ));
        }
        let h = parameters
            .iter()
            .zip(&expected)
            .map(|(p, e)| e.unit.per_si() / p.stiffness.unwrap_or(f64::NAN));
        let n = parameters.len();
        Ok(Compliance {
            h: nalgebra::DVector::from_iterator(n, h),
            covariance: self
                .compliance_covariance_si
                .as_ref()
                .map(|rows| DMatrix::from_fn(n, n, |r, c| rows[r][c])),
            prediction: self.prediction.as_ref().map(PredictionSection::calibration),
            own_weight: self.gravity.as_ref().map(GravitySection::own_weight),
            region: self.region(),
            model_form: self.model_form(model)?,
        })
    }

    /// The models of its `model_form`, the drives in `model`'s coordinates.
    fn model_form(&self, model: &Model) -> Result<Option<crate::model::ModelForm>> {
        (self.model_form.as_ref())
            .map(|m| m.form(model.coordinates()))
            .transpose()
    }

    /// The region of its identification postures: [`Region::Unrecorded`] when the file does
    /// not record it.
    fn region(&self) -> Region {
        match &self.region {
            Some(r) => Region::Postures(r.range()),
            None => Region::Unrecorded,
        }
    }

    /// The compliance of a file of the six drives alone.
    fn drives_compliance(&self, model: &Model) -> Result<Compliance> {
        if !model.is_drives_only() {
            let springs: Vec<&str> = model.springs().iter().map(|s| s.name.as_str()).collect();
            return Err(invalid(
                "parameters".into(),
                format!(
                    "missing: the file holds the six drives alone (stiffness_nm_per_rad) but the setup's model also has the virtual springs {}: identify with this setup (its stiffness file names every parameter)",
                    springs.join(", ")
                ),
            ));
        }
        let k = Vector6::from(self.stiffness_nm_per_rad.unwrap_or([f64::NAN; 6]));
        let cov = self
            .compliance_covariance_rad2_per_nm2
            .map(|rows| Matrix6::from_fn(|r, c| rows[r][c]));
        Ok(Compliance {
            own_weight: self.gravity.as_ref().map(GravitySection::own_weight),
            region: self.region(),
            model_form: self.model_form(model)?,
            ..Compliance::drives(k.map(|v| 1.0 / v), cov)
        })
    }
}
