//! The controllers' programs (`stiffid_machining::program`).

mod cartesian;
mod generate;
mod inform;
mod krl;
mod rapid;
mod speed;
