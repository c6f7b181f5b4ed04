//! The force job: the mean cutting force (and, if asked, its peak over a revolution) of every
//! operation of a process file, in its feed frame ([`stiffid_machining::process`]: Altintas, *Manufacturing
//! Automation*, 2nd ed., ch. 2.4, for milling; the specific-energy model for drilling).

use serde::Serialize;
use stiffid_core::Result;
use stiffid_machining::process::{self, OperationForce, Process};

/// The forces to compute.
pub struct Request<'a> {
    /// The process file's name.
    pub name: String,
    /// The process.
    pub process: &'a Process,
    /// The peak force over one revolution on a grid of spindle angles this far apart, deg
    /// (0.01 to 10; in degrees as the process file and the document state it);
    /// `None` for none.
    pub peak_resolution_deg: Option<f64>,
}

/// The force document.
///
/// The report is its own document (`stiffid force --json`, Python's `process_force(...)`):
/// nothing in it needs a unit converted.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename = "force")]
#[cfg_attr(feature = "schema", schemars(description = "The force document."))]
#[cfg_attr(feature = "schema", schemars(transform = crate::app::document::schema::Kind("force")))]
pub struct Report {
    /// The process file.
    #[serde(rename = "process")]
    pub name: String,
    /// The peak's angular resolution, deg, or `null`.
    pub peak_resolution_deg: Option<f64>,
    /// One entry per operation, in file order.
    pub operations: Vec<OperationForce>,
}

/// The force job's report, which is its document.
pub(crate) type Outcome = crate::app::Outcome<Report>;

/// Runs the force job.
///
/// # Errors
/// Those of [`process::forces`]: [`stiffid_core::Error::InvalidField`] (`peak_resolution_deg`)
/// for a resolution outside its range.
pub fn run(request: &Request<'_>) -> Result<Outcome> {
    let report = Report {
        name: request.name.clone(),
        peak_resolution_deg: request.peak_resolution_deg,
        operations: process::forces(request.process, request.peak_resolution_deg)?,
    };
    Ok(Outcome {
        report,
        document: crate::app::Itself,
    })
}
