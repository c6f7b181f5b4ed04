//! The machining jobs, run the same way by every front end (the pattern: `stiffid_core::app`).

pub mod compensate;
pub mod force;
pub mod place;
