//! The reproduce job: the paper's simulation study (Zhang et al. 2021, Section IV-A, Fig. 8,
//! Tables 3-5) as [`stiffid_design::study::run`] runs it, and what it found ([`stiffid_design::study::findings`]),
//! computed once for every front end and document.

pub mod document;

use crate::app::Warning;
use stiffid_core::common::progress::Progress;
use stiffid_core::{Result, Setup};
use stiffid_design::study::{self, findings, Findings, Options, Study};

/// The study to run.
pub struct Request<'a> {
    /// The setup (the paper's: `zhang2021-comau-nj165`); its nominal stiffness is the true
    /// stiffness of the simulation.
    pub setup: &'a Setup,
    /// Runs, seed, starts per global search, start groups of the start-group check.
    pub options: Options,
    /// Where the study reports its stages (`&()` for nowhere).
    pub progress: &'a dyn Progress,
}

/// What the study found. It serialises to its document, `summary.json`, through the borrowed
/// view [`document::Summary`] (mm and deg, units in every key), built as it is written.
#[derive(Debug, Clone)]
pub struct Report {
    /// The study: every group, its simulation and validation, the start-group check.
    pub study: Study,
    /// What it found, in numbers.
    pub findings: Findings,
    /// None today: the job's warnings, for the pattern ([`crate::app`]).
    pub warnings: Vec<Warning>,
}

impl serde::Serialize for Report {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        document::Summary::new(self).serialize(s)
    }
}

/// The reproduce job's report, which is its document (serialised through
/// [`document::Summary`]).
pub(crate) type Outcome = crate::app::Outcome<Report>;

/// Runs the study.
///
/// # Errors
/// The errors of [`study::run`]: counts out of range, a setup without a nominal stiffness or a
/// characteristic length.
pub fn run(request: &Request) -> Result<Outcome> {
    request
        .setup
        .require_loading("reproduce (the rope load of the study)")?;
    let study = study::run(request.setup, &request.options, request.progress)?;
    let report = Report {
        findings: findings(&study),
        study,
        warnings: Vec::new(),
    };
    Ok(Outcome {
        report,
        document: crate::app::Itself,
    })
}
