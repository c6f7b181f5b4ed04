//! The calibrate crate's jobs (`stiffid_calibrate::app`).

mod calibrate;
