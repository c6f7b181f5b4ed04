//! The document of the force job ([`crate::app::force`]): `stiffid force --json`, Python's
//! `process_force(...)`.

use crate::app::force::Report;
use serde::Serialize;
use stiffid_machining::process::OperationForce;

/// The force document.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "force")]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("force")))]
pub struct Document {
    /// The process file.
    pub process: String,
    /// The peak's angular resolution, deg, or `null`.
    pub peak_resolution_deg: Option<f64>,
    /// One entry per operation, in file order.
    pub operations: Vec<OperationForce>,
}

impl Document {
    /// The document of `report`.
    pub fn new(report: &Report) -> Self {
        Document {
            process: report.name.clone(),
            peak_resolution_deg: report.peak_resolution_deg,
            operations: report.operations.clone(),
        }
    }
}
