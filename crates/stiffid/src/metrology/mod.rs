//! The laser tracker in the cell: registering the tracker to the robot base ([`register`]),
//! calibrating the tracker and the measuring points from unloaded readings ([`calibrate`]), and
//! the robot's geometric and elastostatic calibration from one campaign ([`calibration`]).

pub mod calibrate;
pub mod calibration;
pub mod register;
