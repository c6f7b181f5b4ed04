//! The document of the robot calibration job ([`crate::app::calibrate`]): `stiffid
//! calibrate --json`, Python's `calibrate(...)`.

use super::{Held, Report};
use crate::app::document::parameters::stiffness;
use crate::app::document::{finite, units};
use crate::app::Warning;
use nalgebra::Vector3;
use serde::Serialize;
use stiffid_core::common::choice::Choice;
use stiffid_core::io::readings::point_name;
use stiffid_core::io::stiffness::{FileKind, StiffnessFile};
use stiffid_metrology::calibration::error_model::Target;
use stiffid_metrology::calibration::gravity::Gravity;
use stiffid_metrology::calibration::identifiability::CORRELATION_INSEPARABLE;
use stiffid_view as scene;

use super::held_document::label;
pub use super::held_document::{
    held, IntervalsDocument, OutsideRange, PointError, ValidationDocument,
};
pub use super::ladder_document::{LadderDocument, RungDocument};
use super::maps_document::maps_document;
pub use super::maps_document::{MapTried, MapsDocument, MapsNested};

/// The robot calibration: every parameter with its value and standard deviation, what the
/// readings determine, the residual and held-out errors, the calibrated robot's files.
///
/// A view of the report ([`Report::document`]), built as it is written: its lengths and angles
/// are the report's, in SI, written in the units their keys name by the unit adapters
/// ([`units`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "calibrate")]
#[cfg_attr(
    feature = "schema",
    schemars(
        description = "The robot calibration: every parameter with its value and standard deviation, what the\nreadings determine, the residual and held-out errors, the calibrated robot's files."
    )
)]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("calibrate")))]
pub struct Document<'a> {
    /// The setup as given.
    pub setup: &'a str,
    /// The readings file.
    pub data: &'a str,
    /// The joint errors fitted: `none`, `offsets` or `full`.
    pub geometry: &'static str,
    /// The gravity terms fitted: `none`, `arm`, `masses`, `lumped` or `lumped-links` (with `--gravity
    /// auto`, the ladder's choice).
    pub gravity: &'static str,
    /// With gravity terms: their bound, the prior standard deviation of each term's deflection at
    /// the largest torque it meets within the robot's joint limits (what holds a term the readings
    /// do not determine at its nominal value; `--gravity-bound-mrad`, the same for every gravity
    /// model, chosen by the ladder or given): rad, written in mrad; `null` without gravity terms.
    #[serde(rename = "gravity_prior_mrad", serialize_with = "units::mrad_option")]
    pub gravity_prior: Option<f64>,
    /// The frame of the readings: `tracker` or `base`.
    pub measured_in: &'static str,
    /// Readings fitted: the unloaded, and the loaded ones with load steps.
    pub readings: usize,
    /// Every parameter of the error model, in the Jacobian's column order.
    pub parameters: Vec<Parameter>,
    /// The parameters the readings do not separate from the identified ones (left nominal).
    pub merged: Vec<Merged>,
    /// With `--update`: the parameters held at the calibration's values, in the forward model
    /// and out of the fit (the measuring points without `tool` in the list, the gravity terms of
    /// the calibration's stiffness file without `gravity`); empty otherwise.
    pub held: Vec<String>,
    /// The identified parameters' count: the rank of the identification Jacobian.
    pub rank: usize,
    /// The condition number of the identified columns of the column-scaled identification
    /// Jacobian; `null` when nothing is identified.
    pub condition: Option<f64>,
    /// Pairs of identified parameters correlated above 0.9 in absolute value.
    pub correlations: Vec<Correlation>,
    /// RMS of the fitted readings' 3D residuals: m, written in mm.
    #[serde(rename = "residual_rms_mm", serialize_with = "units::mm")]
    pub residual_rms: f64,
    /// The same with the nominal robot, the tracker registered (readings in the tracker's frame; in
    /// the base frame nothing is registered) and the setup's measuring points: m, written in mm;
    /// where the calibration starts.
    #[serde(rename = "nominal_rms_mm", serialize_with = "units::mm")]
    pub nominal_rms: f64,
    /// Noise per coordinate estimated from the residuals: m, written in mm.
    #[serde(rename = "noise_std_mm", serialize_with = "units::mm")]
    pub noise_std: f64,
    /// `noise_std_mm` over the setup's tracker noise: about 1 when the model explains the
    /// readings to the noise; `null` without a noise.
    pub noise_ratio: Option<f64>,
    /// Levenberg-Marquardt iterations.
    pub iterations: usize,
    /// Why the iterations stopped: `converged`, `stalled`, `damping-exhausted` (a minimum within
    /// rounding) or `iteration-limit` (not converged; a warning says so).
    pub stop_reason: stiffid_core::common::stop::Stop,
    /// Every reading's 3D position error before the calibration (the nominal robot, the tracker
    /// registered on the same readings, the setup's measuring points) and after it: the fitted
    /// readings (`set` `fitted`), then the held-out ones (`validation`, `--validate`), then each
    /// posture predicted by the fit of the others (`cross-validation`, `--cross-validate`).
    pub errors: Vec<BeforeAfter<'a>>,
    /// Each fitted posture (the first [`scene::MAX_POSTURES`]): its label, axis angles and
    /// external axes' values, in the order of the readings; what the scene draws
    /// ([`super::scene`]).
    pub postures: Vec<scene::stance::Stance>,
    /// The joint error maps: what was asked, the choice by cross-validation inside the fitted
    /// readings and its held-out gain by an outer cross-validation around the choice.
    pub maps: MapsDocument,
    /// With `--gravity auto` or `--maps auto`: the models tried (the gravity models without and
    /// with the maps), each one's held-out error over groups of postures, and the one fitted;
    /// `null` when the model was given.
    pub ladder: Option<LadderDocument>,
    /// With `--update`: the check readings' errors with the calibrated robot before the update
    /// against the calibration's held-out error bound, and whether it drifted beyond them;
    /// `null` otherwise, or without `[held_out]` in the robot file.
    pub check: Option<&'a super::drift::Check>,
    /// The held-out readings' errors (`--validate`), if asked.
    pub validation: Option<ValidationDocument<'a>>,
    /// The leave-one-posture-out errors (`--cross-validate`), if asked.
    pub cross_validation: Option<ValidationDocument<'a>>,
    /// The calibrated robot as a robot TOML file; `null` when it cannot be one:
    /// `robot_file_error` says why.
    pub robot_file: Option<&'a str>,
    /// Why there is no robot file.
    pub robot_file_error: Option<&'a str>,
    /// The calibrated robot as a URDF, taking the robot file's axis angles; `null` when it
    /// cannot be one (an axis map that couples or scales axes): `urdf_error` says why.
    pub urdf: Option<&'a str>,
    /// Why there is no URDF.
    pub urdf_error: Option<&'a str>,
    /// The setup fragment: the tracker's registration, the measuring points and the corrected
    /// TCP.
    pub fragment: &'a str,
    /// With the setup's `[tool] tcp_mm`: the TCP moved with the fitted measuring points (what
    /// merges into them, joint 6's `theta` and `d` and the flange's errors, moves the tool), flange
    /// frame: m, written in mm; the `tcp_mm` to use with the calibrated robot.
    #[serde(
        rename = "tcp_mm",
        serialize_with = "units::mm3_option",
        skip_serializing_if = "Option::is_none"
    )]
    #[cfg_attr(feature = "schema", schemars(with = "Option<[f64; 3]>"))]
    pub tcp: Option<Vector3<f64>>,
    /// With loaded readings (load steps) or `gravity` `masses`: the stiffness of every
    /// parameter of the setup's model, as a stiffness file holds it (what `calibrate
    /// --stiffness-out` writes, `predict` and `compensate --stiffness` read); the fitted
    /// parameters at their fitted compliance, the others at the setup's nominal stiffness with
    /// zero variance; `null` otherwise.
    pub stiffness_file: Option<StiffnessFile>,
    /// Why there is no stiffness file with loaded readings or `masses`.
    pub stiffness_file_error: Option<&'a str>,
    /// Results to look at before trusting the calibration.
    pub warnings: &'a [Warning],
}

/// One parameter.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Parameter {
    /// Its name (`tracker.x`, `point1.z`, `joint3.beta`, `gravity.c2`, ...).
    pub name: String,
    /// `tracker`, `base`, `point`, `joint`, `compliance`, `gravity`, `map`, `carrier` (a
    /// track's direction and error motions), `positioner` (its axes' lines and offsets) or
    /// `table` (a reflector on the positioner's table).
    pub kind: &'static str,
    /// The unit of `nominal`, `value` and `sd`.
    pub unit: &'static str,
    /// The nominal value (the frame's: registered on the nominal robot; a frame's rotation is
    /// its rotation vector's component).
    pub nominal: f64,
    /// The fitted value (nominal when merged).
    pub value: f64,
    /// Its standard deviation; `null` when not fitted.
    pub sd: Option<f64>,
    /// Whether the readings determine it (fitted).
    pub identified: bool,
    /// The fitted parameters its estimate is correlated with beyond
    /// [`CORRELATION_INSEPARABLE`] in absolute value: not separately identifiable, the readings
    /// determine only a combination of them, so `sd` alone means nothing; empty otherwise.
    pub inseparable_from: Vec<String>,
    /// For a gravity term, the value the calibrated robot file's `[gravity]` table states for
    /// it under the same name: SI (`value_si`, `value` times 1e-6) and a lumped first moment
    /// (`mx`, `my`, `mz`) in the link frames of the file's DH table, which may be turned from
    /// the fit's (so its components differ from `value`'s); `null` for other parameters and
    /// without a robot file.
    pub robot_file_si: Option<f64>,
}

/// A merged parameter.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Merged {
    /// Its name.
    pub name: String,
    /// The identified parameters its effect is a combination of, largest share first; empty
    /// when it has no effect at all.
    pub into: Vec<String>,
    /// Why, in words.
    pub reason: String,
}

/// One reading's error before and after the calibration.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct BeforeAfter<'a> {
    /// `fitted`, `validation` (held out) or `cross-validation` (held out by the fit of the other
    /// postures).
    pub set: &'static str,
    /// The posture's label.
    pub posture: &'a str,
    /// The measuring point (1-based), or the table reflector's number (`point_name`).
    pub point: usize,
    /// The point as the readings name it: `1`, `2`, ... a measuring point of the tool (`point`),
    /// `T1`, `T2`, ... a reflector on the positioner's table (numbered apart from the tool's).
    pub point_name: String,
    /// Predicted minus read with the nominal robot, base frame: m, written in mm.
    #[serde(rename = "before_mm", serialize_with = "units::mm3")]
    #[cfg_attr(feature = "schema", schemars(with = "[f64; 3]"))]
    pub before: Vector3<f64>,
    /// Predicted minus read with the calibration, base frame: m, written in mm.
    #[serde(rename = "after_mm", serialize_with = "units::mm3")]
    #[cfg_attr(feature = "schema", schemars(with = "[f64; 3]"))]
    pub after: Vector3<f64>,
    /// The length of `before_mm`: m, written in mm.
    #[serde(rename = "before_norm_mm", serialize_with = "units::mm")]
    pub before_norm: f64,
    /// The length of `after_mm`: m, written in mm.
    #[serde(rename = "after_norm_mm", serialize_with = "units::mm")]
    pub after_norm: f64,
}

/// Two correlated parameters.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Correlation {
    /// The first's name.
    pub a: String,
    /// The second's name.
    pub b: String,
    /// Their correlation coefficient.
    pub rho: f64,
}

impl<'a> Document<'a> {
    /// The document of `report` ([`Report::document`]).
    pub(crate) fn new(report: &'a Report) -> Self {
        let model = &report.model;
        let fit = &report.fit;
        let params = model.parameters();
        let id = &fit.identifiability;
        let parameters = parameters(report);
        let merged = merged(report);
        let correlations = (id.correlations.iter())
            .map(|(a, b, rho)| Correlation {
                a: params[*a].name.clone(),
                b: params[*b].name.clone(),
                rho: *rho,
            })
            .collect();
        Document {
            setup: &report.setup,
            data: &report.data_name,
            geometry: Choice::name(report.geometry),
            gravity: Choice::name(report.gravity),
            gravity_prior: (report.gravity != Gravity::None).then_some(report.gravity_bound),
            measured_in: match model.measured_in() {
                stiffid_metrology::calibration::error_model::MeasuredIn::Tracker => "tracker",
                stiffid_metrology::calibration::error_model::MeasuredIn::Base => "base",
            },
            readings: report.readings,
            parameters,
            merged,
            held: (model.held().iter())
                .map(|&c| params[c].name.clone())
                .collect(),
            rank: id.rank,
            condition: finite(id.condition),
            correlations,
            residual_rms: fit.rms,
            nominal_rms: report.nominal.rms,
            noise_std: fit.sigma,
            noise_ratio: finite(report.noise_ratio),
            iterations: fit.iterations,
            stop_reason: fit.stop,
            errors: before_after(report),
            postures: (report
                .labels
                .iter()
                .zip(&report.postures)
                .zip(&report.external))
            .take(scene::MAX_POSTURES)
            .map(|((l, q), e)| {
                scene::stance::Stance::new(report.model.robot().external(), l.clone(), q, e)
            })
            .collect(),
            maps: maps_document(&report.maps),
            ladder: report.ladder.as_ref().map(LadderDocument::new),
            check: report.check.as_ref(),
            validation: report.validation.as_ref().map(held),
            cross_validation: report.cross_validation.as_ref().map(held),
            robot_file: report.robot_toml.as_deref().ok(),
            robot_file_error: report.robot_toml.as_ref().err().map(String::as_str),
            urdf: report.urdf.as_deref().ok(),
            urdf_error: report.urdf.as_ref().err().map(String::as_str),
            fragment: &report.fragment,
            tcp: report.tcp,
            stiffness_file: stiffness_section(report),
            stiffness_file_error: match &report.compliance {
                Some(Err(e)) => Some(e),
                _ => None,
            },
            warnings: &report.warnings,
        }
    }
}

/// Every parameter of `report`'s model with its value and standard deviation, in the
/// document's units (the frame's from the start's registration).
fn parameters(report: &Report) -> Vec<Parameter> {
    let fit = &report.fit;
    let values = &fit.estimate.values;
    let frame_values = frame_vector(&fit.estimate.frame);
    let start = frame_vector(&report.start_frame);
    let params = report.model.parameters();
    let in_file = gravity_in_file(report);
    let inseparable = |c: usize| -> Vec<String> {
        (fit.identifiability.correlations.iter())
            .filter(|(_, _, rho)| rho.abs() > CORRELATION_INSEPARABLE)
            .filter_map(|&(a, b, _)| match (a == c, b == c) {
                (true, _) => Some(params[b].name.clone()),
                (_, true) => Some(params[a].name.clone()),
                _ => None,
            })
            .collect()
    };
    (params.iter().enumerate())
        .map(|(c, p)| {
            let f = p.document_factor();
            let (nominal, value) = match p.target {
                Target::Frame(i) => (start[i] * f, frame_values[i] * f),
                _ => (p.nominal * f, values[c] * f),
            };
            Parameter {
                name: p.name.clone(),
                kind: p.kind.name(),
                unit: p.unit(),
                nominal,
                value,
                sd: fit.sd[c].map(|s| s * f),
                identified: fit.fitted.contains(&c),
                inseparable_from: inseparable(c),
                robot_file_si: (in_file.iter())
                    .find(|(n, _)| *n == p.name)
                    .map(|(_, v)| *v),
            }
        })
        .collect()
}

/// The gravity terms the calibrated robot file states (`[gravity]`: name and SI value, in its
/// table's link frames), empty without a robot file or gravity.
fn gravity_in_file(report: &Report) -> Vec<(String, f64)> {
    let file = (report.robot_toml.as_ref().ok())
        .and_then(|t| stiffid_core::robot::file::parse(t, "the calibrated robot file").ok());
    (file.as_ref().and_then(|r| r.own_weight())).map_or(Vec::new(), |w| w.terms.clone())
}

/// The parameters the readings do not separate from the identified ones, with what absorbs
/// them and why.
fn merged(report: &Report) -> Vec<Merged> {
    let (model, fit) = (&report.model, &report.fit);
    let params = model.parameters();
    (fit.identifiability.merged.iter())
        .filter(|m| !fit.fitted.contains(&m.parameter) && !model.held().contains(&m.parameter))
        .map(|m| {
            let into: Vec<String> = m.into.iter().map(|(k, _)| params[*k].name.clone()).collect();
            let reason = match (into.is_empty(), model.merged_words(m.parameter)) {
                (true, _) => "no effect on the readings at these postures".to_string(),
                (false, None) => format!(
                    "its effect is a combination of {} at these postures: left nominal, absorbed by them",
                    into.join(", ")
                ),
                (false, Some(words)) => format!(
                    "{words}; its effect is a combination of {} at these postures: left nominal, absorbed by them",
                    into.join(", ")
                ),
            };
            Merged {
                name: params[m.parameter].name.clone(),
                into,
                reason,
            }
        })
        .collect()
}

/// The fitted compliance as a stiffness file, when there is one.
fn stiffness_section(report: &Report) -> Option<StiffnessFile> {
    let Some(Ok(c)) = &report.compliance else {
        return None;
    };
    Some(StiffnessFile {
        kind: Some(FileKind::Stiffness),
        parameters: Some(stiffness(&c.parameters, &c.h)),
        compliance_covariance_si: Some(
            (c.covariance.row_iter())
                .map(|r| r.iter().copied().collect())
                .collect(),
        ),
        fitted: Some(c.fitted.clone()),
        region: stiffid_core::model::PostureRange::of(&report.postures)
            .map(|r| stiffid_core::io::stiffness::RegionSection::new(&r)),
        ..StiffnessFile::default()
    })
}

impl Document<'_> {
    /// The text of the calibrated robot file (`stiffid calibrate --out`, Python's `out=`): the
    /// robot TOML with the setup's tracker and measuring points from this calibration in comments
    /// at its end; `None` when there is no robot file (`robot_file_error` says why).
    pub fn robot_file_out(&self) -> Option<String> {
        let text = self.robot_file?;
        let fragment: String = (self.fragment.lines())
            .map(|l| format!("# {}\n", l.trim_start_matches("# ")))
            .collect();
        let note = "\n# The setup's tracker and measuring points from this calibration:\n";
        Some(format!("{text}{note}{fragment}"))
    }

    /// The text of the stiffness file (`stiffid calibrate --stiffness-out`, Python's
    /// `stiffness_out=`): `stiffness_file` as pretty JSON; `None` when there is none
    /// (`stiffness_file_error` says why, or no compliance is fitted: neither loaded readings nor a
    /// gravity model).
    pub fn stiffness_file_out(&self) -> Option<String> {
        serde_json::to_string_pretty(self.stiffness_file.as_ref()?).ok()
    }
}

/// A frame's translation (m) and rotation vector (rad).
fn frame_vector(t: &nalgebra::Isometry3<f64>) -> [f64; 6] {
    let (p, r) = (t.translation.vector, t.rotation.scaled_axis());
    [p.x, p.y, p.z, r.x, r.y, r.z]
}

/// Every reading's error before and after ([`Document::errors`]).
fn before_after(report: &Report) -> Vec<BeforeAfter<'_>> {
    let sets = [
        (
            "fitted",
            Some((&report.nominal, &report.calibrated, &report.labels)),
        ),
        (
            "validation",
            report
                .validation
                .as_ref()
                .map(|h| (&h.nominal, &h.calibrated, &h.labels)),
        ),
        (
            "cross-validation",
            report
                .cross_validation
                .as_ref()
                .map(|h| (&h.nominal, &h.calibrated, &h.labels)),
        ),
    ];
    let mut all = Vec::new();
    for (set, held) in sets {
        let Some((before, after, labels)) = held else {
            continue;
        };
        all.extend(
            before
                .errors
                .iter()
                .zip(&after.errors)
                .map(|(b, a)| BeforeAfter {
                    set,
                    posture: label(labels, a.posture),
                    point: a.point + 1,
                    point_name: point_name(a.point, a.table),
                    before: b.error,
                    after: a.error,
                    before_norm: b.error.norm(),
                    after_norm: a.error.norm(),
                }),
        );
    }
    all
}

/// The calibrated robot file's `[held_out]` table ([`stiffid_core::robot::HeldOut`]): the lengths of
/// the held-out readings' errors (mm, shortest round-trip), those of `--validate` where given,
/// else those of `--cross-validate`; empty without either. A compensation's error budget takes
/// their quantile as the calibration's part.
pub(super) fn held_out_table(validation: Option<&Held>, cross_validation: Option<&Held>) -> String {
    let (source, held) = match (validation, cross_validation) {
        (Some(v), _) => ("validate", v),
        (None, Some(c)) => ("cross-validate", c),
        (None, None) => return String::new(),
    };
    held_out_lines(
        source,
        held.calibrated.errors.iter().map(|e| e.error.norm()),
    )
}

/// The `[held_out]` table of a robot file: the error lengths `lengths` (m) from `source`
/// (`validate` or `cross-validate`).
pub(super) fn held_out_lines(source: &str, lengths: impl Iterator<Item = f64>) -> String {
    let errors: Vec<String> = lengths.map(|e| format!("{:?}", e * 1e3)).collect();
    format!(
        "\n# The calibration's held-out position errors (|predicted - read|, mm): the error budget of\n# `stiffid compensate` takes their quantile at its level.\n[held_out]\nsource = \"{source}\"\nerrors_mm = [{}]\n",
        errors.join(", ")
    )
}
