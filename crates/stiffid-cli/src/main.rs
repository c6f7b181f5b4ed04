//! The `stiffid` command: robot kinematics, joint stiffness identification, posture selection
//! and the paper's study. Bad input prints one line naming the file, line or field and exits 2.

mod commands;
mod feasibility;
mod load;
mod output;
mod report;

use clap::{CommandFactory, Parser, Subcommand};
use std::process::ExitCode;

/// Joint stiffness identification of industrial robots, and which postures to measure in.
#[derive(Parser)]
#[command(
    name = "stiffid",
    version,
    about,
    after_help = "Input files are read up to 256 MiB (UTF-8). Bad input: one 'error:' line, exit code 2, nothing written. Every count option states its limit in its help; the README's 'Limits and safety' lists them all."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// List the built-in robot presets.
    Robots,
    /// Forward kinematics, point Jacobian and dexterity of one posture.
    Kinematics(commands::kinematics::Args),
    /// List the built-in setups, or print one as TOML to copy and edit.
    Setups(commands::setups::Args),
    /// Every design criterion of a group of postures and its predicted deviation rates.
    Evaluate(commands::evaluate::Args),
    /// Choose postures: minimise a design criterion by local SQP, global multistart search or from a
    /// pool of postures; how many are needed; a measurement plan.
    Select(commands::select::Args),
    /// Side and top views of every posture of a postures file, SVG and PNG.
    Plot(commands::plot::Args),
    /// Torques, joint deflections and measuring-point displacements for a posture and wrench.
    Predict(commands::predict::Args),
    /// Identify the joint stiffness from measurements, with confidence intervals.
    Identify(commands::identify::Args),
    /// Compare measured and predicted displacements for an identified stiffness (Eq. 22).
    Validate(commands::validate::Args),
    /// Deflection of a machining path under its process wrench, and the compensated axis angles.
    Compensate(commands::compensate::Args),
    /// The mean cutting force of every operation of a process file (milling, drilling), feed frame.
    Force(commands::force::Args),
    /// Monte Carlo identification with groups of postures from files (the paper's Section IV-A).
    Simulate(commands::simulate::Args),
    /// The paper's simulation study end to end, with a report (HTML, Markdown, JSON, CSV, figures).
    Reproduce(commands::reproduce::Args),
    /// Print a shell completion script (bash, zsh, fish, elvish, powershell).
    Completions(commands::completions::CompletionsArgs),
    /// Print the man page (roff) of stiffid or of one subcommand.
    Man(commands::completions::ManArgs),
    /// Print the JSON Schema of a JSON document stiffid writes or reads (without a name: the
    /// names); the repository ships them in docs/schemas/.
    #[command(hide = true)]
    Schema(commands::schema::Args),
}

fn main() -> ExitCode {
    restore_sigpipe();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if e.use_stderr() => return fail(&e.to_string()),
        Err(e) => {
            // --help, --version: their text on stdout.
            return match output::print(&e.render().to_string()) {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => fail(&output::one_line_chain(&e)),
            };
        }
    };
    let result = match cli.command {
        Command::Robots => commands::robots::run(),
        Command::Kinematics(args) => commands::kinematics::run(&args),
        Command::Setups(args) => commands::setups::run(&args),
        Command::Simulate(args) => commands::simulate::run(&args),
        Command::Evaluate(args) => commands::evaluate::run(&args),
        Command::Select(args) => commands::select::run(&args),
        Command::Plot(args) => commands::plot::run(&args),
        Command::Reproduce(args) => commands::reproduce::run(&args),
        Command::Predict(args) => commands::predict::run(&args),
        Command::Identify(args) => commands::identify::run(&args),
        Command::Validate(args) => commands::validate::run(&args),
        Command::Compensate(args) => commands::compensate::run(&args),
        Command::Force(args) => commands::force::run(&args),
        Command::Completions(args) => commands::completions::completions(&args, Cli::command()),
        Command::Man(args) => commands::completions::man(&args, Cli::command()),
        Command::Schema(args) => commands::schema::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => fail(&output::one_line_chain(&e)),
    }
}

/// Prints `message` as one `error: ` line on stderr (its first line for a clap error, long words
/// cut) and returns exit code 2. A stderr that cannot be written is ignored: the exit code still
/// says it.
fn fail(message: &str) -> ExitCode {
    use std::io::Write;
    let first = message.lines().next().unwrap_or_default();
    let first = first.strip_prefix("error: ").unwrap_or(first);
    let line = output::one_line(first);
    let _ = writeln!(std::io::stderr().lock(), "error: {line}");
    ExitCode::from(2)
}

/// Restores the default SIGPIPE action (Rust ignores it), so `stiffid ... | head` ends quietly
/// like other Unix tools instead of panicking on a closed stdout.
fn restore_sigpipe() {
    #[cfg(unix)]
    // SAFETY: called first thing in main, before any other thread exists; SIG_DFL is a valid action.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}
