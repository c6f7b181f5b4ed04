//! The controllers' programs (`stiffid_machining::program`).

mod arcs;
mod backup;
mod comments;
mod controller;
mod dwell;
mod ends;
mod generate;
mod headers;
mod inform;
mod inform_jobs;
mod inform_rectan;
mod inform_vars;
mod joint_targets;
mod krl;
mod numbered;
mod process;
pub(crate) mod rapid;
