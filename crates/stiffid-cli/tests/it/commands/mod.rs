//! The subcommands' code (`stiffid_cli::commands`).

mod kinematics;
