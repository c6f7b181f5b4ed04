//! The controllers' programs (`stiffid_machining::program`).

mod cartesian;
mod generate;
mod inform;
mod inform_jobs;
mod krl;
mod process;
pub(crate) mod rapid;
mod speed;
