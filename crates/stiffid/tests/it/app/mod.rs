//! The jobs' tests (`stiffid::app`), one folder per job as in `crates/stiffid/src/app`.

mod calibrate;
mod compensate;
mod document;
mod identify;
mod place;
mod setups_new;
