//! The machining crate's jobs (`stiffid_machining::app`).

mod compensate;
mod place;
