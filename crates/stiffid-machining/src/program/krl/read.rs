//! A KRL program read line by line (module docs of [`super`]): its motions in order, each with
//! its frames ([`super::frames`]) and speed ([`super::speed`]), its points from the `.src` or its
//! `.dat` ([`super::declare`]), what is in force at each followed through loops, branches and
//! the routines of the file ([`super::state`], [`crate::program::paths`]).

use super::declare::{declarations, words, Declarations};
use super::frames::{compact, Frames};
use super::motion::{motion, Context, Found};
use super::speed;
use super::state::{same, State};
use crate::program::cartesian::Frame;
use crate::program::controller::Read;
use crate::program::paths::{Closed, Join, Kind, Paths};
use crate::program::speed::Speed;
use crate::program::{at, JointTarget, Left};
use std::collections::HashMap;
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// Every joint target of the `.src` `text` (with its `.dat` and the controller's home posture
/// from `context`), in the order of its motions (module docs), the program's external axes
/// (`E1` to the highest `E`n any target gives) and the motions left as found
/// ([`crate::program::Context::leave_refused`]).
///
/// # Errors
/// [`stiffid_core::Error::Program`] naming the line: a motion outside the subset, to a point
/// neither file declares, a `GOTO` in a program with motions; a motion whose frames or point
/// only the run decides (paths that set different frames, a value assigned at run time), unless
/// the context leaves it as found.
pub(crate) fn targets(text: &str, context: &crate::program::Context) -> Result<Read> {
    let data = context.data;
    let declared = declarations(text, data, &super::declare::global_lists(context, data))?;
    let mut at_motion = Context {
        declared: &declared,
        data: data.is_some(),
        routine: 0,
    };
    let setters = frame_routines(text, &declared);
    let local = routines(text);
    let call_lines = call_lines(text, &local);
    let mut out = Vec::new();
    let mut left = Vec::new();
    let tables = super::backup::tables(context)?;
    let mut state = State {
        frames: Frames::new(unset),
        speed: speed::Krl::new(),
    };
    state.frames.table = tables.clone();
    let mut paths: Paths<State> = Paths::default();
    // The state at each call of a routine of the file, by its upper-case name.
    let mut calls: HashMap<String, Vec<(u64, State)>> = HashMap::new();
    let mut jump: Option<u64> = None;
    for (line, start, l) in crate::program::lines(text) {
        let code = l.split(';').next().unwrap_or("");
        let words = words(code);
        let first = words.first().map(String::as_str).unwrap_or("");
        well_formed(line, first)?;
        if let Some(name) = routine_name(&words) {
            at_motion.routine += 1;
            paths.clear();
            if at_motion.routine > 1 {
                state = entry(&name, line, &calls, &call_lines);
                for (k, f) in &tables {
                    state.frames.table.entry(*k).or_insert_with(|| f.clone());
                }
            }
            continue;
        }
        if flow(line, first, (&mut paths, &mut state), &mut out) {
            continue;
        }
        if first == "GOTO" {
            jump.get_or_insert(line);
        }
        if let Some((name, _)) = called(code, &local) {
            calls
                .entry(name.to_string())
                .or_default()
                .push((line, state.clone()));
        }
        let framed = state.frames.set(line, code, &declared.fdats);
        if let Some((name, l)) = called(code, &setters) {
            state.frames.unsettle(line, format!("line {line} calls {name}, which sets a frame (line {l}): the frames after the call are the ones it leaves, which stiffid does not follow; set them again after the call"));
        }
        if state.speed.set(line, code)? || framed {
            continue;
        }
        let targets = match motion((line, start), code, first, &at_motion)? {
            Found::Nothing => continue,
            Found::RunTime(why, point) => {
                let error = at(line, why);
                context.leave(&mut left, error)?;
                if let (Some(l), Some(p)) = (left.last_mut(), point) {
                    l.point = Some(p);
                }
                continue;
            }
            Found::Home(what) => {
                left.push(Left::passed(line, what));
                continue;
            }
            Found::Targets(t) => t,
        };
        let (base, tool) = state.frames.motion(line, code, &declared.fdats);
        let speed = state.speed.motion(line, first, code)?;
        for mut target in targets {
            target.speed = speed.clone();
            if let Some(c) = target.cartesian.as_deref_mut() {
                let at_motion = |f: &Frame| match f {
                    Frame::Unknown(0, why) => Frame::Unknown(line, why.clone()),
                    other => other.clone(),
                };
                (c.frame, c.tool) = (at_motion(&base), at_motion(&tool));
                c.follows = !matches!(first, "PTP" | "SPTP");
            }
            out.push(target);
        }
    }
    if let (Some(line), false) = (jump, out.is_empty()) {
        return Err(at(line, "GOTO: a jump in a program with motions; the order the controller runs them would not be the file's: write the path as straight-line code".into()));
    }
    if context.leave_refused {
        out = leave_unknown(out, &mut left);
    }
    let n = out.iter().map(|t| t.external.len()).max().unwrap_or(0);
    Ok(Read {
        targets: out,
        axes: (1..=n).map(|k| format!("E{k}")).collect(),
        left,
        ..Read::default()
    })
}

/// A frame not set before a motion: the controller's.
fn unset(name: &str) -> Frame {
    Frame::Unknown(0, format!("no {name} set before this Cartesian motion: its frame is the controller's, which the program does not state; set it in the program (an inline form's FDAT, {name} = {{X .., Y .., Z .., A .., B .., C ..}} or {}_DATA[n])", &name[1..]))
}

/// Takes a line whose first word (upper case) is `first` that opens, divides or closes a loop
/// or branch ([`crate::program::paths`]); whether it did. A loop whose body ends with other
/// frames than it began makes the frames of its motions before the change unknown.
fn flow(
    line: u64,
    first: &str,
    (paths, state): (&mut Paths<State>, &mut State),
    out: &mut [JointTarget],
) -> bool {
    let kind = match first {
        "IF" => Some(Kind::Branches),
        "SWITCH" => Some(Kind::Cases),
        "FOR" | "WHILE" | "REPEAT" | "LOOP" => Some(Kind::Loop),
        _ => None,
    };
    if let Some(kind) = kind {
        paths.open((first, line), state, kind, out.len());
        return false;
    }
    match first {
        "ELSE" | "DEFAULT" => paths.branch(state, true),
        "CASE" => paths.branch(state, false),
        "ENDIF" | "ENDSWITCH" | "ENDFOR" | "ENDWHILE" | "UNTIL" | "ENDLOOP" => {
            if let Some(closed) = paths.close(state) {
                repeated(&closed, &mut out[closed.mark..]);
            }
        }
        _ => return false,
    }
    true
}

/// The frames and speed of the motions of a loop's body (`targets`) whose body ends with other
/// ones than it began ([`Closed::changed`]): a motion that moves with the first run's value
/// moves with the other on the next run, so that frame is unknown there.
fn repeated(closed: &Closed<State>, targets: &mut [JointTarget]) {
    let Some((entry, end)) = &closed.changed else {
        return;
    };
    let (word, l) = (&closed.word, closed.line);
    let why = |name: &str, line: u64| {
        format!("the {name} of the motion on line {line} in {word} (line {l}) is another on the loop's next run (the body ends with another than it began with): set it before the loop or at the start of its body")
    };
    for t in targets.iter_mut() {
        let line = t.line;
        if let Some(c) = t.cartesian.as_deref_mut() {
            let pairs = [
                (&mut c.frame, &entry.frames.base, &end.frames.base, "$BASE"),
                (&mut c.tool, &entry.frames.tool, &end.frames.tool, "$TOOL"),
            ];
            for (f, a, b, name) in pairs {
                if !same(a, b) && !same(f, b) {
                    *f = Frame::Unknown(line, why(name, line));
                }
            }
        }
        if entry.speed.in_force != end.speed.in_force && t.speed == entry.speed.in_force {
            t.speed = Speed::Unread(why("path speed", line));
        }
    }
}

/// The state at the start of the routine `name` (upper case) whose `DEF` is on `line`: the
/// states at its calls before it in the file, joined; unknown frames where it is called after
/// its `DEF` (by a routine below it) or not at all (its caller is another module's).
fn entry(
    name: &str,
    line: u64,
    calls: &HashMap<String, Vec<(u64, State)>>,
    late: &HashMap<String, Vec<u64>>,
) -> State {
    let unknown = |why: String| State {
        frames: Frames::new(|n| Frame::Unknown(0, format!("{n}: {why}"))),
        speed: speed::Krl::unread(why.clone()),
    };
    if let Some(l) = (late.get(name).into_iter().flatten()).find(|l| **l > line) {
        return unknown(format!("DEF {name} (line {line}) is called on line {l}, below it, by a routine whose frames stiffid reads after it; put the routine after its callers, or set the frames and speed in it"));
    }
    match calls.get(name).map(Vec::as_slice) {
        None | Some([]) => unknown(format!("DEF {name} (line {line}) is not called before it in this file, so what is in force at its motions is its caller's, which stiffid does not see; set the frames and speed in the routine")),
        Some([(_, first), rest @ ..]) => {
            let mut state = first.clone();
            for (l, other) in rest {
                state.join(other, (&format!("the calls of {name}"), *l));
            }
            state
        }
    }
}
/// Refuses a statement whose first word (`first`) KRL cannot read: a character outside ASCII
/// (but a byte-order mark),
/// a quote, a backslash or a closing bracket without its opening one (`LIN]`, `LI\N`, `LIéN`),
/// which the controller refuses to load; passed over, a motion written so would be dropped.
fn well_formed(line: u64, first: &str) -> Result<()> {
    // A byte-order mark opening the file (editors on Windows write one) is no character of it.
    let first = first.trim_start_matches('\u{feff}');
    let stray = |c: char| !c.is_ascii() || matches!(c, '"' | '\'' | '\\' | '}' | ')' | '`');
    match first.contains(stray) || (first.contains(']') && !first.contains('[')) {
        true => Err(at(line, format!("'{}': not a KRL statement (keywords, names and system variables are ASCII letters, digits, _ and $, indices in [..])", short(first)))),
        false => Ok(()),
    }
}

/// The routines after the program's first that set a frame or the frame data, by upper-case
/// name, with the line of the first they set.
fn frame_routines(text: &str, declared: &Declarations) -> HashMap<String, u64> {
    let mut out = HashMap::new();
    let mut scratch = Frames::new(|_| Frame::World);
    let (mut seen, mut current) = (0usize, None::<String>);
    for (line, _, l) in crate::program::lines(text) {
        let code = l.split(';').next().unwrap_or("");
        if let Some(name) = routine_name(&words(code)) {
            seen += 1;
            current = (seen > 1).then_some(name);
            continue;
        }
        if let Some(name) = &current
            && scratch.set(line, code, &declared.fdats)
        {
            out.entry(name.clone()).or_insert(line);
        }
    }
    out
}

/// The routine of `setters` that the statement `code` calls (`NAME( )`), with its line.
fn called<'a>(code: &str, setters: &'a HashMap<String, u64>) -> Option<(&'a str, u64)> {
    let c = compact(code);
    let name = c.split('(').next().filter(|n| c.len() > n.len())?;
    setters.get_key_value(name).map(|(k, l)| (k.as_str(), *l))
}

/// The name of the routine a `DEF`/`DEFFCT` line opens (`GLOBAL DEF name( )`).
fn routine_name(words: &[String]) -> Option<String> {
    let w: Vec<&str> = words
        .iter()
        .map(String::as_str)
        .skip_while(|w| *w == "GLOBAL")
        .collect();
    match w.as_slice() {
        ["DEF", name, ..] => Some(name.to_string()),
        ["DEFFCT", _, name, ..] => Some(name.to_string()),
        _ => None,
    }
}

/// The routines of the file after its first (`DEF`, `DEFFCT`), by upper-case name, with their
/// line.
fn routines(text: &str) -> HashMap<String, u64> {
    let mut out = HashMap::new();
    let mut seen = 0usize;
    for (line, _, l) in crate::program::lines(text) {
        let code = l.split(';').next().unwrap_or("");
        if let Some(name) = routine_name(&words(code)) {
            seen += 1;
            if seen > 1 {
                out.entry(name).or_insert(line);
            }
        }
    }
    out
}

/// The targets of `out` whose frame or tool is unknown moved to `left` (left as found).
fn leave_unknown(out: Vec<JointTarget>, left: &mut Vec<Left>) -> Vec<JointTarget> {
    let mut kept = Vec::with_capacity(out.len());
    for t in out {
        let unknown = t
            .cartesian
            .as_deref()
            .and_then(|c| match (&c.frame, &c.tool) {
                (Frame::Unknown(_, why), _) | (_, Frame::Unknown(_, why)) => Some(why.clone()),
                _ => None,
            });
        match unknown {
            Some(why) => left.push(Left::of(&t, why)),
            None => kept.push(t),
        }
    }
    kept
}

/// The lines that call each routine of `local`, by its name.
fn call_lines(text: &str, local: &HashMap<String, u64>) -> HashMap<String, Vec<u64>> {
    let mut out: HashMap<String, Vec<u64>> = HashMap::new();
    for (line, _, l) in crate::program::lines(text) {
        let code = l.split(';').next().unwrap_or("");
        if let Some((name, _)) = called(code, local) {
            out.entry(name.to_string()).or_default().push(line);
        }
    }
    out
}
