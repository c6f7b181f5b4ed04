//! The jobs of the experiment design and the paper's study, run the same way by every front
//! end (the pattern: `stiffid_core::app`).

pub mod document;
pub mod evaluate;
pub mod plan;
pub mod purpose;
pub mod reproduce;
pub mod select;
pub mod simulate;
