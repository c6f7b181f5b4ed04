//! The model's form: the models the data support and their resampled parameter sets, as the
//! posture bootstrap of the model comparison gives them (`identify --compare-models --bootstrap
//! N`, `stiffid_identify::compare::bootstrap`), and the TCP translation each set predicts under
//! a wrench. Compensation's error budget takes their spread about its own prediction as the
//! model-form part (`stiffid_machining::compensate::budget`).
//!
//! A set's translation is the observation matrix's (Eq. 10-11) for its model, the law of each
//! virtual joint applied as identification applies it ([`super::Law`]): the joint deflections
//! `dq_j = h_j g_j(tau_j)` of the loads `tau = J_a^T W` (`g` the identity for a drive and a
//! spring), and the translation `J_a[0..3] dq`.

use super::Model;
use crate::robot::kinematics::Frames;
use nalgebra::{DVector, Vector3, Vector6};

/// One model the data support and its parameter sets.
#[derive(Debug, Clone, PartialEq)]
pub struct FormModel {
    /// The model: the drives in the setup's coordinates and its virtual springs.
    pub model: Model,
    /// Its parameter sets, one per resample that supports it: each the compliance-side value of
    /// every parameter, SI, drives first ([`crate::model::Compliance::h`]; a lost motion in rad
    /// or m, a load-dependent compliance in rad/Nm^2).
    pub sets: Vec<DVector<f64>>,
}

/// The models the data support and their resampled parameter sets (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct ModelForm {
    /// The models, each with its sets.
    pub models: Vec<FormModel>,
    /// The comparison's recommended model fitted to every posture (one set), when the file
    /// carries it: what a compensation sets beside the file's own model to say whether the two
    /// rank the path's postures alike.
    pub recommended: Option<FormModel>,
}

impl ModelForm {
    /// The number of parameter sets over every model.
    pub(crate) fn sets(&self) -> usize {
        self.models.iter().map(|m| m.sets.len()).sum()
    }

    /// The TCP translation (m, base frame) each set predicts at the posture `frames` under the
    /// wrench `wrench` (`[f; m]`, N and Nm, base frame) at the tool point `point` (flange frame,
    /// m), model by model in order, each model's sets in order (module docs).
    pub fn translations(
        &self,
        frames: &Frames,
        point: &Vector3<f64>,
        wrench: &Vector6<f64>,
    ) -> Vec<Vector3<f64>> {
        let mut out = Vec::with_capacity(self.sets());
        for m in &self.models {
            out.extend(m.translations(frames, point, wrench));
        }
        out
    }
}

impl FormModel {
    /// The TCP translation (m, base frame) each of its sets predicts at the posture `frames`
    /// under the wrench `wrench` (`[f; m]`, N and Nm, base frame) at the tool point `point`
    /// (flange frame, m), in the sets' order (module docs).
    pub fn translations(
        &self,
        frames: &Frames,
        point: &Vector3<f64>,
        wrench: &Vector6<f64>,
    ) -> Vec<Vector3<f64>> {
        let j = self.model.jacobian(frames, point);
        let tau = j.tr_mul(wrench);
        let laws = self.model.springs().iter().map(|s| s.law);
        let g = DVector::from_iterator(
            tau.len(),
            (tau.iter().take(6).copied()).chain(
                tau.iter()
                    .skip(6)
                    .zip(laws)
                    .map(|(t, law)| law.response(*t)),
            ),
        );
        let rows = j.fixed_rows::<3>(0);
        self.sets
            .iter()
            .map(|h| rows * h.component_mul(&g))
            .collect()
    }
}
