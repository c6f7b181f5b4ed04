//! The compensate job's parts (`stiffid::app::compensate`).

mod certify;
mod pulses;
