//! The document of the evaluate job ([`crate::app::evaluate`]): `stiffid evaluate --json`,
//! Python's `Setup.evaluate`: a group's criteria, calibration criteria and parameters
//! ([`crate::app::document::group`]), and every posture's feasibility.

use crate::app::document::candidates::CandidatesDoc;
use crate::app::document::feasibility::{self, Posture};
use crate::app::document::group::{parameters, CalibrationDoc, Criteria, Parameter};
use crate::app::evaluate::Report;
use serde::Serialize;
use stiffid_core::Setup;

/// The evaluate document: the criteria, every posture's feasibility in the cell, and how well the
/// group identifies each parameter.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "evaluate")]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("evaluate")))]
pub struct Document {
    /// The criteria.
    #[serde(flatten)]
    pub criteria: Criteria,
    /// Every posture's checks in the cell, in the order of the group.
    pub feasibility: Vec<Posture>,
    /// Every parameter of the setup's model, drives first: whether the group identifies it and
    /// how well.
    pub parameters: Vec<Parameter>,
    /// The combinations of parameters the group cannot separate (e.g. `0.71 k6 - 0.71 twin6`);
    /// empty when it identifies every parameter.
    pub unidentifiable: Vec<String>,
    /// With `--for calibration` or `both`: the group's calibration criteria.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub calibration: Option<CalibrationDoc>,
    /// Unless `--for calibration`: how the group identifies each candidate of the model
    /// comparison together with the setup's model.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub candidates: Option<CandidatesDoc>,
}

impl Document {
    /// The document of an evaluate report on `setup`.
    pub fn new(report: &Report, setup: &Setup) -> Self {
        Self {
            criteria: Criteria::from(&report.evaluation),
            feasibility: feasibility::postures(&report.feasibility),
            parameters: parameters(&report.evaluation, setup),
            unidentifiable: report.unidentifiable.clone(),
            calibration: (report.calibration.as_ref()).map(|(o, c)| CalibrationDoc::new(o, c)),
            candidates: report.candidates.as_ref().map(CandidatesDoc::from),
        }
    }
}
