//! A KRL program read line by line (module docs of [`super`]): its motions in order, each with
//! its frames ([`super::frames`]) and speed ([`super::speed`]), its points from the `.src` or its
//! `.dat` ([`super::declare`]), loops and branches around motions refused ([`super::flow`]).

use super::declare::{declarations, words, Declarations};
use super::flow::Flow;
use super::frames::{compact, Frames};
use super::motion::{motion, Context};
use super::speed;
use crate::program::cartesian::Frame;
use crate::program::{at, JointTarget};
use std::collections::HashMap;
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// Every joint target of the `.src` `text` (with its `.dat` `data` when given; `XHOME` the
/// controller's `home` posture, deg, when known), in the order of its motions (module docs), and
/// the program's external axes: `E1` to the highest `E`n any
/// target gives.
///
/// # Errors
/// [`stiffid_core::Error::Program`] naming the line: a motion outside the subset, to a point
/// neither file declares, inside a loop or branch, in a routine other than the program's first,
/// a `GOTO` in a program with motions.
pub(crate) fn targets(
    text: &str,
    (data, home): (Option<&str>, Option<[f64; 6]>),
) -> Result<(Vec<JointTarget>, Vec<String>)> {
    let declared = declarations(text, data)?;
    let context = Context {
        declared: &declared,
        data: data.is_some(),
        home,
    };
    let setters = frame_routines(text, &declared);
    let mut out = Vec::new();
    // The program's own routine (its first DEF) and the one of the line.
    let mut main: Option<Routine> = None;
    let mut current: Option<Routine> = None;
    let mut flow = Flow::default();
    let unset = |name: &str| {
        Frame::Unknown(0, format!("no {name} set before this Cartesian motion: its frame is the controller's, which the program does not state; set it in the program (an inline form's FDAT, {name} = {{X .., Y .., Z .., A .., B .., C ..}} or {}_DATA[n])", &name[1..]))
    };
    let mut frames = Frames::new(unset);
    let mut speed = speed::Krl::new();
    for (line, start, l) in crate::program::lines(text) {
        let code = l.split(';').next().unwrap_or("");
        let words = words(code);
        let first = words.first().map(String::as_str).unwrap_or("");
        well_formed(line, first)?;
        if let Some(name) = routine_name(&words) {
            main.get_or_insert_with(|| (name.clone(), line));
            current = Some((name, line));
            flow.line(line, "DEF");
            continue;
        }
        flow.line(line, first);
        let framed = frames.set(line, code, &declared.fdats);
        if let (true, Some((word, l))) = (framed, flow.inside()) {
            frames.unsettle(line, format!("a frame is set on line {line} inside {word} (line {l}), so the one in force after it depends on the run: set it outside loops and branches"));
        }
        if let Some((name, l)) = called(code, &setters) {
            frames.unsettle(line, format!("line {line} calls {name}, which sets a frame (line {l}) in an order the file does not show: set the frames in the program's own routine"));
        }
        if speed.set(line, code)? || framed {
            continue;
        }
        let Some(targets) = motion((line, start), code, first, &context)? else {
            continue;
        };
        if let Some((word, l)) = flow.inside() {
            return Err(at(line, format!("{first} inside {word} (line {l}): a motion in a loop or branch runs as many times as the run decides, not as the file reads: write the path as straight-line code")));
        }
        if let (Some((a, a_line)), Some((b, b_line))) = (&main, &current)
            && a != b
        {
            return Err(at(line, format!("{first} in DEF {b} (line {b_line}), a routine the program's DEF {a} (line {a_line}) may call: the order and number of times the controller runs it depend on the calls; put the path in the program's own routine")));
        }
        let (base, tool) = frames.motion(line, code, &declared.fdats);
        let speed = speed.motion(line, first, code)?;
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
    if let (Some(line), false) = (flow.jump, out.is_empty()) {
        return Err(at(line, "GOTO: a jump in a program with motions; the order the controller runs them would not be the file's: write the path as straight-line code".into()));
    }
    let n = out.iter().map(|t| t.external.len()).max().unwrap_or(0);
    Ok((out, (1..=n).map(|k| format!("E{k}")).collect()))
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

/// A routine of the file: its upper-case name and the line of its `DEF`.
type Routine = (String, u64);

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
