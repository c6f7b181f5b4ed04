//! `stiffid completions SHELL` and `stiffid man [SUBCOMMAND]`: shell completions and man pages,
//! generated from the command's own definition (clap_complete, clap_mangen), so they never lag it.

use crate::output::write_stdout;
use anyhow::{bail, Result};

/// Arguments of `stiffid completions`.
#[derive(clap::Args)]
pub struct CompletionsArgs {
    /// The shell: bash, zsh, fish, elvish or powershell.
    #[arg(value_enum)]
    shell: clap_complete::Shell,
}

/// Arguments of `stiffid man`.
#[derive(clap::Args)]
pub struct ManArgs {
    /// A subcommand's page (e.g. `select`) instead of the page of `stiffid` itself.
    subcommand: Option<String>,
}

/// Prints the completion script for `args.shell` to standard output.
pub fn completions(args: &CompletionsArgs, mut command: clap::Command) -> Result<()> {
    let mut script = Vec::new();
    clap_complete::generate(args.shell, &mut command, "stiffid", &mut script);
    write_stdout(&script)
}

/// Prints the man page (roff) of `stiffid` or of one of its subcommands to standard output.
pub fn man(args: &ManArgs, command: clap::Command) -> Result<()> {
    let page = match &args.subcommand {
        None => command,
        Some(name) => match command.find_subcommand(name) {
            Some(sub) => sub
                .clone()
                .display_name(format!("stiffid-{name}"))
                .bin_name(format!("stiffid {name}"))
                .version(env!("CARGO_PKG_VERSION")),
            None => bail!(
                "man: no subcommand '{}' (expected one of: {})",
                name.chars().take(40).collect::<String>(),
                command
                    .get_subcommands()
                    .map(|s| s.get_name())
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        },
    };
    let mut roff = Vec::new();
    clap_mangen::Man::new(page).render(&mut roff)?;
    write_stdout(&roff)
}
