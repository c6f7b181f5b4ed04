//! `stiffid setups [show NAME]`: the built-in setups.

use crate::output;
use anyhow::Result;
use stiffid::setup;

/// Arguments of `stiffid setups`.
#[derive(clap::Args)]
pub struct Args {
    #[command(subcommand)]
    show: Option<Show>,
}

#[derive(clap::Subcommand)]
enum Show {
    /// Print a built-in setup's TOML (copy it, edit it, pass the file to --setup).
    Show {
        /// The setup's name.
        name: String,
    },
}

/// Lists the setups, or prints one.
pub fn run(args: &Args) -> Result<()> {
    match &args.show {
        Some(Show::Show { name }) => output::print(setup::builtin_text(name)?),
        None => {
            let mut text = String::new();
            for name in setup::builtin_names() {
                text += &format!("{name}\n  {}\n", setup::builtin(name)?.description);
            }
            output::print(&text)
        }
    }
}
