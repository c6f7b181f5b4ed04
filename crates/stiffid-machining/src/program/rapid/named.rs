//! A motion's target named in the module (a declared `robtarget` or `jointtarget`, or an array's
//! element), from the module's data.

use super::{arrays, num, Data};
use crate::program::{at, JointTarget};
use stiffid_core::Result;

/// The declared target `ident` (a name, or an array's element `pts{2}`) of the motion `name`
/// on `line`, of `kind` (`cartesian`: a `robtarget`), from the module's `data`.
pub(super) fn target(
    data: &Data,
    (line, name): (u64, &str),
    (kind, cartesian): (&str, bool),
    ident: &str,
) -> Result<JointTarget> {
    let array = ident
        .split('{')
        .next()
        .unwrap_or("")
        .trim()
        .to_ascii_lowercase();
    let key = match ident.contains('{') {
        true => arrays::element(ident, &|e| num::value(e, &|n| data.nums.get(n).cloned()))
            .map_err(|why| match data.targets.get(&array) {
                // An array without elements the module states: that is the cause.
                Some(Err(a)) if !data.targets.contains_key(&format!("{array}{{1}}")) => {
                    at(line, format!("{name} {ident}: {a}"))
                }
                _ => at(line, format!("{name} {why}")),
            })?,
        false => ident.to_ascii_lowercase(),
    };
    let base = key.split('{').next().unwrap_or(&key);
    // A point the module assigns whole: the value its assignments leave here (module `assign`).
    if let Some(b) = data.bound.get(&key) {
        return match &b.target {
            Ok(t) if t.cartesian.is_some() == cartesian => Ok(t.moved_to(line, false)),
            Ok(_) => Err(at(line, format!("{name} {ident}: not a {kind}"))),
            Err(why) => Err(at(line, format!("{name} {ident}: {why}"))),
        };
    }
    if let Some(assigned_on) = data.assigned.get(base) {
        let written = ident.split('{').next().unwrap_or(ident).trim();
        return Err(at(line, format!("{name} {ident}: {written} is assigned on line {assigned_on}, so its value at the motion is the controller's, not the file's: give the motion its own declared {kind}")));
    }
    if let (None, Some(Err(why))) = (data.targets.get(&key), data.targets.get(base)) {
        let beyond = match data.targets.contains_key(&format!("{base}{{1}}")) {
            true => "beyond the array; ",
            false => "",
        };
        return Err(at(line, format!("{name} {ident}: {beyond}{why}")));
    }
    match data.targets.get(&key) {
        Some(Ok(t)) if t.cartesian.is_some() == cartesian => Ok(t.moved_to(line, false)),
        Some(Ok(_)) => Err(at(line, format!("{name} {ident}: not a {kind}"))),
        Some(Err(why)) => Err(at(line, format!("{name} {ident}: {why}"))),
        None => Err(at(line, format!("{name} {ident}: not a {kind} declared in this module or the backup's modules given; give the task's modules (--backup, Python backup=), declare it in the module or write the target as a literal"))),
    }
}
