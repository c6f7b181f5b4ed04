//! The machining crate's tests (`stiffid_machining`), through its public paths: programs, compensation, placement.

pub(crate) mod program;
