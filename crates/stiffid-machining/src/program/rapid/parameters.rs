//! The parameters a routine's header declares (`PROC pick(robtarget pPick, PERS tooldata
//! tGrip, num dz)`): a motion to one moves where its caller says, at run time.

use super::Declared;
use crate::program::cartesian::Frame;
use std::collections::HashMap;

/// The targets, tools, work objects and `num`s a routine's header `body` (on `line`) takes as
/// parameters (`PROC pick(robtarget pPick, PERS tooldata tGrip)`): each one's type, name and
/// why a motion cannot read it: its value is the caller's, at run time.
fn parameters(line: u64, body: &str) -> Vec<(&'static str, String, String)> {
    let header = body.trim_start();
    let lower = header.to_ascii_lowercase();
    let routine = ["proc ", "func ", "trap "]
        .iter()
        .any(|k| lower.starts_with(k));
    let (Some(open), Some(close)) = (header.find('('), header.rfind(')')) else {
        return Vec::new();
    };
    if !routine || close < open {
        return Vec::new();
    }
    let name = header[..open].split_whitespace().last().unwrap_or("");
    let mut out = Vec::new();
    for p in header[open + 1..close].split([',', '|']) {
        let words: Vec<&str> = (p.split_whitespace())
            .map(|w| w.trim_start_matches('\\'))
            .filter(|w| {
                !["var", "pers", "inout"]
                    .iter()
                    .any(|k| w.eq_ignore_ascii_case(k))
            })
            .collect();
        let Some(kind) = words.first().and_then(|w| {
            let w = w.to_ascii_lowercase();
            [
                "robtarget",
                "jointtarget",
                "tooldata",
                "wobjdata",
                "num",
                "dnum",
            ]
            .into_iter()
            .find(|k| *k == w)
        }) else {
            continue;
        };
        if let Some(p) = words.get(1) {
            let p = p.split('{').next().unwrap_or(p);
            let why = format!("{p} is a parameter of {name} (line {line}): its value is the caller's, given at run time");
            out.push((kind, p.to_ascii_lowercase(), why));
        }
    }
    out
}

/// The parameters of the routine header `body` on `line` ([`parameters`]) into `declared` and
/// `frames`, where the module declares no such name before it.
pub(super) fn declare(
    line: u64,
    body: &str,
    (declared, frames): (&mut Declared, &mut HashMap<String, Frame>),
) {
    for (kind, name, why) in parameters(line, body) {
        match kind {
            "num" | "dnum" => {}
            "robtarget" | "jointtarget" => _ = declared.entry(name).or_insert(Err(why)),
            _ => _ = frames.entry(name).or_insert(Frame::Unknown(line, why)),
        }
    }
}

/// The `num` parameters of the routine header `body` on `line` into `nums`, where the module
/// declares no such name before it: each one's value is the caller's.
pub(super) fn declare_nums(
    line: u64,
    body: &str,
    nums: &mut HashMap<String, std::result::Result<f64, String>>,
) {
    for (kind, name, why) in parameters(line, body) {
        if matches!(kind, "num" | "dnum") {
            nums.entry(name).or_insert(Err(why));
        }
    }
}

/// What a routine's parameters hide of the module's data while the routine is read: each
/// parameter's name and the module's target or `num` of that name, if any.
#[derive(Debug, Default)]
pub(super) struct Shadowed {
    targets: Vec<(String, Option<Result<crate::program::JointTarget, String>>)>,
    nums: Vec<(String, Option<Result<f64, String>>)>,
}

/// Within the routine whose header is `body` on `line`, each target or `num` parameter hides the
/// module's datum of its name (*RAPID kernel*: scope rules): its value is the caller's. What
/// the routine before hid is the module's again.
pub(super) fn shadow(line: u64, body: &str, data: &mut super::Data) {
    let before = std::mem::take(&mut data.shadowed);
    for (name, old) in before.targets {
        match old {
            Some(v) => _ = data.targets.insert(name, v),
            None => _ = data.targets.remove(&name),
        }
    }
    for (name, old) in before.nums {
        match old {
            Some(v) => _ = data.nums.insert(name, v),
            None => _ = data.nums.remove(&name),
        }
    }
    for (kind, name, why) in parameters(line, body) {
        match kind {
            "num" | "dnum" => {
                let old = data.nums.insert(name.clone(), Err(why));
                data.shadowed.nums.push((name, old));
            }
            "robtarget" | "jointtarget" => {
                let old = data.targets.insert(name.clone(), Err(why));
                data.shadowed.targets.push((name, old));
            }
            _ => {}
        }
    }
}
