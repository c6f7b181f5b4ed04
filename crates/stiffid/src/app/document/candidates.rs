//! The candidates part of the evaluate and select documents: how a group identifies each
//! candidate of the model comparison together with the setup's model
//! ([`stiffid_design::candidates`]).

use serde::{Serialize, Serializer};
use stiffid_core::model::ParameterKind;
use stiffid_design::candidates::{Verdict, Verdicts};
use stiffid_identify::compare::document::DroppedDoc;
use stiffid_identify::compare::nonlinear_separation;

/// Every candidate of the pool on the group, and which `identify --compare-models` could
/// separate with data measured in it.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct CandidatesDoc {
    /// The load levels per posture the design assumes: the setup's load steps, 1 without.
    pub load_levels: usize,
    /// The candidates identified with the model and needing no load steps, by name: those the
    /// comparison can separate on data measured in this group.
    pub separable: Vec<String>,
    /// With a lost motion or load-dependent candidate: whether the load levels separate them
    /// from the springs, in words.
    pub nonlinear_separation: Option<String>,
    /// The linear candidates some group can identify together with the model (in the pool's
    /// order, each unless a generic group cannot separate it from the model and those before it):
    /// what `select --for-candidates` designs for.
    pub designable: Vec<String>,
    /// The linear candidates no group can identify together with the model and the designable
    /// ones before them, with the combination that deflects nothing.
    pub not_designable: Vec<DroppedDoc>,
    /// Whether this group identifies the model and every designable candidate at once (then
    /// every model a forward selection among them can reach is identified too).
    pub together: bool,
    /// The combinations of the model's parameters and the designable candidates, all at once,
    /// this group cannot separate; empty when `together`.
    pub together_unidentifiable: Vec<String>,
    /// Each candidate, in the pool's order.
    pub candidates: Vec<CandidateDoc>,
    /// The candidates the pool left out because no data could identify them.
    pub dropped: Vec<DroppedDoc>,
}

/// How the group identifies one candidate together with the setup's model.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct CandidateDoc {
    /// The candidate's name (`tilt2_x`, `bend3_y`, `lost2`, a declared spring's name).
    pub name: String,
    /// Its family: `tilt`, `bend`, `base`, `tool`, `lost`, `load` or `declared`.
    pub family: &'static str,
    /// What it is: `rotation`, `translation`, `lost-motion` or `load-dependent`.
    pub kind: &'static str,
    /// The group identifies the setup's model and this candidate together (column-scaled rank of
    /// their observation matrix, the rule of `identify`).
    pub identified: bool,
    /// `|P psi_c| / |psi_c|`, 0 to 1: the share of the candidate's deflections over the group
    /// that the model cannot reproduce (the sine of the angle between its column and the model's
    /// columns, `1 / sqrt(VIF)`); 0 when not identified.
    pub separation: f64,
    /// A lost motion or load-dependent compliance with one load level per posture: identified,
    /// if at all, only through how the load changes from posture to posture.
    pub needs_load_steps: bool,
    /// The combinations of the model's parameters and the candidate the group cannot separate
    /// (e.g. `0.71 k2 - 0.71 tilt2_x`); empty when identified.
    pub unidentifiable: Vec<String>,
}

impl From<&Verdict> for CandidateDoc {
    fn from(v: &Verdict) -> Self {
        Self {
            name: v.parameter.name.clone(),
            family: v.family,
            kind: v.parameter.kind.name(),
            identified: v.identified,
            separation: v.separation,
            needs_load_steps: v.needs_load_steps,
            unidentifiable: v.unidentifiable.clone(),
        }
    }
}

impl CandidatesDoc {
    /// The document of the verdicts `v`.
    pub(crate) fn of(v: &Verdicts) -> Self {
        let nonlinear = (v.candidates.iter()).any(|c| {
            matches!(
                c.parameter.kind,
                ParameterKind::LostMotion | ParameterKind::LoadDependent
            )
        });
        Self {
            load_levels: v.load_levels,
            separable: v.separable().into_iter().map(String::from).collect(),
            nonlinear_separation: nonlinear.then(|| nonlinear_separation(v.load_levels)),
            designable: (v.designable.kept.iter())
                .map(|&c| v.candidates[c].parameter.name.clone())
                .collect(),
            not_designable: v.designable.left_out.iter().map(DroppedDoc::from).collect(),
            together: v.together.is_empty(),
            together_unidentifiable: v.together.clone(),
            candidates: v.candidates.iter().map(CandidateDoc::from).collect(),
            dropped: v.dropped.iter().map(DroppedDoc::from).collect(),
        }
    }
}

/// How a group identifies each candidate (the design library's [`Verdicts`]) or none, written
/// as a [`CandidatesDoc`] or `null`. Schema: `Option<CandidatesDoc>`.
///
/// # Errors
/// The serialiser's.
pub(crate) fn verdicts<S: Serializer>(v: &Option<Verdicts>, s: S) -> Result<S::Ok, S::Error> {
    v.as_ref().map(CandidatesDoc::of).serialize(s)
}
