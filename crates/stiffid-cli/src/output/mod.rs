//! Everything the command writes, through one module so every command gets the same guarantees:
//! - results on stdout through [`print()`] (a write error such as a full device is an error exit,
//!   never a panic; a closed pipe ends the output quietly);
//! - files through [`OutFile`] and report directories through [`ReportDir`] ([`target`]): checked
//!   before any computation, never over an input, a device, a directory or any other non-regular
//!   file, through an existing symlink to its target, whole (a short temporary name, then a
//!   rename when the run has succeeded, [`staged`]), nothing left behind on failure, stdout
//!   included; one run at a time into a report directory;
//! - errors on one line ([`one_line_chain`]), long values cut.

mod dir;
mod file;
mod parts;
pub mod staged;
mod target;

pub use dir::{Fill, ReportDir};
pub use file::{OutFile, Writer};

use anyhow::{Context, Result};
use std::io::Write;
use stiffid::internal::common::error::combination;
use stiffid::JobOption;

/// Writes `text` to stdout (locked, flushed): [`write_stdout`] of its bytes.
///
/// # Errors
/// When stdout cannot take it (for example `> /dev/full`).
pub fn print(text: &str) -> Result<()> {
    write_stdout(text.as_bytes())
}

/// Writes `bytes` to stdout (locked, flushed).
///
/// # Errors
/// When stdout cannot take them (for example `> /dev/full`).
pub fn write_stdout(bytes: &[u8]) -> Result<()> {
    let mut out = std::io::stdout().lock();
    quiet_pipe(out.write_all(bytes).and_then(|_| out.flush()))
}

/// A closed pipe (`stiffid ... | head`) ends the output quietly, as other Unix tools do (the
/// run's files are still written); any other write error is an error.
fn quiet_pipe(written: std::io::Result<()>) -> Result<()> {
    match written {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        other => other.context("stdout: cannot write"),
    }
}

/// Writes to stdout by `fill` (locked, flushed), never whole in memory.
///
/// # Errors
/// When stdout cannot take it or `fill` fails otherwise.
pub fn write_stdout_with(fill: Fill) -> Result<()> {
    let mut out = std::io::stdout().lock();
    quiet_pipe(fill(&mut out).and_then(|()| out.flush()))
}

/// Prints `warning: {text}` on stderr; a stderr that cannot be written is ignored (the result
/// still goes to stdout, the exit code still says how it went).
pub fn warn(text: &str) {
    let _ = writeln!(std::io::stderr().lock(), "warning: {text}");
}

/// Every warning of a job's report on stderr ([`warn`]), as Python raises them.
pub fn warnings(list: &[stiffid::internal::common::warning::Warning]) {
    for w in list {
        warn(&w.message);
    }
}

/// Pretty JSON of `value`, with a final newline.
pub fn json<T: serde::Serialize>(value: &T) -> Result<String> {
    Ok(serde_json::to_string_pretty(value)? + "\n")
}

/// Prints `value` as pretty JSON if `as_json`, else the text `human` makes of it.
pub fn print_json_or<T: serde::Serialize>(
    as_json: bool,
    value: &T,
    human: impl FnOnce(&T) -> String,
) -> Result<()> {
    match as_json {
        true => print(&json(value)?),
        false => print(&human(value)),
    }
}

/// Longest word of an error line: a path may be this long; values quoted in messages are cut
/// shorter where they are quoted ([`stiffid::internal::common::limits::short`]).
const MAX_ERROR_WORD: usize = 4096;

/// Longest error line.
const MAX_ERROR_CHARS: usize = 3 * MAX_ERROR_WORD;

/// An error and its causes on one line, outermost first, as a safety net every word cut at
/// [`MAX_ERROR_WORD`] characters and the whole at [`MAX_ERROR_CHARS`].
pub fn one_line(message: &str) -> String {
    stiffid::internal::common::limits::one_line_within(message, MAX_ERROR_WORD, MAX_ERROR_CHARS)
}

/// [`one_line`] of an error and its causes, outermost first.
pub fn one_line_chain(e: &anyhow::Error) -> String {
    let chain: Vec<String> = e.chain().map(named).collect();
    one_line(&chain.join(": "))
}

/// One error of a chain in words; a job option's as the command names it ([`flag`]).
fn named(e: &(dyn std::error::Error + 'static)) -> String {
    match e.downcast_ref::<stiffid::Error>() {
        Some(
            stiffid::Error::InvalidOption { option, message }
            | stiffid::Error::Gate { option, message },
        ) => format!("{}: {message}", flag(*option)),
        Some(stiffid::Error::OptionCombination {
            option,
            with,
            needs,
            reason,
        }) => combination(option, with, needs, reason, flag),
        _ => e.to_string(),
    }
}

/// A job option as the command names it: `--margin-deg`, `--free station range`; the program's name comes from `--out`.
pub fn flag(option: JobOption) -> String {
    match option {
        JobOption::ProgramName => "--out: program name".into(),
        JobOption::Tolerances => "--tolerance-mm, --tolerance-deg".into(),
        o => format!("--{}", o.name().replace('_', "-")),
    }
}
