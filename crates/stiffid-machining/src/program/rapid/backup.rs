//! The other modules of the task, from the controller's backup ([`Context::backup`]): the
//! `robtarget`s, `jointtarget`s, `tooldata`, `wobjdata` and `speeddata` they declare, which a
//! module's motions name without declaring (ABB, *Technical reference manual - RAPID kernel*:
//! a task's modules share their global data). The module's own declarations hide theirs. A
//! target of another module is compensated and declared again in the module, `LOCAL` (which hides
//! the other module's within it), on the line after `MODULE`, its values the compensated ones;
//! the other module is never written.

use super::{declarations, shared, statements, without_comments, Data};
use crate::program::cartesian::Frame;
use crate::program::points::Foreign;
use crate::program::{Context, JointTarget};
use stiffid_core::{Error, Result};

/// `data`, the module `text`'s own, with the data of the backup's other modules that it does not
/// declare (module docs); `code` is `text` with its comments blanked.
///
/// # Errors
/// [`Error::Parse`] naming a backup module whose declarations cannot be read.
pub(super) fn merge(mut data: Data, (text, code): (&str, &str), context: &Context) -> Result<Data> {
    let extensions = super::Rapid::BACKUP;
    let modules = context.backup_with(|n| {
        let e = n
            .rsplit_once('.')
            .map_or("", |(_, e)| e)
            .to_ascii_lowercase();
        extensions.contains(&e.as_str())
    });
    let insert = after_module_line(code);
    // The backup module each tool and work object the module does not declare comes from.
    let mut from: std::collections::HashMap<String, &str> = Default::default();
    let own = shared::values(code, &statements(code));
    let mut others = Vec::new();
    for (file, other) in modules.into_iter().filter(|(_, t)| *t != text) {
        let other_code = without_comments(other);
        let unreadable = |e: Error| Error::Parse {
            source_name: file.to_string(),
            message: format!("a module of the controller's backup: {e}"),
        };
        crate::program::ends::check(other, crate::program::Dialect::Rapid).map_err(unreadable)?;
        let other_statements = statements(&other_code);
        let values = shared::values(&other_code, &other_statements);
        let mut found = declarations(&other_code, &other_statements).map_err(unreadable)?;
        hide_local(&mut found, &values);
        others.push((file, values));
        for (k, v) in found.frames {
            let v = foreign(v, file);
            match (data.frames.get(&k), from.get(&k)) {
                (None, _) => {
                    from.insert(k.clone(), file);
                    data.frames.insert(k, v);
                }
                // Declared alike in two modules (a `PERS` shared by the task): one value.
                (Some(f), Some(_)) if *f == v => {}
                (Some(_), Some(first)) => {
                    let why = format!("{k} is declared in {first} and in {file} with two values: the controller holds one of them; give the task's modules one declaration");
                    data.frames.insert(k, Frame::Unknown(0, why));
                }
                (Some(_), None) => {}
            }
        }
        for (k, v) in found.speeds {
            data.speeds.entry(k).or_insert(v);
        }
        for (k, v) in found.nums {
            data.nums.entry(k).or_insert(v);
        }
        for (k, line) in &found.renum.set_on {
            let why = format!("num {k} is set in {} on its line {line}, so its value is the controller's as the task runs", crate::program::file_name(file));
            if data.nums.contains_key(k) {
                data.nums.insert(k.clone(), Err(why.clone()));
                data.renum.set_elsewhere(k, &why);
            }
        }
        for (k, v) in found.targets {
            if data.targets.contains_key(&k) {
                continue;
            }
            // Assigned in its own module: the line is that module's, named with it.
            let v = match found.assigned.get(&k) {
                Some(l) => Err(format!("assigned in {} on its line {l}, so its value at the motion is the controller's, not the module's", crate::program::file_name(file))),
                None => v.and_then(|t| elsewhere(t, (file, other), insert)),
            };
            data.targets.insert(k, v);
        }
    }
    for (name, why) in shared::ambiguous(&own, &others) {
        refuse(&mut data, &name, &why);
    }
    Ok(data)
}

/// `found`, another module's data, without what it declares `LOCAL` (its `values`): seen by
/// that module alone (*RAPID kernel*: scope rules).
fn hide_local(found: &mut Data, values: &shared::Values) {
    let local = |k: &String| {
        let name = k.split('{').next().unwrap_or(k);
        values.get(name).is_some_and(|v| v.2)
    };
    found.targets.retain(|k, _| !local(k));
    found.frames.retain(|k, _| !local(k));
    found.speeds.retain(|k, _| !local(k));
    found.nums.retain(|k, _| !local(k));
}

/// `data`'s datum `name` (an array's elements too) refused for `why`: two modules of the task
/// declare it with two values ([`shared::ambiguous`]).
fn refuse(data: &mut Data, name: &str, why: &str) {
    let mine = |k: &String| k == name || k.split('{').next() == Some(name);
    for (_, t) in data.targets.iter_mut().filter(|(k, _)| mine(k)) {
        *t = Err(why.to_string());
    }
    if let Some(f) = data.frames.get_mut(name) {
        *f = Frame::Unknown(0, why.to_string());
    }
    if let Some(v) = data.speeds.get_mut(name) {
        *v = Err(why.to_string());
    }
    if let Some(v) = data.nums.get_mut(name) {
        *v = Err(why.to_string());
    }
}

/// A tool or work object `frame` of the backup's module `file`, as the module's motions read it:
/// its line is none of the module's (0: the motion that names it stands for it, `lookup` of
/// `cartesian`), and a frame refused names its own file and line.
fn foreign(frame: Frame, file: &str) -> Frame {
    let name = crate::program::file_name(file);
    match frame {
        Frame::Stated(_, f) => Frame::Stated(0, f),
        Frame::Unknown(l, why) => Frame::Unknown(0, format!("{why} ({name}, line {l})")),
        other => other,
    }
}

/// The byte of `code` after the line that opens the module (`MODULE name`), 0 without one.
fn after_module_line(code: &str) -> usize {
    let mut at = 0;
    for line in code.split_inclusive('\n') {
        at += line.len();
        if line.trim_start().to_ascii_lowercase().starts_with("module") {
            return at;
        }
    }
    0
}

/// The target `t` of the module `file` (its text `other`) as the program declares its copy at
/// byte `insert` (module docs), or why it cannot.
fn elsewhere(
    t: JointTarget,
    (file, other): (&str, &str),
    insert: usize,
) -> std::result::Result<JointTarget, String> {
    let Some(p) = t.point.as_deref().cloned() else {
        return Err(format!("declared in {file} on a line it shares with another statement: declare it on a line of its own, or in this module"));
    };
    let decl = &other[p.declaration.clone()];
    let lead = decl.len() - decl.trim_start().len();
    let body = &decl[lead..];
    let lower = body.to_ascii_lowercase();
    let (prefix, skip) = match () {
        _ if lower.starts_with("local") => ("", 0),
        _ if lower.starts_with("task") => ("LOCAL", 4),
        _ => ("LOCAL ", 0),
    };
    let text = format!("{}{prefix}{}", &decl[..lead], &body[skip..]);
    let grown = prefix.len() - skip;
    let Some(at) = p.declaration.start.checked_sub(grown) else {
        return Err(format!(
            "declared in {file} on its first line: declare it in this module"
        ));
    };
    let name = p.name.start - at..p.name.end - at;
    Ok(t.declared_elsewhere(
        Foreign {
            text,
            at,
            computed: false,
        },
        name,
        insert,
    ))
}
