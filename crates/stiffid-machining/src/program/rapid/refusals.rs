//! Why the reader refuses what it does not follow: a motion instruction outside its subset, a
//! datum declared twice.

use super::cartesian;
use std::collections::HashMap;

/// Why a motion instruction (lower case) other than `MoveAbsJ`, `MoveL`, `MoveJ`, `MoveC` and the
/// arc welding ones is not read.
pub(super) fn unfollowed(first: &str) -> &'static str {
    match first {
        "movelsync" | "movejsync" | "movecsync" | "moveldo"
        | "movejdo" | "movecdo" | "movelgo" | "movejgo" | "movecgo" | "movelao"
        | "movejao" | "movecao" => "a motion stiffid does not follow (a circle, or a signal set on the way); write the path as MoveL, MoveJ or MoveAbsJ",
        "moveextj" => "a motion of external axes only; not compensated: remove it",
        f if f.starts_with("trigg") => "a motion with triggered events (robtarget); not compensated: write the path as MoveL or MoveAbsJ and set the events apart",
        f if f.starts_with("search") => "a search motion stops where a sensor fires, which the program does not say; not compensated",
        f if f.starts_with("egm") => "an Externally Guided Motion: the robot follows the positions a sensor sends at run time, which the program does not hold; not compensated",
        f if f.starts_with("ind") => "an independent axis motion: the axis moves apart from the path, as the controller decides; not compensated",
        f if f.starts_with("fcpress") => "a force-controlled motion: the robot presses with the programmed force and its path follows the contact, which the program does not hold; not compensated",
        "contactl" => "a motion that stops where contact is made, which the program does not say; not compensated",
        "pathrecmovebwd" | "pathrecmovefwd" | "stepbwdpath" => "a motion along a path the controller recorded at run time; not compensated",
        _ => "a motion instruction stiffid does not follow; write the path as MoveL, MoveJ or MoveAbsJ",
    }
}

/// For a declaration of data a motion reads (`words`, lower case, of the statement on `line`: a
/// `jointtarget`, `speeddata` or [`cartesian::is_data`]) of a name declared before (`names`:
/// each name's first line), its kind, name and why a motion cannot read it: RAPID refuses a
/// name declared twice in a module, and of two in two routines, which one a motion uses is
/// the routine's scope, which the reader does not follow.
pub(super) fn declared_twice<'a>(
    line: u64,
    words: &[&'a str],
    names: &mut HashMap<String, u64>,
) -> Option<(&'a str, String, String)> {
    let ["const" | "var" | "pers", kind, name, ..] = words else {
        return None;
    };
    if !matches!(*kind, "jointtarget" | "speeddata") && !cartesian::is_data(kind) {
        return None;
    }
    let name = name.trim_end_matches(';');
    let name = name.split('{').next().unwrap_or(name);
    let first = names.insert(name.to_string(), line)?;
    let why = format!("{kind} {name} is declared twice, on line {first} and on line {line}: the controller refuses a name declared twice in a module, and of two in two routines which one a motion uses depends on the scope, which stiffid does not follow; give each its own name");
    Some((kind, name.to_string(), why))
}
