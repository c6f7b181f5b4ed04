//! One module per subcommand.

pub mod robots;
pub mod setups;
