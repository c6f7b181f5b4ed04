//! The jobs of the controller's backup a job calls that move (`CALL JOB:NAME`, also with `IF
//! ..`), read where they are called: each one's motions compensated in place in its own file,
//! its targets after the caller's, its text after every text before it (the whole program's
//! text: the job's, then each job it calls, in the order of its first call; a job called again is
//! read once). Refused naming the call's line: a job that calls itself, one called from two jobs,
//! one whose motions move other axes or in other pulses than the caller's; a refusal inside it
//! names the call, its file and its line.

use super::calls::Call;
use super::read_job;
use crate::program::Read;
use crate::program::{at, Context};
use stiffid_core::{Error, Result};

/// `read` (the job `text`'s own targets) with the jobs of `moving` it calls, through the jobs
/// of `chain`, read after it (module docs).
///
/// # Errors
/// Naming the call's line (module docs).
pub(super) fn read(
    mut read: Read,
    (text, moving): (&str, &[Call]),
    (context, sets): (&Context, &[super::variables::Set]),
    chain: &mut Vec<String>,
) -> Result<Read> {
    let mut total = text.len();
    let mut done: Vec<&str> = Vec::new();
    for call in moving {
        if done.contains(&call.name.as_str()) {
            continue;
        }
        done.push(&call.name);
        let refuse = |why: String| at(call.line, format!("CALL JOB:{}: {why}", call.name));
        if chain.contains(&call.name) || chain.len() >= 16 {
            return Err(refuse(format!(
                "the job calls itself through {}; stiffid follows calls that end",
                chain.join(", ")
            )));
        }
        chain.push(call.name.clone());
        let within = |e: Error| match e {
            Error::Program { line, message } => {
                refuse(format!("{} line {line}: {message}", call.file))
            }
            other => other,
        };
        let inner = read_job(call.text, (context, sets), chain).map_err(within)?;
        chain.pop();
        if read.targets.is_empty() && read.axes.is_empty() {
            read.pulses.clone_from(&inner.pulses);
        }
        if inner.axes != read.axes || (!inner.targets.is_empty() && inner.pulses != read.pulses) {
            return Err(refuse(format!("{} moves other axes, or in other pulses, than this job ({}); stiffid compensates one set of axes: give both jobs the same groups", call.file, read.axes.join(", "))));
        }
        let offset = total;
        total += call.text.len();
        read.called
            .push((call.file.to_string(), call.text.to_string()));
        for (file, t) in inner.called {
            if read.called.iter().any(|(f, _)| *f == file) {
                return Err(refuse(format!("{file} is called from two jobs; stiffid writes each job once: call it from one")));
            }
            total += t.len();
            read.called.push((file, t));
        }
        read.targets
            .extend(inner.targets.into_iter().map(|t| t.shifted(offset)));
        (read.notes).extend(inner.notes.iter().map(|n| format!("{}: {n}", call.file)));
    }
    Ok(read)
}
