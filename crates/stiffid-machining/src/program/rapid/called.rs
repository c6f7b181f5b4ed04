//! A `PROC` of another module of the task (the controller's backup) called by the module, read
//! where it is called (module `calls`): its motions compensated in place in its own module, with
//! the tool, work object and speed each names and the configuration monitoring in force at the
//! call; its module's text after every text before it (the program's, then each module called,
//! in the order of its first call), written beside the program under its own name.
//!
//! Its parameters (*RAPID overview*: routine parameters) take the call's arguments: a
//! `robtarget`, `jointtarget`, `tooldata`, `wobjdata` or `speeddata` argument that names a
//! datum the caller reads (declared with a value, never assigned) is that datum, a target
//! compensated in the caller's declaration (visits compensated apart are then refused, naming
//! both lines); a `num` argument whose value the caller states (a number, arithmetic of its `num`
//! data) is that value; any other argument (an expression, `Offs(..)`, a literal, a datum
//! assigned at run time) leaves the parameter the run's, refused at the motion that uses it,
//! naming the call.

use super::cartesian::is_data;
use super::{arguments, Data};
use crate::program::cartesian::Frame;
use crate::program::JointTarget;
use std::collections::HashMap;

/// The most calls of other modules' procedures read for one program (each is read where it is
/// called): a longer reading is refused.
pub(super) const MAX_READS: usize = 1_000;

/// The calls of the task's procedures read so far, for one program.
#[derive(Debug, Default)]
pub(super) struct Task<'a> {
    /// The task's `PROC`s: name (lower case), module file and text ([`super::calls::procedures`]).
    pub procs: HashMap<String, (&'a str, &'a str)>,
    /// The `PROC`s two modules of the task declare: name (lower case) and the second module.
    pub twice: HashMap<String, &'a str>,
    /// The modules called that move, in the order their texts follow the program's: each one's
    /// name as given and its text.
    pub files: Vec<(String, String)>,
    /// Where each module's text begins in the whole text, by file name.
    pub offsets: HashMap<String, usize>,
    /// The length of every text so far.
    pub total: usize,
    /// The procedures being read (`Module.proc`), outermost first.
    pub chain: Vec<String>,
    /// Calls read so far ([`MAX_READS`]).
    pub reads: usize,
    /// The program's text, as the called modules see its data.
    pub program: Vec<(String, String)>,
}

/// What a call gives the procedure's parameters: each bound parameter's name (lower case) and
/// its value in the caller.
#[derive(Debug, Default, Clone)]
pub(super) struct Bindings {
    targets: Vec<(String, std::result::Result<JointTarget, String>)>,
    frames: Vec<(String, Frame)>,
    speeds: Vec<(String, SpeedValue)>,
    nums: Vec<(String, std::result::Result<f64, String>)>,
}

/// A `speeddata`'s `v_tcp` (mm/s) and line, or why it has none ([`super::speed::RapidSpeeds`]).
type SpeedValue = std::result::Result<(f64, u64), String>;

impl Bindings {
    /// The parameters of the procedure whose header is `header` given the arguments of the
    /// call `args` (the text after its name) on `line`, from the caller's `data` (module docs).
    pub(super) fn of(
        header: &str,
        (args, line, renamed): (&str, u64, Option<usize>),
        data: &Data,
    ) -> Bindings {
        let mut out = Bindings::default();
        let args = args.trim_end().trim_end_matches(';');
        let joined = arguments::switches_joined(args);
        let given: Vec<(&str, usize)> = (arguments::top_level(&joined).into_iter())
            .map(|r| {
                let a = &joined[r.clone()];
                (a.trim(), r.start + a.len() - a.trim_start().len())
            })
            .filter(|(a, _)| !a.is_empty() && !a.starts_with('\\'))
            .collect();
        for (k, (kind, name)) in parameters(header).into_iter().enumerate() {
            let Some((arg, arg_at)) = given.get(k).copied().filter(|_| !kind.is_empty()) else {
                continue;
            };
            let reference = renamed.map(|at| at + arg_at..at + arg_at + arg.len());
            let key = arg.to_ascii_lowercase();
            if kind == "num" {
                let v = super::num::value(arg, &|n| data.nums.get(n).cloned());
                let why = |w: String| {
                    format!("{name} is the argument '{arg}' of the call on line {line}: {w}")
                };
                let v = v.map_err(why);
                out.nums.push((name, v));
                continue;
            }
            let named = !key.is_empty()
                && key.starts_with(|c: char| c.is_ascii_alphabetic())
                && key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
            let run = format!("{name} is the argument '{arg}' of the call on line {line}");
            let why = match (named, data.assigned.get(&key)) {
                (false, _) => Some(format!("{run}, computed at run time: pass a datum declared with its value")),
                (true, Some(l)) => Some(format!("{run}, which is assigned on line {l}, so its value at the call is the controller's")),
                (true, None) => None,
            };
            match kind {
                "robtarget" | "jointtarget" => {
                    let value = match &why {
                        Some(w) => Err(w.clone()),
                        None => bound_target(data, &key, &run, reference),
                    };
                    out.targets.push((name, value));
                }
                "speeddata" => {
                    let value = match (&why, data.speeds.get(&key)) {
                        (Some(w), _) => Err(w.clone()),
                        (None, Some(v)) => v.clone(),
                        (None, None) => predefined(&key, line).ok_or_else(|| {
                            format!("{run}, a speed declared in neither the caller's module nor the task's")
                        }),
                    };
                    out.speeds.push((name, value));
                }
                _ => {
                    let frame = match (&why, key.as_str()) {
                        (Some(w), _) => Frame::Unknown(0, w.clone()),
                        (None, "tool0" | "wobj0") => Frame::World,
                        (None, _) => match data.frames.get(&key) {
                            Some(Frame::Stated(_, f)) => Frame::Stated(0, *f),
                            Some(Frame::Unknown(_, w)) => Frame::Unknown(0, format!("{run}: {w}")),
                            Some(other) => other.clone(),
                            None => Frame::Unknown(0, format!("{run}, declared with a value in neither the caller's module nor the task's")),
                        },
                    };
                    out.frames.push((name, frame));
                }
            }
        }
        out
    }

    /// The procedure's module's `data` with the parameters bound.
    pub(super) fn apply(&self, data: &mut Data) {
        for (name, t) in &self.targets {
            data.targets.insert(name.clone(), t.clone());
            data.assigned.remove(name);
        }
        for (name, f) in &self.frames {
            data.frames.insert(name.clone(), f.clone());
        }
        for (name, s) in &self.speeds {
            data.speeds.insert(name.clone(), s.clone());
        }
        for (name, v) in &self.nums {
            data.nums.insert(name.clone(), v.clone());
        }
    }
}

/// The caller's target `key` as a bound parameter: its declaration stays the caller's, its visit
/// from the procedure writes there; named at the call's argument (`reference`, bytes of the
/// text) where the call may name a copy under another name (a routine of the module read at its
/// call, module `percall`), else never copied (the procedure names the parameter, not the datum).
fn bound_target(
    data: &Data,
    key: &str,
    run: &str,
    reference: Option<std::ops::Range<usize>>,
) -> std::result::Result<JointTarget, String> {
    match data.targets.get(key) {
        Some(Ok(t)) if t.point.as_deref().is_some_and(|p| p.foreign.is_some()) => Err(format!(
            "{run}, declared in another module of the task: declare it in the caller's module"
        )),
        Some(Ok(t)) if t.point.is_some() && reference.is_some() => {
            Ok(t.clone().named_at(reference.unwrap_or_default()))
        }
        Some(Ok(t)) => Ok(JointTarget {
            point: None,
            ..t.clone()
        }),
        Some(Err(why)) => Err(format!("{run}: {why}")),
        None => Err(format!(
            "{run}, declared with a value in neither the caller's module nor the task's"
        )),
    }
}

/// A predefined `speeddata` (`v100`): its `v_tcp`, mm/s, and the call's line.
fn predefined(key: &str, line: u64) -> Option<(f64, u64)> {
    let v: u32 = key.strip_prefix('v')?.parse().ok()?;
    super::speed::is_predefined(v).then_some((f64::from(v), line))
}

/// The positional parameters (not `\` optional ones) of a routine's header, in order: each
/// one's type when it is data a motion reads (`robtarget`, `jointtarget`, `tooldata`,
/// `wobjdata`, `speeddata`, `num`; else `""`) and its name, lower case.
fn parameters(header: &str) -> Vec<(&'static str, String)> {
    let (Some(open), Some(close)) = (header.find('('), header.rfind(')')) else {
        return Vec::new();
    };
    if close < open {
        return Vec::new();
    }
    let inner = &header[open + 1..close];
    let mut out = Vec::new();
    for p in arguments::top_level(inner) {
        let p = inner[p].trim();
        if p.is_empty() || p.starts_with('\\') {
            continue;
        }
        let words: Vec<String> = (p.split_whitespace())
            .map(str::to_ascii_lowercase)
            .filter(|w| !matches!(w.as_str(), "var" | "pers" | "inout"))
            .collect();
        let kind = words.first().map_or("", |w| match w.as_str() {
            "speeddata" => "speeddata",
            "num" | "dnum" => "num",
            k if is_data(k) || k == "jointtarget" => {
                ["robtarget", "tooldata", "wobjdata", "jointtarget"]
                    .into_iter()
                    .find(|x| *x == k)
                    .unwrap_or("")
            }
            _ => "",
        });
        let name = words
            .get(1)
            .map_or("", |n| n.split('{').next().unwrap_or(n));
        out.push((kind, name.to_string()));
    }
    out
}
