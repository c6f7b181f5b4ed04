//! The calibrate job's parts (`stiffid::app::calibrate`).

mod document;
mod drift;
mod extrapolation;
mod ladder;
mod region;
