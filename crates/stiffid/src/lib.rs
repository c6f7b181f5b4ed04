//! # stiffid
//!
//! Joint stiffness identification of 6-axis serial industrial robots, the design of its
//! experiment (which postures to measure in), calibration and deflection compensation for robotic
//! machining: the jobs ([`app`]: one entry point per use case, run the same way by the command
//! and the Python package) and the library under one name. Each concern below the jobs is a
//! crate of its own, re-exported here:
//!
//! - `stiffid-core` ([`robot`], [`model`], [`setup`], [`observation`], [`cell`], [`io`],
//!   [`math`], [`common`]): what every stage stands on;
//! - `stiffid-metrology` ([`metrology`]): registration, cell and robot calibration;
//! - `stiffid-identify` ([`identify`]): the stiffness identification;
//! - `stiffid-design` ([`design`], [`study`]): the experiment design and the paper's study;
//! - `stiffid-machining` ([`machining`]): machining programs and their compensation;
//! - `stiffid-view` ([`app::document::scene`]): the 3D scenes (glTF, three.js page), above the
//!   science and below the jobs.
//!
//! The model is the Virtual Joint Method of Zhang, Guo, Sun and Sun, "Method of Postures Selection
//! for Industrial Robot Joint Stiffness Identification", IEEE Access 9, 2021,
//! doi:10.1109/ACCESS.2021.3073671 (equation numbers in these docs are that paper's): rigid links,
//! one torsional spring per joint, a wrench at a loading point of a tool and the displacements of
//! measuring points of the same tool.
//!
//! Data flows one way:
//! [`Setup`] -> postures -> [`observation`] matrix -> [`identify`] -> report.
//!
//! ## Conventions
//! - SI inside: metres, radians, newtons, newton-metres, Nm/rad. Files speak mm and degrees.
//! - Jacobians are geometric, in the robot base frame, rows `[v; omega]`.
//! - Postures are *axis* angles q (what the controller shows), `theta = M q + c` maps them to the
//!   kinematic angles of the DH table or URDF (see [`AxisMap`]).
#![deny(missing_docs)]
#![deny(rustdoc::broken_intra_doc_links, rustdoc::private_intra_doc_links)]

pub use stiffid_core::{cell, common, io, math, model, observation, robot, setup};
pub use stiffid_core::{
    dexterity, AxisMap, ColumnProblem, Coordinates, Error, Frames, JobOption, Joint,
    MeasurementField, Progress, Result, Robot, Setup,
};
pub use stiffid_design as design;
pub use stiffid_design::study;
pub use stiffid_identify as identify;
pub use stiffid_machining as machining;
pub use stiffid_metrology as metrology;

pub mod app;

/// The Rust examples of the README, run as doctests.
#[doc = include_str!("../../../README.md")]
#[cfg(doctest)]
pub(crate) struct ReadmeDoctests;

/// The Rust examples of the user guide (`docs/guide.md`), run as doctests.
#[doc = include_str!("../../../docs/guide.md")]
#[cfg(doctest)]
pub(crate) struct GuideDoctests;
