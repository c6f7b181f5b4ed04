//! The place job's parts (`stiffid_machining::app::place`).

mod free;
mod search;
mod written;
