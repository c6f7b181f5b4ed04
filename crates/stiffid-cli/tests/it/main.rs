//! The command's integration tests, one test binary: each former test file is a module here. A new
//! test file `tests/it/NAME.rs` is added as `mod NAME;` below; `common` holds the shared helpers.

mod answers;
mod backlash_cli;
mod bodies_cli;
mod calibrate_cli;
mod calibrated_robot_cli;
mod cell_cli;
mod common;
mod compensate_cli;
mod completions;
mod documents_renamed;
mod extrapolation_cli;
mod fixed_part_cli;
mod free_options_refused;
mod hardening;
mod hardening_edges;
mod identify_cli;
mod kinematics;
mod lead_tilt_cli;
mod limits_edges;
mod mass_cli;
mod model_ranking_cli;
#[path = "../../../stiffid/tests/it/mutate.rs"]
mod mutate;
mod optional_fields_cli;
mod options_proptest;
mod place_cli;
mod pool_cli;
mod program_axes_cli;
mod program_readback_cli;
mod program_speeds_cli;
mod readable_files;
mod refine_cli;
mod refused_options;
mod register_cli;
mod report_cli;
mod reproduce;
mod schemas;
mod select_cli;
mod setups_new;
mod simulate_cli;
mod table_cli;
mod track_cli;
mod trust_cli;
mod update_cli;
