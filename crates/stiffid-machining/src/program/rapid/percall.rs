//! A routine of the module with parameters (`PROC move_to(robtarget p, num dz)`), read at each of
//! its calls in the module with that call's arguments (*RAPID overview*: routine parameters), not
//! where it is: a `robtarget`, `jointtarget`, `tooldata`, `wobjdata` or `speeddata` argument that
//! names a datum the caller reads is that datum, a `num` argument whose value the module states
//! (a number, arithmetic of `num` data, module `num`) is that value; any other argument leaves
//! its parameter the run's, refused at the motion that uses it, naming the call. Each call's
//! motions are compensated in place: a target argument is compensated in its declaration, and
//! where two calls need two values of it, the later call names a copy (`p1_2`) declared after it;
//! where one call's motions need two values of its one argument, refused naming the call.

use super::called::{Bindings, Task, MAX_READS};
use super::state::{Conf, Entry, Here, Module};
use super::Data;
use crate::program::{at, Context, JointTarget, Left};
use stiffid_core::{Error, Result};

/// How a module is read (module `read`): its text, offset, entry, context and the task's calls.
pub(super) type Reader = fn(&str, usize, Option<&Entry>, &Context, &mut Task) -> Result<Module>;

/// The targets and motions left of the call of the module's routine `name` (its arguments
/// `args`, up to the `;`) at `here`, read alone with the call's arguments bound, with the
/// configuration monitoring `conf` in force at the call (unknown after it where the routine
/// switches it); `module` reads it.
pub(super) fn read(
    here: &Here,
    (name, args): (&str, &str),
    (data, conf): (&Data, &mut Conf),
    (context, task): (&Context, &mut Task),
    module: Reader,
) -> Result<(Vec<JointTarget>, Vec<Left>)> {
    let line = here.statement.line;
    let key = name.to_ascii_lowercase();
    let (text, offset) = here.module;
    let link = format!("{key}@{offset}");
    if task.chain.contains(&link) || task.chain.len() >= 16 {
        return Err(at(
            line,
            format!("{name}: the routine calls itself; stiffid follows calls that end"),
        ));
    }
    task.reads += 1;
    if task.reads > MAX_READS {
        return Err(at(line, format!("{name}: more than {MAX_READS} calls of routines with parameters read: stiffid reads each where it is called")));
    }
    let header = super::calls::header(text, &key);
    // The arguments end the call's statement: where they are in the text, so that a target
    // argument the call's motions need twice is renamed there to its copy.
    let renamed = here.statement.span.end - args.len();
    let entry = Entry {
        name: key,
        bindings: Bindings::of(&header, (args, line, Some(renamed)), data),
        place: here.place,
        conf: conf.clone(),
        alone: true,
    };
    task.chain.push(link);
    let read = module(text, offset, Some(&entry), context, task);
    task.chain.pop();
    let called = format!("in {name}, called on line {line}");
    let read = read.map_err(|e| match e {
        Error::Program { line: l, message } => at(l, format!("{message} ({called})")),
        other => other,
    })?;
    if read.switches_own {
        let why = format!("the call of {name} on line {line} switches configuration monitoring on some path; set ConfJ and ConfL after the call");
        conf.0 = [Err(why.clone()), Err(why)];
    }
    let left = (read.left.into_iter())
        .map(|l| Left {
            why: format!("{} ({called})", l.why),
            ..l
        })
        .collect();
    Ok((read.targets, left))
}
