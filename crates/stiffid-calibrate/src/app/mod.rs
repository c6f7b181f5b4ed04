//! The calibration jobs, run the same way by every front end (the pattern:
//! `stiffid_core::app`).

pub mod calibrate;
pub mod calibrate_cell;
pub mod register;
