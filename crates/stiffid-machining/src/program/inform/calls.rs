//! The jumps, calls, loops and branches of a job with motions (module docs of [`super`]): each
//! refused naming its line, but a `CALL JOB:NAME` of a job the controller's backup holds that
//! moves nothing (I/O, timers, waits; every job it calls in turn the same): the controller runs
//! it between the motions and the path is the file's.

use super::inst::{instructions, Instructions};
use crate::program::{at, Context};
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// How deep calls are followed: a chain longer than this is refused as a loop.
const DEPTH: usize = 16;

/// Checks the jumps and calls of a job's `inst` (module docs).
///
/// # Errors
/// [`stiffid_core::Error::Program`] naming the line of the first jump, loop, branch, macro or
/// call that is not a call of a job of the backup that moves nothing, in a job with motions.
pub(super) fn check(inst: &Instructions, context: &Context) -> Result<()> {
    if inst.motions.is_empty() {
        return Ok(());
    }
    for (line, word, text) in &inst.control {
        let why = match called(word, text) {
            Some(job) => match moves_nothing(job, context, &mut Vec::new()) {
                Ok(()) => continue,
                Err(why) => why,
            },
            None => String::new(),
        };
        return Err(at(*line, format!("{}: a jump, call, macro, loop or branch in a job with motions; the order the controller runs them (or the motions of the job it calls) would not be the file's{why}: write the path as motions of one job", short(word))));
    }
    Ok(())
}

/// The job a `CALL JOB:NAME` (word `word`, text `text`) calls, if it is one by name.
fn called<'t>(word: &str, text: &'t str) -> Option<&'t str> {
    let rest = text.split_once("JOB:").map(|(_, r)| r)?;
    let name = rest.split_whitespace().next()?;
    (word == "CALL").then_some(name)
}

/// Whether job `name` of the backup moves nothing (module docs): `Err` saying why not.
fn moves_nothing(
    name: &str,
    context: &Context,
    chain: &mut Vec<String>,
) -> std::result::Result<(), String> {
    if chain.len() >= DEPTH || chain.iter().any(|c| c.eq_ignore_ascii_case(name)) {
        return Err(format!(
            " (JOB:{} calls itself, or a chain of more than {DEPTH} jobs)",
            short(name)
        ));
    }
    let file = format!("{name}.JBI");
    let Some((path, text)) = context.backup_file(&file) else {
        return Err(format!(" (JOB:{}: give the controller's backup holding {} to have a job that moves nothing passed over)", short(name), short(&file)));
    };
    let inst = instructions(text).map_err(|e| format!(" (JOB:{}, {path}: {e})", short(name)))?;
    if let Some(m) = inst.motions.first() {
        return Err(format!(
            " (JOB:{}, {path} line {}: {}, a motion)",
            short(name),
            m.line,
            m.word
        ));
    }
    chain.push(name.to_string());
    for (line, word, text) in &inst.control {
        if let Some(job) = called(word, text) {
            moves_nothing(job, context, chain)?;
        } else if word == "CALL" || word.starts_with("MACRO") {
            return Err(format!(
                " (JOB:{}, {path} line {line}: {}, a call stiffid cannot follow)",
                short(name),
                short(text)
            ));
        }
    }
    chain.pop();
    Ok(())
}
