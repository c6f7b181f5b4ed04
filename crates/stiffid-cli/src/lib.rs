//! The `stiffid` command: robot kinematics, joint stiffness identification, posture selection
//! and the paper's study. Bad input prints one line naming the file, line or field and exits 2;
//! a gate the result fails (`compensate --max-error-mm`, `calibrate --update`'s drift check)
//! prints one line and exits 1.
//!
//! The command's code is this library, and `main.rs` only checks the standard streams and calls
//! [`run`]: a library crate is compiled as soon as the `stiffid` library's metadata is ready,
//! beside the rest of that library's compilation, where a binary's code waited for all of it
//! (docs/performance.md, "The first build").

pub mod commands;
mod feasibility;
pub mod load;
pub mod output;
mod progress;
pub mod renamed;
pub mod report;
mod signals;

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
use std::process::ExitCode;

/// Joint stiffness identification of industrial robots, and which postures to measure in.
#[derive(Parser)]
#[command(
    name = "stiffid",
    version,
    about,
    after_help = "Input files are read up to 256 MiB (UTF-8). Bad input: one 'error:' line, exit code 2, nothing written. A gate the result fails (--max-error-mm, calibrate --update's drift check): one 'error:' line, exit code 1. Every count option states its limit in its help; docs/reference.md, 'Limits and safety', lists them all."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// A directory holding ROS packages: a URDF's `package://NAME/PATH` meshes are looked for as
    /// DIR/NAME/PATH, in these directories (repeat the option, at most 64) before a setup's
    /// `package_paths`.
    #[arg(long = "package-path", global = true, value_name = "DIR")]
    package_path: Vec<std::path::PathBuf>,
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
    /// The laser tracker's transform to the robot base from measuring points it read at known
    /// axis angles, with residuals, standard deviation and the setup's `[tracker]` fragment.
    Register(commands::register::Args),
    /// The tracker's transform and the measuring points in the flange frame fitted together from
    /// unloaded readings: each point's shift with its standard deviation, the robot's unloaded
    /// absolute error, the corrected fragment.
    CalibrateCell(commands::calibrate_cell::Args),
    /// The robot's geometric errors (and its deflection under its own weight), the tracker and
    /// the measuring points fitted together from unloaded readings, with held-out validation;
    /// the calibrated robot file and URDF.
    Calibrate(commands::calibrate::Args),
    /// The mean cutting force and moment (about the tool tip) of every operation of a process file (milling, drilling), feed frame.
    Force(commands::force::Args),
    /// Where to clamp the part: the placement in a region of the cell that minimises a G-code
    /// program's (or a path file's) error bound, every point reachable and feasible; writes the
    /// setup with it.
    Place(commands::place::Args),
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

/// Runs the command on the process's arguments: the exit code (0 success, 2 bad input with one
/// `error:` line on stderr). The binary calls it once the standard streams are checked.
pub fn run() -> ExitCode {
    ExitCode::from(run_from(std::env::args_os()))
}

/// Runs the command on `args` (the program's name first, as `std::env::args_os` gives it): the
/// exit code of [`run`] as a number. The Python package's `stiffid` script calls it with `sys.argv`.
pub fn run_from<I, T>(args: I) -> u8
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    if let Err(message) = stiffid::internal::common::threads::start() {
        return report(&message);
    }
    signals::remove_temporaries_on_signals();
    let args: Vec<std::ffi::OsString> = args.into_iter().map(Into::into).collect();
    let words: Vec<String> = (args.iter().skip(1))
        .filter_map(|a| a.to_str().map(str::to_owned))
        .collect();
    if let Some(message) = renamed::refused(&words) {
        return report(&message);
    }
    let cli = match command()
        .try_get_matches_from(args)
        .and_then(|m| Cli::from_arg_matches(&m))
    {
        Ok(cli) => cli,
        Err(e) if e.use_stderr() => return usage_error(&e),
        Err(e) => {
            // --help, --version: their text on stdout.
            return match output::print(&e.render().to_string()) {
                Ok(()) => 0,
                Err(e) => report(&output::one_line_chain(&e)),
            };
        }
    };
    if cli.package_path.len() > stiffid::internal::setup::MAX_PACKAGE_PATHS {
        return report(&format!(
            "--package-path: {} given, at most {}",
            cli.package_path.len(),
            stiffid::internal::setup::MAX_PACKAGE_PATHS
        ));
    }
    load::set_package_paths(cli.package_path);
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
        Command::Register(args) => commands::register::run(&args),
        Command::CalibrateCell(args) => commands::calibrate_cell::run(&args),
        Command::Calibrate(args) => commands::calibrate::run(&args),
        Command::Force(args) => commands::force::run(&args),
        Command::Place(args) => commands::place::run(&args),
        Command::Completions(args) => commands::completions::completions(&args, command()),
        Command::Man(args) => commands::completions::man(&args, command()),
        Command::Schema(args) => commands::schema::run(&args),
    };
    match result.and_then(|()| output::staged::commit()) {
        Ok(()) => 0,
        Err(e) => {
            output::staged::discard();
            let message = output::one_line_chain(&e) + hint(&e);
            report_with(&message, exit_code(&e))
        }
    }
}

/// The exit code of a failed run: 1 for a gate the user set that the result failed
/// ([`stiffid::Error::is_gate`]: `compensate --max-error-mm`, `calibrate --update`'s drift
/// check), 2 for every other error (bad input, no answer).
fn exit_code(e: &anyhow::Error) -> u8 {
    let error = e.chain().find_map(|c| c.downcast_ref::<stiffid::Error>());
    match error.is_some_and(stiffid::Error::is_gate) {
        true => 1,
        false => 2,
    }
}

/// The command line: [`Cli`], with every numeric option (a number, or comma-separated numbers
/// in a unit such as `--q-deg`) taking values that start with `-` (`--target-pct -inf`,
/// `--q0-deg -10,20,...`), in every subcommand. Each option is declared here once (its name,
/// value, help with its range and unit, default): the reference's option tables and the
/// Python keywords of the same jobs are checked against it by the test `options_defined_once`.
pub fn command() -> clap::Command {
    fn numeric(arg: clap::Arg) -> clap::Arg {
        use std::any::TypeId;
        let id = arg.get_value_parser().type_id();
        let number = [
            TypeId::of::<f64>(),
            TypeId::of::<i64>(),
            TypeId::of::<u64>(),
        ]
        .iter()
        .chain(&[TypeId::of::<usize>(), TypeId::of::<u32>()])
        .any(|t| id == *t);
        let unit = arg.get_long().is_some_and(|l| {
            ["-deg", "-mm", "-n", "-nm", "-pct"]
                .iter()
                .any(|u| l.ends_with(u))
        });
        let takes_value = arg.get_num_args().is_none_or(|n| n.takes_values());
        match (number || unit) && takes_value && arg.get_long().is_some() {
            true => arg.allow_hyphen_values(true),
            false => arg,
        }
    }
    fn each(cmd: clap::Command) -> clap::Command {
        cmd.mut_args(numeric).mut_subcommands(each)
    }
    each(Cli::command())
}

/// A usage error of the command line, whole as clap words it (the missing arguments, the similar
/// option, the usage line), on the one `error: ` line every error gets; exit code 2.
fn usage_error(e: &clap::Error) -> u8 {
    let text = e.render().to_string();
    let mut line = String::new();
    for part in text.lines().map(str::trim).filter(|l| !l.is_empty()) {
        if !line.is_empty() {
            line += if line.ends_with(':') { " " } else { "; " };
        }
        line += part;
    }
    report(&line)
}

/// Prints `message` as one `error: ` line on stderr (long words cut) and returns exit code 2. A
/// stderr that cannot be written is ignored: the exit code still says it.
/// The command's own hint for a library error that a command can mend: which command writes a
/// missing setup field, which shows why postures are infeasible.
fn hint(e: &anyhow::Error) -> &'static str {
    let error = e.chain().find_map(|c| c.downcast_ref::<stiffid::Error>());
    match error {
        Some(stiffid::Error::MissingField { field, .. }) if !field.starts_with("test.") => {
            "; `stiffid setups new --robot R` writes it"
        }
        Some(stiffid::Error::Infeasible { .. }) => {
            "; `stiffid evaluate --postures FILE` shows every posture's checks"
        }
        _ => "",
    }
}

/// Prints `error: MESSAGE` (one line) on stderr: exit code 2.
pub fn fail(message: &str) -> ExitCode {
    ExitCode::from(report(message))
}

/// Prints `error: MESSAGE` (one line) on stderr and returns exit code 2.
fn report(message: &str) -> u8 {
    report_with(message, 2)
}

/// Prints `error: MESSAGE` (one line) on stderr and returns `code`.
fn report_with(message: &str, code: u8) -> u8 {
    use std::io::Write;
    let message = message.strip_prefix("error: ").unwrap_or(message);
    let line = output::one_line(message);
    let _ = writeln!(std::io::stderr().lock(), "error: {line}");
    code
}
