//! A motion to a position register (`J PR[i] ..`, `L PR[i:name] ..`), read from the controller's
//! backup: `POSREG.VA` ([`super::va`], `$POSREG[1,i]`) holds its value as the controller does
//! when no program changes it. A position register is the controller's, shared by every program
//! on it: stiffid never changes it. The motion is compensated to a new position of the program
//! (`P[n]`, [`super::copies`]), the register left as it is.
//!
//! Refused naming the line: a register the program sets (`PR[i]=LPOS`, `PR[i,3]=..`, `PR[R[1]]=..`,
//! a motion's `Skip,LBL[..],PR[i]=LPOS`: its value is the run's), or a program it calls or runs
//! sets (read from the backup's `PROG.LS`, followed 16 deep); a call or run of a program the
//! backup does not hold as `PROG.LS` (a KAREL program: it may set the register); a register
//! without `POSREG.VA`, or `Uninitialized` there. With `--leave-refused`
//! ([`Context::leave_refused`]), a motion whose register the run sets is left as found instead,
//! named with its line and why.

use super::statements::english;
use super::va::{entries, Entry};
use crate::program::{at, Context, Left};
use std::collections::HashMap;
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// The file's name in a backup.
pub(super) const FILE: &str = "POSREG.VA";

/// How deep the programs called are searched for an assignment.
const DEPTH: usize = 16;

/// A register a motion moves to, as the backup holds it: its number, its entry and where the
/// file states it.
#[derive(Debug, Clone)]
pub(super) struct Register {
    pub number: u32,
    pub entry: Entry,
    pub source: String,
}

/// The registers the motions use, by motion instruction: the one it moves to, and the one it
/// is offset by (`Offset,PR[i]`: `false`, `Tool_Offset,PR[i]`: `true`).
#[derive(Debug, Default)]
pub(super) struct Used {
    pub targets: HashMap<usize, Register>,
    pub offsets: HashMap<usize, (bool, Register)>,
    /// The motions left as found ([`Context::leave_refused`]): their register is set as the
    /// program runs.
    pub left: Vec<(usize, Left)>,
}

/// Per motion instruction of `instructions` (`motions` says which) to a position register or
/// offset by one, the register as the `context`'s backup holds it (module docs); with
/// [`Context::leave_refused`], a motion whose register the run sets is left as found instead.
///
/// # Errors
/// Naming the line (module docs): the first motion whose register is refused.
pub(super) fn read(
    instructions: &[(u64, String)],
    motions: &[bool],
    context: &Context,
) -> Result<Used> {
    let mut out = Used::default();
    let file = super::va::the_file(context, FILE)?;
    let held = file.map(|(name, text)| (name, entries(text, "$POSREG")));
    for (k, (line, t)) in instructions.iter().enumerate().filter(|(k, _)| motions[*k]) {
        let letter = &t.trim()[..1];
        let offset = english(&t.to_ascii_uppercase())
            .split_whitespace()
            .find_map(super::options::offset);
        let target = register(t).map(|n| (None, n, format!("{letter} PR[{n}]")));
        let offset = offset.map(|(tool, n)| {
            let word = if tool { "Tool_Offset" } else { "Offset" };
            (Some(tool), n, format!("{letter} .. {word},PR[{n}]"))
        });
        for (tool, n, what) in target.into_iter().chain(offset) {
            // A value the run sets: the motion left as found where the context says so.
            if let Some(why) = set_by(instructions, n, context, 0) {
                let why = format!("{what}: {why}");
                match context.leave_refused {
                    true => {
                        out.targets.remove(&k);
                        out.left.push((k, Left::passed(*line, why)));
                    }
                    false => return Err(at(*line, why)),
                }
                break;
            }
            let r = one(*line, &what, n, held.as_ref())?;
            match tool {
                None => out.targets.insert(k, r).map(|_| ()),
                Some(tool) => out.offsets.insert(k, (tool, r)).map(|_| ()),
            };
        }
    }
    Ok(out)
}

/// Register `n` of the motion `what` on `line`, as `held` (the backup's `POSREG.VA`: its name
/// and entries) holds it.
fn one(line: u64, what: &str, n: u32, held: Option<&(&str, Vec<Entry>)>) -> Result<Register> {
    let Some((name, held)) = held else {
        return Err(at(line, format!("{what}: a position register holds its value on the controller, not in this program: give the controller's backup with its {FILE}, or copy the value into a P[] position")));
    };
    let entry = held.iter().find(|e| e.group == 1 && e.number == n);
    let entry = match entry.map(|e| (e, &e.value)) {
        Some((e, Ok(Some(_)))) => e.clone(),
        Some((e, Ok(None))) => return Err(at(line, format!("{what}: {name} line {} gives PR[{n}] no value (Uninitialized): the register is set as programs run; copy its value into a P[] position", e.line))),
        Some((_, Err((l, why)))) => return Err(at(line, format!("{what}: {name} line {l}: {why}"))),
        None => return Err(at(line, format!("{what}: {name} holds no PR[{n}] of motion group 1 (a controller's backup lists every register up to its count, Uninitialized ones too: is the file cut off?)"))),
    };
    let source = format!("{name} line {}", entry.line);
    Ok(Register {
        number: n,
        entry,
        source,
    })
}

/// Why register `n`'s value is not the backup's where `instructions` run: the first line that
/// sets it, or calls or runs a program that sets it or that the `context`'s backup does not
/// hold; `None` where nothing does.
fn set_by(
    instructions: &[(u64, String)],
    n: u32,
    context: &Context,
    depth: usize,
) -> Option<String> {
    for (line, t) in instructions {
        let upper = english(&t.trim().to_ascii_uppercase());
        match assigned(&upper) {
            Some(Some(m)) if m == n => return Some(format!("the position register is set on line {line} as the program runs ({}): its value is the run's, not the file's; move to a P[] position", short(t.trim()))),
            Some(None) => return Some(format!("line {line} sets a position register chosen as the program runs ({}), which may be PR[{n}]: its value is the run's; move to a P[] position", short(t.trim()))),
            _ => {}
        }
        let Some(callee) = called(&upper) else {
            continue;
        };
        let inner = context
            .backup_file(&format!("{callee}.LS"))
            .and_then(|(file, text)| Some((file, super::instructions(text).ok()?)));
        let Some((file, inner)) = inner else {
            return Some(format!("line {line} calls {callee}, which the backup does not hold as {callee}.LS (a KAREL program, or one not given): it may set PR[{n}] as it runs; give the program with the backup, or move to a P[] position"));
        };
        if depth >= DEPTH {
            return Some(format!("line {line} calls {callee}, whose calls stiffid follows {DEPTH} deep: it may set PR[{n}]"));
        }
        if let Some(why) = set_by(&inner, n, context, depth + 1) {
            return Some(format!("line {line} calls {callee}: {file}: {why}"));
        }
    }
    None
}

/// The program instruction `upper` (upper case, English) calls or runs (`CALL NAME`, `RUN
/// NAME`, a branch's `IF ..,CALL NAME`, a macro).
fn called(upper: &str) -> Option<String> {
    match upper.strip_prefix("RUN ") {
        Some(rest) => rest.split(['(', ' ', ';']).next().map(str::to_string),
        None => super::calls::called(upper),
    }
    .filter(|n| !n.is_empty())
}

/// The register number of a motion `t` to a position register (`J PR[3:home] ..`), if it is one;
/// not an element of one (`J PR[3,1]`, a number: no motion the controller loads), which the
/// motion's reader refuses.
fn register(t: &str) -> Option<u32> {
    let rest = t.trim().get(1..)?.trim_start().strip_prefix("PR[")?;
    rest.split([']', ':']).next()?.trim().parse().ok()
}

/// Whether instruction `upper` (upper case, English) sets a position register: `Some(Some(n))`
/// register `n` (or one of its elements), `Some(None)` one chosen at run time (`PR[R[1]]=`);
/// `None` where it sets none. An assignment is a `PR[..]` followed by `=` outside a condition
/// (`IF`, `WAIT`, `SELECT` and its cases compare): a statement `PR[1]=LPOS`, a motion's skip
/// option `Skip,LBL[2],PR[6]=LPOS`.
fn assigned(upper: &str) -> Option<Option<u32>> {
    let compares = ["IF", "WAIT", "SELECT", "=", "ELSE"];
    if compares.iter().any(|w| upper.starts_with(w)) {
        return None;
    }
    let mut from = 0;
    while let Some(i) = upper[from..].find("PR[").map(|i| from + i) {
        from = i + 3;
        if upper[..i].ends_with(|c: char| c.is_ascii_alphanumeric() || c == '_' || c == '$') {
            continue;
        }
        let Some(close) = closing(&upper[i + 3..]).map(|c| i + 3 + c) else {
            continue;
        };
        if !upper[close + 1..].trim_start().starts_with('=') {
            continue;
        }
        let inside = upper[i + 3..close].trim();
        let inside = match inside.strip_prefix("GP") {
            Some(r) => r.split_once(':').map_or(r, |(_, r)| r),
            None => inside,
        };
        let number = inside.split([':', ',']).next().map(str::trim);
        return Some(number.and_then(|d| d.parse().ok()));
    }
    None
}

/// The byte of the `]` closing the bracket opened before `s`, brackets inside counted.
fn closing(s: &str) -> Option<usize> {
    let mut depth = 0usize;
    for (i, c) in s.char_indices() {
        match c {
            '[' => depth += 1,
            ']' if depth == 0 => return Some(i),
            ']' => depth -= 1,
            _ => {}
        }
    }
    None
}
