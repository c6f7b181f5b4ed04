//! One module per subcommand.

pub mod kinematics;
pub mod reproduce;
pub mod robots;
pub mod setups;
pub mod simulate;
