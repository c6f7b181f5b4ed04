//! The stiffid_core crate's tests, through its public paths.

mod cell;
mod common;
mod io;
mod math;
mod model;
mod observation;
mod robot;
mod setup;
