//! The jobs of stiffid: one entry point per use case, run the same way by every front end.
//!
//! # The pattern
//! A job is a module with
//! - a typed **request** (`Request`): everything the job needs, in SI units and library types
//!   (a [`Setup`](crate::Setup), the data or where to read it, the choices as library enums);
//! - `run(&Request) -> Result<Report>`: the whole job (every check and every decision about what
//!   to compute), and nothing about how the result is shown;
//! - a typed **report** (`Report`): what the job found, in SI units, with
//!   `warnings: Vec<Warning>`: results the user must look at before trusting them (a likely unit
//!   mistake, a stiffness that is not physical).
//!
//! The output documents (the JSON and CSV stiffid writes, units in every key) are built from the
//! reports in [`crate::documents`]. Front ends only parse, call and render: the command line
//! (`stiffid`) turns its arguments into a request, calls `run`, prints each warning as
//! `warning: MESSAGE` on stderr and renders the report as text or its document as JSON; the
//! Python package raises each warning as a `UserWarning` with the same message and returns the
//! document as dicts and arrays. The same call therefore gives the same document and the same
//! warnings from both.
//!
//! Errors are [`crate::Error`]s that speak of fields and files (`folds`, `data.csv: line 4`),
//! never of one front end's options; each front end adds its own hints.

pub mod calibrate;
pub mod compare_models;
pub mod compensate;
pub mod evaluate;
pub mod force;
pub mod identify;
pub mod identify_model;
pub mod kinematics;
pub mod predict;
pub mod register;
pub mod reproduce;
pub mod select;
pub mod simulate;
pub mod validate;

use serde::Serialize;

/// What a [`Warning`] is about: a stable code for programs (`kind.code()`), independent of the
/// message's wording.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "kebab-case")]
#[non_exhaustive]
pub enum WarningKind {
    /// Every identified compliance is negative: a sign convention is probably wrong.
    AllNegative,
    /// Some identified compliances are negative: not physical.
    Negative,
    /// Some identified compliances are zero or not finite: the joint looks rigid.
    Rigid,
    /// The identified stiffness is far off the setup's nominal the same way on most joints: a
    /// unit mistake is likely.
    Units,
    /// An input passes every range check but looks like a unit slip (lengths in metres where
    /// millimetres are meant, angles in radians under `_deg` names):
    /// [`crate::setup::plausibility`].
    Plausibility,
    /// Under load steps, some postures' zero-load offset, departure from a straight line or
    /// hysteresis exceeds what the tracker noise explains ([`crate::steps`]).
    LoadSteps,
    /// Points of a machining program get no process force (plunges, rapid moves, blocks no
    /// operation covers).
    NoForce,
    /// The data cannot separate some parameters of the model: they get no interval
    /// ([`crate::identify::model::Identifiability`]).
    Unidentifiable,
    /// A URDF's collision meshes were not found: the robot serves kinematics and identification,
    /// the cell's body checks refuse it ([`crate::robot::Bodies::Missing`]).
    Meshes,
}

impl WarningKind {
    /// The stable code, e.g. `units`.
    pub fn code(self) -> &'static str {
        match self {
            WarningKind::AllNegative => "all-negative",
            WarningKind::Negative => "negative",
            WarningKind::Rigid => "rigid",
            WarningKind::Units => "units",
            WarningKind::Plausibility => "plausibility",
            WarningKind::LoadSteps => "load-steps",
            WarningKind::NoForce => "no-force",
            WarningKind::Unidentifiable => "unidentifiable",
            WarningKind::Meshes => "meshes",
        }
    }
}

/// A result the user must look at before trusting it: what the command line prints as
/// `warning: MESSAGE` and Python raises as `UserWarning(MESSAGE)`.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Warning {
    /// What it is about.
    pub kind: WarningKind,
    /// One sentence for the user: what was found and its likely cause.
    pub message: String,
}

impl Warning {
    /// A warning of `kind` saying `message`.
    pub fn new(kind: WarningKind, message: impl Into<String>) -> Self {
        Warning {
            kind,
            message: message.into(),
        }
    }
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

/// `joint 3` or `joints 1, 2` for 0-based joint indices.
pub(crate) fn joint_list(joints: impl IntoIterator<Item = usize>) -> String {
    let names: Vec<String> = joints.into_iter().map(|j| (j + 1).to_string()).collect();
    match names.len() {
        1 => format!("joint {}", names[0]),
        _ => format!("joints {}", names.join(", ")),
    }
}
