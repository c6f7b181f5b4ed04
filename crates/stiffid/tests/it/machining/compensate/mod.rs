//! The compensation (`stiffid_machining::compensate`).

mod budget;
mod free;
mod refine;
mod runs;
mod tool_axis;
mod variables;
