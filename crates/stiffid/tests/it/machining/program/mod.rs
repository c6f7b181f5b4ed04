//! The controllers' programs (`stiffid_machining::program`).

mod cartesian;
mod generate;
mod krl;
mod speed;
