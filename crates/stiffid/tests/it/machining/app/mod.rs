//! The machining crate's jobs (`stiffid::app`).

mod compensate;
mod place;
