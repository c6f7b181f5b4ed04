//! The calibrate job's parts (`stiffid_calibrate::app::calibrate`).

mod document;
mod drift;
mod extrapolation;
mod ladder;
mod region;
