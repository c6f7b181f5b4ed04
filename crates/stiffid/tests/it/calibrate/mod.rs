//! The calibration jobs' tests (`stiffid::app::calibrate`, `calibrate_cell`, `register`),
//! through their public paths.

mod app;
