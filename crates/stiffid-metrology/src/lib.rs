//! The laser tracker in the cell: registering the tracker to the robot base ([`register`]),
//! calibrating the tracker and the measuring points from unloaded readings ([`cell_calibration`]), and
//! the robot's geometric and elastostatic calibration from one campaign ([`calibration`]).
#![deny(missing_docs)]
#![deny(rustdoc::broken_intra_doc_links, rustdoc::private_intra_doc_links)]

pub mod calibration;
pub mod cell_calibration;
pub mod register;
