//! The machining crate's tests (`stiffid_machining`), through its public paths: programs, compensation, placement.

mod compensate;
mod dynamics;
pub(crate) mod program;
