//! The jobs of stiffid: one entry point per use case, run the same way by every front end.
//!
//! # The pattern
//! A job is a module with
//! - a typed **request** (`Request`): everything the job needs, in SI units and library types
//!   (a [`Setup`](stiffid_core::Setup), the data or where to read it, the choices as library enums);
//! - `run(&Request) -> Result<Report>`: the whole job (every check and every decision about what
//!   to compute), and nothing about how the result is shown;
//! - a typed **report** (`Report`): what the job found, in SI units, with
//!   `warnings: Vec<Warning>`: results the user must look at before trusting them (a likely unit
//!   mistake, a stiffness that is not physical).
//!
//! The output documents (the JSON and CSV stiffid writes, units in every key) are built from the
//! reports in [`crate::app::document`]. Front ends only parse, call and render: the command line
//! (`stiffid`) turns its arguments into a request, calls `run`, prints each warning as
//! `warning: MESSAGE` on stderr and renders the report as text or its document as JSON; the
//! Python package raises each warning as a `UserWarning` with the same message and returns the
//! document as dicts and arrays. The same call therefore gives the same document and the same
//! warnings from both.
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

/// `error` about the data named `name`.
pub fn in_data(name: &str, error: Error) -> Error {
    Error::Input {
        source_name: name.to_string(),
        error: Box::new(error),
    }
}
