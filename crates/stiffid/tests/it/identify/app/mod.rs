//! The identify crate's jobs (`stiffid::app`).

mod identify;
