//! # stiffid
//!
//! Joint stiffness identification of 6-axis serial industrial robots, the design of its
//! experiment (which postures to measure in), calibration and deflection compensation for robotic
//! machining. The API is the jobs ([`app`]: one entry point per use case, each a request, a
//! `run` and a typed report and document, run the same way by the command and the Python
//! package), the nouns they share ([`Setup`], [`Robot`], [`Compliance`], [`Model`], [`Error`],
//! [`Warning`], [`Progress`]) and a few one-step functions for a program of your own:
//!
//! - [`setup`]: the built-in setups and a setup file read;
//! - [`robot`]: the built-in robot presets (kinematics are [`Robot`]'s and [`Frames`]' methods,
//!   the dexterity index [`dexterity`]);
//! - [`io`]: the measurement, postures and stiffness files, as `&str -> Result` functions;
//! - [`identify`]: least squares by QR, with its uncertainty;
//! - [`design`]: a seeded start group, the paper's local search, the global search, every
//!   criterion of a group;
//! - [`study`]: the paper's simulation study;
//! - [`cell`]: the cell's checks of a posture.
//!
//! The crates below the jobs (core, metrology, identify, design, machining, view) are not API:
//! the command and the Python package reach them through a hidden module, and their items may
//! change in any release. The API is listed, item by item, in `crates/stiffid/public-api.txt`.
//!
//! The model is the Virtual Joint Method of Zhang, Guo, Sun and Sun, "Method of Postures Selection
//! for Industrial Robot Joint Stiffness Identification", IEEE Access 9, 2021,
//! doi:10.1109/ACCESS.2021.3073671 (equation numbers in these docs are that paper's): rigid links,
//! one torsional spring per joint, a wrench at a loading point of a tool and the displacements of
//! measuring points of the same tool.
//!
//! Data flows one way:
//! [`Setup`] -> postures -> observation matrix -> [`identify`] -> report.
//!
//! ## Conventions
//! - SI inside: metres, radians, newtons, newton-metres, Nm/rad. Files speak mm and degrees.
//! - Jacobians are geometric, in the robot base frame, rows `[v; omega]`.
//! - Postures are *axis* angles q (what the controller shows), `theta = M q + c` maps them to the
//!   kinematic angles of the DH table or URDF (see [`AxisMap`]).
#![deny(missing_docs)]
#![deny(rustdoc::broken_intra_doc_links, rustdoc::private_intra_doc_links)]

pub use stiffid_core::common::warning::Warning;
pub use stiffid_core::model::{Compliance, Model};
pub use stiffid_core::{
    dexterity, AxisMap, ColumnProblem, Coordinates, Error, Frames, JobOption, Joint,
    MeasurementField, Progress, Result, Robot, Setup,
};

/// Setups: the built-in ones ([`setup::builtin`], [`setup::builtin_names`]), a setup file's
/// text read ([`setup::parse`]: its robot resolved by the caller), a setup built in code from SI
/// values ([`setup::SetupBuilder`], from [`Setup::builder`]), and the setup's parts, [`Setup`]'s
/// accessors.
pub mod setup {
    pub use stiffid_core::setup::{
        builtin, builtin_names, parse, Arm, Experiment, SetupBuilder, Workcell,
    };
}

/// Robots: the built-in presets ([`robot::presets`]); a robot's kinematics are
/// [`Robot`]'s methods and [`Frames`]'.
pub mod robot {
    pub use stiffid_core::robot::presets;
}

/// The file formats the jobs read, as `&str -> Result` functions: measurements, postures and
/// stiffness files (the reference's "File formats").
pub mod io {
    pub use stiffid_core::io::{measurements, postures, stiffness};
}

/// Stiffness identification in one step: [`identify::least_squares`] (the paper's Eq. 13-14 by
/// QR) and what it returns.
pub mod identify {
    pub use stiffid_identify::{least_squares, Identification, Uncertainty};
}

/// Experiment design in one step each: a seeded start group, the paper's local search, the
/// global search, and every criterion of a group.
pub mod design {
    pub use stiffid_design::{
        evaluate, global, local, random_group, Criterion, Evaluation, Gradient, SearchOptions,
        SearchOutcome, Solver,
    };
}

/// The paper's simulation study (Zhang et al. 2021, section IV) in one step: [`study::run`].
pub mod study {
    pub use stiffid_design::study::{run, Findings, Group, Options, Study};
}

/// The cell's checks of a posture: [`cell::feasibility`] once, [`cell::Checker`] for many.
pub mod cell {
    pub use stiffid_core::cell::{feasibility, Checker};
}

/// Not API: the crates below the jobs, whole, for the command, the Python package, the benches
/// and the tests of this repository. Their items change without notice; a program linking
/// stiffid uses [`app`] and the items above.
#[doc(hidden)]
pub mod internal {
    pub use stiffid_core::{cell, common, io, math, model, observation, robot, setup};
    pub use stiffid_design as design;
    pub use stiffid_design::study;
    pub use stiffid_identify as identify;
    pub use stiffid_machining as machining;
    pub use stiffid_metrology as metrology;
    pub use stiffid_view as view;
}

pub mod app;

/// The Rust examples of the README, run as doctests.
#[doc = include_str!("../../../README.md")]
#[cfg(doctest)]
pub(crate) struct ReadmeDoctests;

/// The Rust examples of the user guide (`docs/guide.md`), run as doctests.
#[doc = include_str!("../../../docs/guide.md")]
#[cfg(doctest)]
pub(crate) struct GuideDoctests;
