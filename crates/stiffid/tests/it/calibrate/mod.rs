//! The calibrate crate's tests (`stiffid_calibrate`), through its public paths.

mod app;
