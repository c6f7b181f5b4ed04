//! The place job's parts (`stiffid_machining::app::place`).

mod search;
mod written;
