//! The stiffness file's optional `model_form`: the models the data support and their resampled
//! parameter sets, from the posture bootstrap of the model comparison (`stiffid identify
//! --compare-models --bootstrap N --stiffness-out`), read into a [`ModelForm`] for compensation's
//! error budget.
//!
//! ```json
//! "model_form": {"resamples": 200, "seed": 1,
//!   "springs": [{"name": "tilt3_x", "kind": "rotation", "law": "linear", "link": 3,
//!                "axis": [1, 0, 0], "point_mm": [0, 0, 0]}, ...],
//!   "models": [{"springs": ["tilt3_x"], "compliance_si": [[...7 numbers...], ...]}, ...]}
//! ```

use super::invalid;
use crate::common::limits;
use crate::model::{unit_axis, FormModel, Kind, Law, Model, ModelForm, Spring};
use crate::robot::kinematics::Coordinates;
use crate::Result;
use nalgebra::{DVector, Vector3};
use serde::{Deserialize, Serialize};

/// The most parameter sets a `model_form` holds: every supported model of every resample of the
/// largest bootstrap ([`limits::MAX_BOOTSTRAP`]), ten models each.
pub(crate) const MAX_MODEL_FORM_SETS: usize = 20_000;

/// The largest magnitude of a parameter set's value (SI: rad/Nm for a drive or a rotation
/// spring, m/N for a translation, rad/Nm^2 for a load-dependent law): a stiffness of 1 Nm/rad,
/// 1e-3 N/mm, softer than any robot's ([`limits::STIFFNESS_NM_PER_RAD`]).
pub(crate) const MAX_COMPLIANCE_SI: f64 = 1.0;

/// The models the data support and their resampled parameter sets (module docs).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct ModelFormSection {
    /// The bootstrap's resamples.
    pub resamples: u64,
    /// The seed of its draws.
    pub seed: u64,
    /// Every virtual spring the models hold, defined in full (so the file does not depend on a
    /// setup's families or candidates).
    pub springs: Vec<FormSpring>,
    /// The models, each with the parameter sets of the resamples that support it; at most 20 000
    /// sets in all.
    pub models: Vec<FormModelSection>,
    /// The comparison's recommended model fitted to every posture: one parameter set (its
    /// springs among `springs`); absent in files written before it was.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub recommended: Option<FormModelSection>,
}

/// A virtual spring of a `model_form` model, as a setup's `[[model.spring]]` gives it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct FormSpring {
    /// Its name.
    pub name: String,
    /// `rotation` or `translation`.
    pub kind: Kind,
    /// `linear` (a spring), `lost-motion` or `load-dependent` ([`Law`]).
    pub law: FormLaw,
    /// The body it is fixed in: 0 the base, 1..6 the link after joint k.
    pub link: usize,
    /// The axis (rotation) or direction (translation) in link `link`'s frame; finite, non-zero.
    pub axis: [f64; 3],
    /// A point of the rotation axis in the link's frame, mm (0 for a translation).
    pub point_mm: [f64; 3],
}

/// The law of a `model_form` spring.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "kebab-case")]
pub enum FormLaw {
    /// A spring.
    Linear,
    /// A lost motion, smoothed over [`crate::model::DEFAULT_SMOOTHING`].
    LostMotion,
    /// A load-dependent compliance.
    LoadDependent,
}

/// One supported model and its parameter sets.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct FormModelSection {
    /// Its virtual springs by name (among `springs`), after the six drives.
    pub springs: Vec<String>,
    /// Its parameter sets, one per resample that supports it: the compliance-side value of every
    /// parameter, drives first, SI (rad/Nm, m/N; a lost motion rad or m, a load-dependent
    /// compliance rad/Nm^2); finite.
    pub compliance_si: Vec<Vec<f64>>,
}

impl FormSpring {
    /// The section's spring of `s`.
    pub fn new(s: &Spring) -> Self {
        Self {
            name: s.name.clone(),
            kind: s.kind,
            law: match s.law {
                Law::Linear => FormLaw::Linear,
                Law::LostMotion { .. } => FormLaw::LostMotion,
                Law::LoadDependent => FormLaw::LoadDependent,
            },
            link: s.link,
            axis: s.axis.into_inner().into(),
            point_mm: (s.point * 1e3).into(),
        }
    }

    fn spring(&self, field: &str) -> Result<Spring> {
        Ok(Spring {
            name: self.name.clone(),
            kind: self.kind,
            link: self.link,
            axis: unit_axis(Vector3::from(self.axis), &format!("{field}.axis"))?,
            point: Vector3::from(self.point_mm) * 1e-3,
            nominal_stiffness: None,
            law: match self.law {
                FormLaw::Linear => Law::Linear,
                FormLaw::LostMotion => Law::LostMotion {
                    smoothing: crate::model::DEFAULT_SMOOTHING,
                },
                FormLaw::LoadDependent => Law::LoadDependent,
            },
        })
    }
}

impl ModelFormSection {
    /// Checks it as [`ModelFormSection::form`] reads it.
    ///
    /// # Errors
    /// Those of [`ModelFormSection::form`].
    pub(super) fn check(&self) -> Result<()> {
        self.form(Coordinates::Axis).map(|_| ())
    }

    /// The models and sets, the drives in `coordinates` (the setup's).
    ///
    /// # Errors
    /// [`crate::Error::InvalidField`] naming the field (`model_form.models[2].compliance_si[4]`):
    /// more than [`MAX_MODEL_FORM_SETS`] sets, a spring that is not one (as a setup's
    /// `[model]` checks it) or is not among `springs`, a set without one finite value per
    /// parameter or with a value beyond [`MAX_COMPLIANCE_SI`].
    pub(crate) fn form(&self, coordinates: Coordinates) -> Result<ModelForm> {
        let sets: usize = self.models.iter().map(|m| m.compliance_si.len()).sum();
        limits::check_count("model_form.compliance_si", sets, 0, MAX_MODEL_FORM_SETS)?;
        let springs = (self.springs.iter().enumerate())
            .map(|(i, s)| s.spring(&format!("model_form.springs[{}]", i + 1)))
            .collect::<Result<Vec<_>>>()?;
        Model::new(coordinates, springs.clone())?;
        let models = (self.models.iter().enumerate())
            .map(|(i, m)| {
                m.model(
                    &format!("model_form.models[{}]", i + 1),
                    &springs,
                    coordinates,
                )
            })
            .collect::<Result<Vec<_>>>()?;
        let recommended = (self.recommended.as_ref())
            .map(|m| m.model("model_form.recommended", &springs, coordinates))
            .transpose()?;
        if let Some(r) = recommended.as_ref().filter(|r| r.sets.len() != 1) {
            return Err(invalid(
                "model_form.recommended.compliance_si".into(),
                format!("expected one parameter set, found {}", r.sets.len()),
            ));
        }
        Ok(ModelForm {
            models,
            recommended,
        })
    }
}

impl FormModelSection {
    /// The model named `field` and its sets, its springs among `springs`.
    fn model(
        &self,
        field: &str,
        springs: &[Spring],
        coordinates: Coordinates,
    ) -> Result<FormModel> {
        let own = (self.springs.iter())
            .map(|name| {
                springs
                    .iter()
                    .find(|s| &s.name == name)
                    .cloned()
                    .ok_or_else(|| {
                        invalid(
                            format!("{field}.springs"),
                            format!("'{}' is not among model_form.springs", limits::short(name)),
                        )
                    })
            })
            .collect::<Result<Vec<_>>>()?;
        let model = Model::new(coordinates, own)?;
        let sets = (self.compliance_si.iter().enumerate())
            .map(|(k, h)| match h.len() == model.len() && h.iter().all(|v| v.abs() <= MAX_COMPLIANCE_SI) {
                true => Ok(DVector::from_column_slice(h)),
                false => Err(invalid(
                    format!("{field}.compliance_si[{}]", k + 1),
                    format!("expected {} finite values of magnitude at most {MAX_COMPLIANCE_SI} (rad/Nm, m/N, rad/Nm^2), the six drives' then the springs' in order", model.len()),
                )),
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(FormModel { model, sets })
    }
}
