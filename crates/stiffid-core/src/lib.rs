//! # stiffid-core
//!
//! What every stage of stiffid stands on: the robot ([`robot`]: kinematics, dynamics, collision
//! geometry, external axes, URDF and robot files), the stiffness model ([`model`]), the setup of an
//! experiment or a cell ([`setup`]), the observation matrix of the Virtual Joint Method
//! ([`observation`]), the cell's checks ([`cell`]), the file formats ([`io`]), the linear algebra
//! ([`math`]) and the errors, limits and warnings ([`common`]).
//!
//! ## Conventions
//! - SI inside: metres, radians, newtons, newton-metres, Nm/rad. Files speak mm and degrees.
//! - Jacobians are geometric, in the robot base frame, rows `[v; omega]`.
//! - Postures are *axis* angles q (what the controller shows), `theta = M q + c` maps them to the
//!   kinematic angles of the DH table or URDF (see [`AxisMap`]).
#![deny(missing_docs)]
#![deny(rustdoc::broken_intra_doc_links, rustdoc::private_intra_doc_links)]

pub mod cell;
pub mod common;
pub mod io;
pub mod math;
pub mod model;
pub mod observation;
pub mod robot;
pub mod setup;

pub use common::error::{ColumnProblem, Error, JobOption, MeasurementField, Result};
pub use common::progress::Progress;
pub use robot::kinematics::{dexterity, Coordinates, Frames};
pub use robot::{AxisMap, Joint, Robot};
pub use setup::Setup;
