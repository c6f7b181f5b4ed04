//! One module per subcommand.

pub mod calibrate;
pub mod calibrate_cell;
pub mod cell_readings;
pub mod common;
pub mod compensate;
pub mod completions;
pub mod configuration_table;
pub mod evaluate;
pub mod force;
pub mod identify;
pub mod kinematics;
pub mod place;
pub mod plot;
pub mod predict;
pub mod register;
pub mod reproduce;
pub mod robots;
pub mod schema;
pub mod select;
pub mod setups;
pub mod setups_new;
pub mod simulate;
pub mod speed_line;
pub mod validate;
