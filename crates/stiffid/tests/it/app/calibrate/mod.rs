//! The calibrate job's parts (`stiffid::app::calibrate`).

mod document;
mod extrapolation;
mod ladder;
mod region;
mod track_fit;
