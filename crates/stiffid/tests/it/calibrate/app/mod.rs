//! The calibrate crate's jobs (`stiffid::app`).

mod calibrate;
