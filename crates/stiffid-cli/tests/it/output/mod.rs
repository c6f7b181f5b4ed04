//! The command's outputs (`stiffid_cli::output`).

mod file;
mod signals;
mod staged;
