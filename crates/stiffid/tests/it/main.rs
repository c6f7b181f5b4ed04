//! The library's integration tests, one test binary (one link, one set of monomorphised
//! generics): each former test file is a module here. A new test file `tests/it/NAME.rs` is added as
//! `mod NAME;` below; `common` holds the shared helpers, `mutate` the property tests' mutations.

mod active_set;
mod bodies;
mod calibrate_cell;
mod candidates;
mod cell;
mod cell_search;
mod comau_checks;
mod common;
mod compensate;
mod criteria;
mod fanuc_data;
mod formats_proptest;
mod forward_model;
mod gradients;
mod identify;
mod identify_blocks;
mod identify_streamed;
mod jacobians;
mod joint_box;
mod load_steps;
mod load_steps_design;
mod lsq;
mod model_fits;
mod model_prediction;
mod models;
mod mounting;
mod mutate;
mod optional_fields;
mod options_validation;
mod parsers_proptest;
mod path_format;
mod pool;
mod prior;
mod process_forces;
mod program_forms;
mod programs;
mod register_postures;
mod search;
mod setup_builder;
mod simulate;
mod solver_auto;
mod study;
mod trust;
mod urdf;
