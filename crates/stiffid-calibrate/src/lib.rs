//! # stiffid-calibrate
//!
//! The calibration jobs: [`app::register`] registers the laser tracker to the robot base and
//! designs the postures that register it best, [`app::calibrate`] fits the robot's geometric and
//! elastostatic errors to a campaign of tracker readings (and checks a calibrated robot for drift),
//! [`app::calibrate_cell`] calibrates the tracker and the measuring points. They sit above the
//! experiment design (`stiffid-design`), which they ask for postures, and the calibration science
//! (`stiffid-metrology`).
#![deny(missing_docs)]
#![deny(rustdoc::broken_intra_doc_links, rustdoc::private_intra_doc_links)]

pub mod app;
