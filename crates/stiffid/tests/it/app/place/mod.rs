//! The place job's parts (`stiffid::app::place`).

mod free;
mod turns;
mod written;
