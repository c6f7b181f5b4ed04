//! `stiffid setups [show NAME|FILE]`: the built-in setups.

use crate::output;
use anyhow::Result;
use stiffid::internal::setup;

/// Arguments of `stiffid setups`.
#[derive(clap::Args)]
pub struct Args {
    #[command(subcommand)]
    action: Option<Action>,
}

#[derive(clap::Subcommand)]
enum Action {
    /// Print a built-in setup's TOML (copy it, edit it, pass the file to --setup), or a setup
    /// file's after checking that it loads.
    Show {
        /// The setup's name, or a setup .toml file.
        name: String,
    },
    /// Write a complete, commented setup for your own robot (preset, robot TOML or URDF).
    New(super::setups_new::NewArgs),
}

/// Lists the setups, or prints one.
pub fn run(args: &Args) -> Result<()> {
    match &args.action {
        Some(Action::Show { name }) if std::path::Path::new(name).is_file() => {
            crate::load::setup(name)?;
            output::print(&crate::load::read(std::path::Path::new(name))?)
        }
        Some(Action::Show { name }) => output::print(setup::builtin_text(name)?),
        Some(Action::New(args)) => super::setups_new::run(args),
        None => {
            let mut text = String::new();
            for name in setup::builtin_names() {
                text += &format!("{name}\n  {}\n", setup::builtin(name)?.description());
            }
            output::print(&text)
        }
    }
}
