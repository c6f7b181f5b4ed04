//! The laser tracker in the cell: registering the tracker to the robot base ([`register`]) and
//! calibrating the tracker and the measuring points from unloaded readings ([`calibrate`]).

pub mod calibrate;
pub mod register;
