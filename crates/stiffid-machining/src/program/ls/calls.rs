//! A call between two motions of a program (`CALL NAME`, `CALL NAME(1, 2)`, a macro `NAME` or
//! `NAME(1)`) passed over when the controller's backup holds the program called (`NAME.LS`) and
//! it moves nothing: no motion, no frame selected or set, no `ABORT`, and every program it
//! calls in turn the same (followed [`DEPTH`] deep); the controller runs it between the motions
//! and the path is the file's.

use super::statements::{conditional_call, english, macro_call, sets_frame};
use crate::program::Context;

/// How deep calls are followed: a longer chain (or one that loops) is not passed over.
const DEPTH: usize = 16;

/// Whether instruction `t` is a call of a program of the `context`'s backup that moves nothing
/// (module docs).
pub(super) fn passed_over(t: &str, context: &Context) -> bool {
    called(t).is_some_and(|name| moves_nothing(&name, context, &mut Vec::new()))
}

/// The program of the `context`'s backup instruction `t` calls, when it holds one that may move
/// (not [`passed_over`]): its name (upper case), its file's name as given and its text.
pub(super) fn moving<'a>(t: &str, context: &Context<'a>) -> Option<(String, &'a str, &'a str)> {
    let name = called(t)?;
    let (file, text) = context.backup_file(&format!("{name}.LS"))?;
    (!moves_nothing(&name, context, &mut Vec::new())).then_some((name, file, text))
}

/// The lines of the first `UFRAME_NUM=` and `UTOOL_NUM=` of program `text` or of a program of the
/// `context`'s backup it calls (followed [`DEPTH`] deep), if any: the frames it may leave
/// selected.
pub(super) fn selections(
    text: &str,
    context: &Context,
    depth: usize,
) -> (Option<u64>, Option<u64>) {
    let mut out = (None, None);
    let Ok(instructions) = super::instructions(text) else {
        return out;
    };
    for (line, t) in &instructions {
        let upper = english(&t.trim().to_ascii_uppercase());
        if upper.starts_with("UFRAME_NUM") {
            out.0 = out.0.or(Some(*line));
        }
        if upper.starts_with("UTOOL_NUM") {
            out.1 = out.1.or(Some(*line));
        }
        let callee = called(t).and_then(|n| context.backup_file(&format!("{n}.LS")));
        if let (Some((_, inner)), true) = (callee, depth < DEPTH) {
            let (u, k) = selections(inner, context, depth + 1);
            out = (out.0.or(u.map(|_| *line)), out.1.or(k.map(|_| *line)));
        }
    }
    out
}

/// The program instruction `t` calls by name (`CALL NAME ..`, a branch's `IF ..,CALL NAME`, a
/// macro `NAME(..)`), upper case.
pub(super) fn called(t: &str) -> Option<String> {
    let upper = english(&t.trim().to_ascii_uppercase());
    let name = match conditional_call(&upper) {
        Some(rest) => rest,
        None if macro_call(&upper) => upper.as_str(),
        None => return None,
    };
    let name = name.split(['(', ' ']).next().unwrap_or("");
    (!name.is_empty()).then(|| name.to_string())
}

/// Whether program `name` of the backup moves nothing (module docs).
fn moves_nothing(name: &str, context: &Context, chain: &mut Vec<String>) -> bool {
    if chain.len() >= DEPTH || chain.iter().any(|c| c == name) {
        return false;
    }
    let Some((_, text)) = context.backup_file(&format!("{name}.LS")) else {
        return false;
    };
    // A program cut off may have lost its motions: not passed over (read, and refused).
    let whole = crate::program::ends::check(text, crate::program::Dialect::FanucLs).is_ok();
    let Ok(instructions) = super::instructions(text)
        .map_err(|_| ())
        .and_then(|i| match whole {
            true => Ok(i),
            false => Err(()),
        })
    else {
        return false;
    };
    chain.push(name.to_string());
    let nothing = instructions.iter().all(|(_, t)| {
        let t = t.trim();
        let upper = english(&t.to_ascii_uppercase());
        let selects = upper.starts_with("UFRAME_NUM") || upper.starts_with("UTOOL_NUM");
        let moves = super::motion::rest(t).is_some() || upper.contains("P[");
        let stops = upper.starts_with("ABORT");
        let calls_on = called(t).is_none_or(|n| moves_nothing(&n, context, chain));
        !(selects || moves || stops || sets_frame(&upper)) && calls_on
    });
    chain.pop();
    nothing
}
