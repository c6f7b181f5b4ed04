//! The jumps, calls, loops and branches of a job with motions (module docs of [`super`]).
//!
//! A job's positions are pulses, which no instruction around the motions changes (the tool file
//! is each motion's own), so each motion is read where it is whatever path reaches it: jumps to
//! the job's labels (`JUMP *LABEL`, also with `IF ..`), `IFTHEN`/`ELSEIF`/`ELSE`/`ENDIF`,
//! `FOR`/`NEXT`, `WHILE`/`ENDWHILE`, `SWITCH`/`CASE`/`DEFAULT`/`ENDSWITCH` and `RET` are
//! followed. Refused naming the line: a jump to a label the job does not hold or holds twice, to
//! a label or job taken from a variable (`JUMP LABEL:B000`), to another job (`JUMP JOB:NAME`,
//! which does not come back), weaving (`WVON`) in a job with jumps, loops or branches (which
//! motions it weaves is the run's), a macro, and a call but a `CALL JOB:NAME` of a job the
//! controller's backup holds that moves nothing (I/O, timers, waits; every job it calls in turn
//! the same): the controller runs it between the motions and the path is the file's.

use super::inst::{instructions, Instructions};
use crate::program::{at, Context};
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// How deep calls are followed: a chain longer than this is refused as a loop.
const DEPTH: usize = 16;

/// Checks the jumps and calls of a job's `inst` (module docs): the calls of jobs of the
/// backup that move, which the caller reads ([`super::called`]).
///
/// # Errors
/// [`stiffid_core::Error::Program`] naming the line of the first jump, macro or call refused
/// (module docs), in a job with motions.
pub(super) fn check<'a>(inst: &Instructions, context: &Context<'a>) -> Result<Vec<Call<'a>>> {
    let mut moving = Vec::new();
    labels_once(inst)?;
    // The first jump, loop or branch followed.
    let mut flow: Option<u64> = None;
    for (line, word, text) in &inst.control {
        let job = called(word, text);
        let held = job.and_then(|j| context.backup_file(&format!("{j}.JBI")));
        if let (Some(job), Some((file, text))) = (job, held) {
            if moves_nothing(job, context, &mut Vec::new()).is_err() {
                moving.push(Call {
                    line: *line,
                    name: job.to_ascii_uppercase(),
                    file,
                    text,
                });
            }
            continue;
        }
        if inst.motions.is_empty() {
            continue;
        }
        let why = match word.as_str() {
            "CALL" => match job {
                Some(job) => match moves_nothing(job, context, &mut Vec::new()) {
                    Ok(()) => continue,
                    Err(why) => why,
                },
                None => " (a job named by a variable, which the job does not say)".into(),
            },
            "JUMP" => match jump(inst, text) {
                Ok(()) => {
                    flow.get_or_insert(*line);
                    continue;
                }
                Err(why) => return Err(at(*line, format!("{}: {why}", short(text)))),
            },
            w if w.starts_with("MACRO") => String::new(),
            _ => {
                flow.get_or_insert(*line);
                continue;
            }
        };
        return Err(at(*line, format!("{}: a jump, call, macro, loop or branch in a job with motions; the order the controller runs them (or the motions of the job it calls) would not be the file's{why}: write the path as motions of one job", short(word))));
    }
    match (inst.weaves, flow) {
        (Some(w), Some(f)) => Err(at(w, format!("WVON: weaving in a job with jumps, loops or branches (line {f}): which motions it weaves across the path is decided as the job runs; remove it or compensate the job without it"))),
        _ => Ok(moving),
    }
}

/// A call of a job of the backup that moves: its line, the job's name (upper case), its file's
/// name as given and its text.
pub(super) struct Call<'a> {
    pub line: u64,
    pub name: String,
    pub file: &'a str,
    pub text: &'a str,
}

/// Refuses a label the job holds twice: where a jump to it goes is not the file's to say.
fn labels_once(inst: &Instructions) -> Result<()> {
    for (k, (name, line)) in inst.labels.iter().enumerate() {
        if let Some((_, first)) = inst.labels[..k].iter().find(|(n, _)| n == name) {
            return Err(at(*line, format!("{name}: the label is also on line {first}; a JUMP to it goes to one of them, which is not the file's to say: give each label one place")));
        }
    }
    Ok(())
}

/// Checks the jump `text` (`JUMP *LABEL ..`) goes to a label of the job: `Err` saying why not.
fn jump(inst: &Instructions, text: &str) -> std::result::Result<(), String> {
    let target = text
        .split_whitespace()
        .nth(1)
        .unwrap_or("")
        .to_ascii_uppercase();
    if target.starts_with("JOB:") {
        return Err("a jump to another job, which does not come back: the motions after it are that job's; compensate each job on its own".into());
    }
    if !target.starts_with('*') {
        return Err("a jump to a label taken from a variable as the job runs, which the job does not say: jump to a label *NAME".into());
    }
    match inst.labels.iter().any(|(n, _)| *n == target) {
        true => Ok(()),
        false => Err(format!(
            "a jump to a label the job does not hold ({target})"
        )),
    }
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
