//! The jobs of stiffid: one entry point per use case, run the same way by every front end.
//!
//! # The pattern
//! A job is a module with
//! - a typed **request** (`Request`): everything the job needs, in SI units and library types
//!   (a [`Setup`](stiffid_core::Setup), the data or where to read it, the choices as library enums,
//!   the names its document states: the setup's as the user gave it, the files written), and
//!   where the job reports progress (a `progress: &dyn Progress` field) if it takes long;
//! - `run(&Request) -> Result<Outcome>`: the whole job (every check and every decision about what
//!   to compute), and nothing about how the result is shown. The one job that streams its rows,
//!   [`compensate`], takes a second argument, the sink that receives them in path order;
//! - an **outcome** (`Outcome`, an [`Outcome`]`<Report, Document>`, or the job's own struct
//!   where it returns more, a scene or a written file): the typed **report** (`Report`) of what
//!   the job found, in SI units, with `warnings: Vec<Warning>`: results the user must look at
//!   before trusting them (a likely unit mistake, a stiffness that is not physical); and the
//!   **document** the job writes (the JSON stiffid writes, mm and deg with units in every key,
//!   its types in the job's `document` module and in [`crate::app::document`]), or, as an
//!   `Outcome<Report>`, none of its own: the report serialises to the document itself, its SI
//!   fields written in the document's units by the adapters of [`document::units`].
//!
//! Front ends only parse, call and render: the command line (`stiffid`) turns its arguments into
//! a request, calls `run`, prints each warning as `warning: MESSAGE` on stderr and renders the
//! report as text or prints the document as JSON; the Python package raises each warning as a
//! `UserWarning` with the same message and returns the document as dicts and arrays. Neither
//! builds a document: the same call therefore gives the same document and the same warnings from
//! both.
//!
//! Errors are [`stiffid_core::Error`]s that speak of fields and files (`folds`, `data.csv: line 4`),
//! never of one front end's options; each front end adds its own hints.

pub mod calibrate;
pub mod calibrate_cell;
pub mod compensate;
pub mod evaluate;
pub mod force;
pub mod identify;
pub mod kinematics;
pub mod measurements;
pub mod place;
pub mod plan;
pub mod predict;
pub mod purpose;
pub mod readings;
pub mod register;
pub mod reproduce;
pub mod select;
pub mod setups_new;
pub mod simulate;
pub mod validate;

pub mod document;

pub use stiffid_core::common::warning::{Warning, WarningKind};

use stiffid_core::Error;

/// What a job returns: the report of what it found (SI units) and the document it writes (mm,
/// deg, units in every key). It reads as its report (`outcome.warnings`, `&outcome` where a
/// `&Report` is expected), and [`Outcome::written`] is the document for every job: the
/// `document` value where the job builds one (`Outcome<Report, Document>`), the report itself
/// where the report serialises to its document through the unit adapters
/// ([`document::units`]; `Outcome<Report>`, the document [`Itself`]).
#[derive(Debug, Clone)]
pub struct Outcome<R, D = Itself> {
    /// What the job found, SI units.
    pub report: R,
    /// The document the job writes: `--json` and the Python function's result; [`Itself`] where
    /// the report is the document.
    pub document: D,
}

/// The document of an [`Outcome`] whose report serialises to the document itself (its keys with
/// their units, its `kind`): no second value to build or hold.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Itself;

/// Where an [`Outcome`]'s document is, given its report `R`: a document value of its own (any
/// serialisable type) or the report itself ([`Itself`]).
pub trait Writes<R> {
    /// The type serialised as the document.
    type Document: serde::Serialize;
    /// The document, from this value and the outcome's `report`.
    fn of<'a>(&'a self, report: &'a R) -> &'a Self::Document;
}

impl<R, D: serde::Serialize> Writes<R> for D {
    type Document = D;

    fn of<'a>(&'a self, _: &'a R) -> &'a D {
        self
    }
}

impl<R: serde::Serialize> Writes<R> for Itself {
    type Document = R;

    fn of<'a>(&'a self, report: &'a R) -> &'a R {
        report
    }
}

impl<R, D: Writes<R>> Outcome<R, D> {
    /// The document the job writes (`--json`, the Python function's result).
    pub fn written(&self) -> &D::Document {
        self.document.of(&self.report)
    }
}

impl<R, D> std::ops::Deref for Outcome<R, D> {
    type Target = R;

    fn deref(&self) -> &R {
        &self.report
    }
}

/// `error` about the data named `name`.
pub(crate) fn in_data(name: &str, error: Error) -> Error {
    Error::Input {
        source_name: name.to_string(),
        error: Box::new(error),
    }
}
