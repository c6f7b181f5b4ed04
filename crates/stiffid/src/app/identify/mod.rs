//! The identify job: the stiffness of the setup's model from measurements (Zhang et al. 2021,
//! Eq. 10-14), with its uncertainty, or the model chosen by the data. One request ([`Request`]:
//! the setup, whose model says what to fit, the data and the [`Options`]), one report
//! ([`Report`]), which is its document ([`document::Document`], a view of it), whatever is
//! asked:
//!
//! - the six drive springs (a setup's model without virtual springs): least squares by QR, the
//!   job's fast path ([`drives`]: streamed in blocks from a file, robust and non-negative fits,
//!   offsets, load steps, cross-validation);
//! - a model with virtual springs: the column-scaled SVD ([`springs`]);
//! - the model comparison (`compare_models`): forward selection of candidate springs
//!   ([`comparison`]).
//!
//! The options are checked together once ([`Options`]), so that the command and Python refuse
//! the same combinations with the same error.

pub mod comparison;
pub mod document;
pub mod drives;
pub mod folds;
mod model_form;
mod options;
pub mod springs;

pub use options::Options;

use crate::app::measurements::Data;
use crate::app::Warning;
use options::Plan;
use std::io::Read;
use stiffid_core::common::error::JobOption;
use stiffid_core::common::progress::Progress;
use stiffid_core::{Error, Result, Setup};
use stiffid_identify::Loss;
use stiffid_identify::Method;

/// The fit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Fit {
    /// Linear least squares by QR (Eq. 13-14).
    #[default]
    LeastSquares,
    /// Iteratively reweighted least squares with this loss ([`stiffid_identify::Identify::robust`]).
    Robust(Loss),
    /// Least squares with every compliance `>= 0` ([`stiffid_identify::Identify::nonnegative`]).
    Nonnegative,
}

impl Fit {
    /// The fit as the method of every cross-validation fold.
    pub(crate) fn method(self) -> Method {
        match self {
            Fit::Robust(loss) => Method::Robust(loss),
            Fit::Nonnegative => Method::Nonnegative,
            Fit::LeastSquares => Method::LeastSquares,
        }
    }

    /// The fit's name in documents: `least-squares`, `nonnegative-least-squares`, `huber` or
    /// `tukey`.
    pub fn name(self) -> &'static str {
        match self {
            Fit::LeastSquares => "least-squares",
            Fit::Nonnegative => "nonnegative-least-squares",
            Fit::Robust(loss) => loss.name(),
        }
    }
}

/// The folds of a cross-validation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Folds {
    /// One fold per posture.
    LeaveOneOut,
    /// This many folds (2 to the number of postures).
    Count(usize),
}

impl Folds {
    /// The number of folds over `postures` postures.
    pub(crate) fn count(self, postures: usize) -> usize {
        match self {
            Folds::LeaveOneOut => postures,
            Folds::Count(k) => k,
        }
    }
}
/// What to identify and how.
pub struct Request<'a, R> {
    /// The setup: robot, tool, the model to fit (the six drives alone take the fast path),
    /// tracker noise, nominal stiffness, candidate springs.
    pub setup: &'a Setup,
    /// The setup as the user named it (a built-in setup's name or a file's path): what the
    /// document states.
    pub setup_name: String,
    /// The measurements.
    pub data: Data<R>,
    /// The fit, the cross-validation, the offsets and the model comparison.
    pub options: Options,
    /// Told of the model comparison's bootstrap resamples (one stage, `bootstrap resamples`);
    /// the other paths report nothing. `&()` for none.
    pub progress: &'a dyn Progress,
}

/// The identify job's report, which is its document (serialised through
/// [`document::Document`]).
pub(crate) type Outcome = crate::app::Outcome<Report>;

/// What the identify job found, by what was asked. It serialises to its document, `stiffid
/// identify --json`, through the borrowed view [`document::Document`] ([`Report::document`]:
/// mm, units in every key), built as it is written.
#[derive(Debug, Clone)]
pub enum Report {
    /// The six drive springs.
    Drives(Box<drives::Report>),
    /// A model with virtual springs.
    Springs(Box<springs::Report>),
    /// The model comparison.
    Comparison(Box<comparison::Report>),
}

impl Report {
    /// Results to look at before trusting them.
    pub fn warnings(&self) -> &[Warning] {
        match self {
            Report::Drives(r) => &r.warnings,
            Report::Springs(r) => &r.warnings,
            Report::Comparison(r) => &r.warnings,
        }
    }

    /// The postures of the measurements (axis angles, rad) in the order they first appear in the
    /// data (what [`document::scene::scene`] takes); `None` for the model comparison.
    pub fn postures(&self) -> Option<&[nalgebra::Vector6<f64>]> {
        match self {
            Report::Drives(r) => Some(&r.origin.angles),
            Report::Springs(r) => Some(&r.origin.angles),
            Report::Comparison(_) => None,
        }
    }

    /// The external axes' values (SI, the cell's order) of [`Report::postures`], one list per
    /// posture (empty without external axes); `None` for the model comparison.
    pub fn external(&self) -> Option<Vec<Vec<f64>>> {
        let origin = match self {
            Report::Drives(r) => &r.origin,
            Report::Springs(r) => &r.origin,
            Report::Comparison(_) => return None,
        };
        let all = origin.external.iter().map(|e| e.as_slice().to_vec());
        Some(match origin.external.iter().all(|e| e.is_empty()) {
            true => Vec::new(),
            false => all.collect(),
        })
    }

    /// The document this report is written as (`stiffid identify --json`, Python's
    /// `identify`), to read: its form's ([`drives::Report::document`],
    /// [`springs::Report::document`], [`comparison::Report::document`]).
    pub fn document(&self) -> document::Document<'_> {
        match self {
            Report::Drives(r) => document::Document::Drives(Box::new(r.document())),
            Report::Springs(r) => document::Document::Springs(Box::new(r.document())),
            Report::Comparison(r) => document::Document::Comparison(Box::new(r.document())),
        }
    }
}

impl drives::Report {
    /// The document this report is written as (`stiffid identify --json` and its `--out`,
    /// Python's `identify`), to read: what the command's text prints.
    pub fn document(&self) -> document::drives::Document<'_> {
        document::drives::Document::new(self)
    }
}

impl springs::Report {
    /// The document this report is written as (`stiffid identify --json` and its `--out` for a
    /// model with virtual springs, the stiffness file of `--stiffness-out`), to read: what the
    /// command's text prints.
    pub fn document(&self) -> document::springs::Document<'_> {
        document::springs::Document::new(self)
    }
}

impl serde::Serialize for Report {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        self.document().serialize(s)
    }
}

/// Runs the identify job: checks the options together, then fits the six drive springs by QR,
/// a model with virtual springs by the SVD, or compares models.
///
/// # Errors
/// Those of [`Options`]' check ([`stiffid_core::Error::OptionCombination`],
/// [`stiffid_core::Error::InvalidOption`]); errors about the data as [`stiffid_core::Error::Input`] naming the
/// data (a file's line and column, or the measurement's number), from the path taken.
pub fn run<R: Read + Send>(request: Request<'_, R>) -> Result<Outcome> {
    Ok(Outcome {
        report: find(request)?,
        document: crate::app::Itself,
    })
}

/// What [`run`] finds.
fn find<R: Read + Send>(request: Request<'_, R>) -> Result<Report> {
    let Request {
        setup,
        setup_name,
        data,
        options,
        progress,
    } = request;
    match options.plan()? {
        Plan::Compare {
            candidates,
            bootstrap,
        } => comparison::run(comparison::Request {
            setup,
            setup_name,
            data,
            candidates: candidates.as_deref(),
            bootstrap,
            progress,
        })
        .map(|r| Report::Comparison(Box::new(r))),
        Plan::Fit {
            fit,
            folds,
            offsets,
        } => {
            let request = drives::Request {
                setup,
                setup_name,
                data,
                fit,
                folds,
                offsets,
            };
            match setup.model().is_drives_only() {
                true => drives::run(request).map(|r| Report::Drives(Box::new(r))),
                false => springs::run(request).map(|r| Report::Springs(Box::new(r))),
            }
        }
    }
}

/// Reads back the stiffness file `text` (the document's JSON, as `identify --out` writes it) as
/// `validate`, `predict` and `compensate` read a stiffness file: parsed
/// ([`stiffid_core::io::stiffness::parse`]) and checked against `setup`'s model
/// ([`stiffid_core::io::stiffness::StiffnessFile::compliance`]). What identify writes, the next step
/// reads: a fit whose file they would refuse (a negative or zero compliance, a stiffness outside
/// its range, a fold's outside it) is refused here, before anything is written, with the way out.
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::Out`]) with the reader's reason and the way out: the
/// non-negative fit, or the model comparison (the data may need springs the model lacks), each
/// option as the front end `spell`s it.
pub fn check_stiffness_file(
    text: &str,
    setup: &Setup,
    spell: &dyn Fn(JobOption) -> String,
) -> Result<()> {
    let read = stiffid_core::io::stiffness::parse(text).and_then(|f| f.compliance(setup.model()));
    read.map(|_| ()).map_err(|e| Error::InvalidOption {
        option: JobOption::Out,
        message: format!(
            "not written: validate, predict and compensate would refuse this stiffness file ({e}); fit with every compliance non-negative ({}), or compare models ({}): the data may need springs the model lacks",
            spell(JobOption::Nonnegative),
            spell(JobOption::CompareModels)
        ),
    })
}
