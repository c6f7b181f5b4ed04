//! One module per subcommand.

pub mod evaluate;
pub mod kinematics;
pub mod reproduce;
pub mod robots;
pub mod select;
pub mod setups;
pub mod simulate;
