//! The jobs of the stiffness identification, run the same way by every front end
//! (the pattern: `stiffid_core::app`).

pub mod identify;
pub mod measurements;
pub mod validate;
