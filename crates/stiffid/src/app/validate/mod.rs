//! The validate job: an identified stiffness of every parameter of the setup's model against
//! measurements it was not fitted to (Zhang et al. 2021, Eq. 22, Table 7; [`stiffid_identify::validate`]).

pub mod document;

use super::measurements::{angle_warnings, on_measurements, Data, Origin};
use crate::app::Warning;
use serde::Serialize;
use std::io::Read;
use stiffid_core::common::limits::Violation;
use stiffid_core::model::region::{self, PostureRange, Region};
use stiffid_core::model::{Compliance, Parameter};
use stiffid_core::{Result, Setup};
use stiffid_identify::validate::{compare_at, Validation};

/// What to validate on what.
pub struct Request<'a, R> {
    /// The setup as the user named it (a built-in setup's name or a file's path): what the
    /// document states.
    pub setup_name: String,
    /// The setup: robot, tool, model.
    pub setup: &'a Setup,
    /// The compliance of every parameter of the setup's model (e.g. a stiffness file's,
    /// [`stiffid_core::io::stiffness::StiffnessFile::compliance`]).
    pub compliance: &'a Compliance,
    /// The measurements (as for [`super::identify`]), ideally postures not used to identify.
    pub data: Data<R>,
    /// The level of the prediction intervals (with the compliance's prediction calibration),
    /// within 0.5 to 0.999, only with a compliance that carries one;
    /// `None` for [`stiffid_core::model::prediction::DEFAULT_LEVEL`].
    pub level: Option<f64>,
}

/// What the validate job found. It serialises to its document (`stiffid validate --json`,
/// Python's `validate(...)`) through the borrowed view [`document::Document`]
/// ([`Report::document`]: mm, built as it is written).
#[derive(Debug, Clone)]
pub struct Report {
    /// The setup as the user named it (a built-in setup's name or a file's path).
    pub setup: String,
    /// The data's name (a file's, or `arrays`).
    pub data_name: String,
    /// The parameters of the setup's model, in the order of the compliance's values.
    pub parameters: Vec<Parameter>,
    /// The compliance validated.
    pub compliance: Compliance,
    /// Every measurement against its prediction, and the summary.
    pub validation: Validation,
    /// Where each measurement came from.
    pub origin: Origin,
    /// Per posture (by the number of [`Origin::angles`]), its axes outside the region the
    /// compliance was identified from ([`stiffid_core::model::region`]): empty inside; `None` when it
    /// records no region.
    pub outside_region: Option<Vec<Vec<Violation>>>,
    /// Inputs to look at before trusting the result (angles that look like radians, postures
    /// outside the region the stiffness was identified from).
    pub warnings: Vec<Warning>,
}

impl Serialize for Report {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        self.document().serialize(s)
    }
}

/// The validate job's report, which is its document (serialised through
/// [`document::Document`]).
pub(crate) type Outcome = crate::app::Outcome<Report>;

/// Runs the validate job.
///
/// # Errors
/// Errors about the data are [`stiffid_core::Error::Input`] naming the data (a file's line and column,
/// or the measurement's number): those of [`stiffid_core::io::measurements::parse`] and of
/// [`compare`](stiffid_identify::validate::compare) (the compliance against the model, the measurements against the setup).
pub fn run<R: Read>(request: Request<'_, R>) -> Result<Outcome> {
    Ok(Outcome {
        report: find(request)?,
        document: crate::app::Itself,
    })
}

/// What [`run`] finds, before its document.
fn find<R: Read>(request: Request<'_, R>) -> Result<Report> {
    let Request {
        setup_name,
        setup,
        compliance,
        data,
        level,
    } = request;
    let level =
        stiffid_core::model::prediction::requested_level(level, compliance.prediction.is_some())?;
    let (data_name, origin, validation) = on_measurements(setup, data, |m| {
        compare_at(setup.arm(), compliance, m, level)
    })?;
    let mut warnings = angle_warnings(&data_name, &origin);
    warnings.extend(compliance.region.unrecorded_warning());
    let outside_region: Option<Vec<Vec<Violation>>> = match &compliance.region {
        Region::Postures(r) => Some(origin.angles.iter().map(|q| r.outside(q)).collect()),
        _ => None,
    };
    if let (Region::Postures(r), Some(outside)) = (&compliance.region, &outside_region) {
        warnings.extend(extrapolated(r, &origin, outside));
    }
    Ok(Report {
        setup: setup_name,
        parameters: setup.model().parameters(),
        outside_region,
        data_name,
        compliance: compliance.clone(),
        validation,
        origin,
        warnings,
    })
}

/// The warning naming the postures outside `region` (`outside`: per posture number, its axes
/// outside), if any.
fn extrapolated(
    region: &PostureRange,
    origin: &Origin,
    outside: &[Vec<Violation>],
) -> Option<Warning> {
    let flagged: Vec<usize> = (0..outside.len())
        .filter(|&p| !outside[p].is_empty())
        .collect();
    let n = flagged.len();
    (n > 0).then(|| {
        let named: Vec<(String, Vec<Violation>)> = (flagged.iter().take(region::NAMED))
            .map(|&p| {
                let label = origin.label(origin.first_of_posture[p]);
                (format!("posture {label}"), outside[p].clone())
            })
            .collect();
        let subject = format!("{n} of {} postures {}", outside.len(), region::lie(n));
        region::extrapolation_warning(region, &subject, &named, n - named.len())
    })
}
