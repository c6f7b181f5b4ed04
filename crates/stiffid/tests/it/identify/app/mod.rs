//! The identify crate's jobs (`stiffid_identify::app`).

mod identify;
