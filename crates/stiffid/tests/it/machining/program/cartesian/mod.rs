//! Cartesian targets in programs (`stiffid_machining::program::cartesian`).

mod flags;
mod literal;
