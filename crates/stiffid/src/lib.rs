//! # stiffid
//!
//! Joint stiffness identification of 6-axis serial industrial robots, and the design of its
//! experiment: which postures to measure in.
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

pub mod app;
pub mod cell;
pub mod common;
pub mod design;
pub mod identify;
pub mod io;
pub mod machining;
pub mod math;
pub mod metrology;
pub mod model;
pub mod observation;
pub mod robot;
pub mod setup;
pub mod study;

pub use common::error::{ColumnProblem, Error, JobOption, MeasurementField, Result};
pub use common::progress::Progress;
pub use robot::kinematics::{dexterity, Coordinates, Frames};
pub use robot::{AxisMap, Joint, Robot};
pub use setup::Setup;

/// The Rust examples of the README, run as doctests.
#[doc = include_str!("../../../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;

/// The Rust examples of the user guide (`docs/guide.md`), run as doctests.
#[doc = include_str!("../../../docs/guide.md")]
#[cfg(doctest)]
pub struct GuideDoctests;
