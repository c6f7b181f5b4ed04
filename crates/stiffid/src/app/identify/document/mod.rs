//! The document of the identify job ([`crate::app::identify`]): `stiffid identify --json` (and
//! `--out`), whatever the model and the options. One document with one schema
//! (`docs/schemas/identify.schema.json`), in one of three forms by what was asked: the six drive
//! springs ([`drives`]), a model with virtual springs ([`springs`]) or the model comparison
//! ([`Comparison`]); each form names itself in its `kind` (`identify-drives`, `identify-springs`,
//! `identify-comparison`), so the schema's union is told apart by that key.

pub mod drives;
pub mod scene;
pub mod springs;

use serde::Serialize;
pub(crate) use stiffid_identify::compare::Document as Comparison;

/// `stiffid identify --json`: the identification of the setup's model or the model comparison.
/// Each form carries its own `kind` (its struct's tag), so the union needs none of its own.
///
/// A view of the report ([`super::Report::document`]), built as it is written: the drives' and
/// a model's forms borrow from their reports; the model comparison's is its own value, built
/// from its report then.
#[derive(Debug, Serialize)]
#[serde(untagged)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[cfg_attr(
    feature = "schema",
    schemars(
        description = "`stiffid identify --json`: the identification of the setup's model or the model comparison.\nEach form carries its own `kind` (its struct's tag), so the union needs none of its own."
    )
)]
pub enum Document<'a> {
    /// The six drive springs (the setup's model without virtual springs), fitted by QR.
    Drives(Box<drives::Document<'a>>),
    /// A model with virtual springs, fitted by the column-scaled SVD.
    Springs(Box<springs::Document<'a>>),
    /// The model comparison (`compare_models`).
    Comparison(Box<Comparison>),
}
