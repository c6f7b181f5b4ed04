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

use super::flow::Graph;
use super::statements::english;
use super::va::{entries, Entry};
use super::values;
use crate::program::{at, Context, Left};
use std::collections::HashMap;
use stiffid_core::common::limits::short;
use stiffid_core::Result;

pub(super) use super::values::FILE;

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
    /// The frame number an `OFFSET CONDITION PR[i],UFRAME[j]` (`TOOL_OFFSET CONDITION ..,
    /// UTOOL[j]`) names for a motion's bare offset, and its line.
    pub frames: HashMap<usize, (u32, u64)>,
    /// The motions left as found ([`Context::leave_refused`]): their register is set as the
    /// program runs.
    pub left: Vec<(usize, Left)>,
}

/// Per motion instruction of `instructions` (`motions` says which, `graph` their order) to a
/// position register or offset by one, the register as the program leaves it there
/// ([`super::values`]) or else as the `context`'s backup holds it (module docs); `inherited`,
/// the registers the programs calling this one set, and where. With
/// [`Context::leave_refused`], a motion whose register the run sets is left as found instead.
///
/// # Errors
/// Naming the line (module docs): the first motion whose register is refused.
pub(super) fn read(
    instructions: &[(u64, String)],
    (motions, graph): (&[bool], &Graph),
    inherited: &[(u32, String)],
    context: &Context,
) -> Result<Used> {
    let mut out = Used::default();
    let file = super::va::the_file(context, FILE)?;
    let held = file.map(|(name, text)| (name, entries(text, "$POSREG")));
    let states = values::states(
        instructions,
        graph,
        held.as_ref().map(|(n, e)| (*n, &e[..])),
        inherited,
    );
    for (k, (line, t)) in instructions.iter().enumerate().filter(|(k, _)| motions[*k]) {
        let letter = &t.trim()[..1];
        let state = states[k].clone().unwrap_or_default();
        let target = register(t).map(|n| (None, n, format!("{letter} PR[{n}]")));
        let offset = match offset_of(*line, t, &state) {
            Ok(o) => o.map(|(tool, n, what, frame)| {
                out.frames.extend(frame.map(|f| (k, f)));
                (tool, n, what)
            }),
            Err(why) => {
                leave_or_refuse(&mut out, (k, *line), why, context)?;
                continue;
            }
        };
        for (tool, n, what) in target.into_iter().chain(offset) {
            // A value the run sets: the motion left as found where the context says so.
            let value = match set_by(instructions, n, context, 0) {
                Some(why) => Err(format!("{what}: {why}")),
                None => match values::register(&state, n) {
                    None => Ok(one(*line, &what, n, held.as_ref())?),
                    Some(r) => r
                        .map(|(entry, source)| Register {
                            number: n,
                            entry,
                            source,
                        })
                        .map_err(|why| format!("{what}: {why}")),
                },
            };
            let r = match value {
                Ok(r) => r,
                Err(why) => {
                    out.targets.remove(&k);
                    leave_or_refuse(&mut out, (k, *line), why, context)?;
                    break;
                }
            };
            match tool {
                None => out.targets.insert(k, r).map(|_| ()),
                Some(tool) => out.offsets.insert(k, (tool, r)).map(|_| ()),
            };
        }
    }
    Ok(out)
}

/// A motion's offset: whether in the tool frame, the register, the motion's text naming it, the
/// frame number its condition names and the condition's line.
type Offset = (Option<bool>, u32, String, Option<(u32, u64)>);

/// The motion `k` on `line` left as found for `why` where the `context` says so, else refused.
fn leave_or_refuse(
    out: &mut Used,
    (k, line): (usize, u64),
    why: String,
    context: &Context,
) -> Result<()> {
    match context.leave_refused {
        true => {
            out.left.push((k, Left::passed(line, why)));
            Ok(())
        }
        false => Err(at(line, why)),
    }
}

/// The offset of the motion `t` on `line` with `state` in force: `Offset,PR[i]`, or a bare
/// `Offset` by the `OFFSET CONDITION` in force (`Tool_Offset`: in the tool frame); whether in the
/// tool frame, the register and the motion's text naming it. Why not, where the condition is the
/// controller's or the run's. With the frame number the condition names, and its line.
fn offset_of(
    line: u64,
    t: &str,
    state: &values::State,
) -> std::result::Result<Option<Offset>, String> {
    let letter = &t.trim()[..1];
    // The register may be written apart from its option (`Tool_Offset ,PR[2]`).
    let mut upper = english(&t.to_ascii_uppercase());
    while upper.contains(" ,") {
        upper = upper.replace(" ,", ",");
    }
    let words = || upper.split_whitespace();
    if let Some((tool, n)) = words().find_map(super::options::offset) {
        let word = if tool { "Tool_Offset" } else { "Offset" };
        return Ok(Some((
            Some(tool),
            n,
            format!("{letter} .. {word},PR[{n}]"),
            None,
        )));
    }
    let Some(tool) = words().find_map(super::options::conditioned) else {
        return Ok(None);
    };
    let (word, condition) = match tool {
        true => ("Tool_Offset", "TOOL_OFFSET CONDITION"),
        false => ("Offset", "OFFSET CONDITION"),
    };
    match &state.conditions[usize::from(tool)] {
        values::Condition::Set { register, frame, line: l } => Ok(Some((Some(tool), *register, format!("{letter} .. {word} ({condition} PR[{register}] on line {l})"), frame.map(|f| (f, *l))))),
        values::Condition::None => Err(format!("{letter} .. {word}: no {condition} before the motion on every path in this program: the offset is the register the controller's last {condition} named; set {condition} PR[i] before the motion (line {line})")),
        values::Condition::Run(why) => Err(format!("{letter} .. {word}: {why}")),
    }
}

/// Register `n` of the motion `what` on `line`, as `held` (the backup's `POSREG.VA`: its name
/// and entries) holds it.
fn one(line: u64, what: &str, n: u32, held: Option<&(&str, Vec<Entry>)>) -> Result<Register> {
    let Some((name, held)) = held else {
        return Err(at(line, format!("{what}: a position register holds its value on the controller, not in this program: give the controller's backup with its {FILE}, or copy the value into a P[] position")));
    };
    if held.is_empty() {
        return Err(at(line, format!("{what}: {name} holds no $POSREG entry (empty, cut off, or another file): expected the ASCII variable file a controller's backup writes beside POSREG.SV, its registers under '[*POSREG*]$POSREG ..'; give the backup's {FILE}")));
    }
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
        match values::assigned(&upper) {
            // The program's own assignments are followed along its paths (`values`).
            Some(Some(m)) if m == n && depth > 0 => return Some(format!("the position register is set on line {line} as the program runs ({}): its value is the run's, not the file's; move to a P[] position", short(t.trim()))),
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

/// The position registers `instructions` (of the program `name`) set, each with where: the run's
/// in the programs they call.
pub(super) fn sets(instructions: &[(u64, String)], name: &str) -> Vec<(u32, String)> {
    let mut out = Vec::new();
    for (line, t) in instructions {
        if let Some(Some(n)) = values::assigned(&english(&t.trim().to_ascii_uppercase())) {
            out.push((n, format!("PR[{n}] is set by {name} on its line {line} ({}) as the program runs: its value is the run's", short(t.trim()))));
        }
    }
    out
}
