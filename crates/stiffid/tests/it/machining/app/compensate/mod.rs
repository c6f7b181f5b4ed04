//! The compensate job's parts (`stiffid_machining::app::compensate`).

mod certify;
mod pulses;
