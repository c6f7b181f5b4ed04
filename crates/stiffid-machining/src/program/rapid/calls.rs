//! Procedure calls of a RAPID module (*RAPID overview*: procedure calls; *RAPID kernel*: a
//! task's modules share their routines): which statement calls a procedure, which of RAPID's own
//! instructions cannot move the robot, which ones change where every motion after them lands,
//! and which module of the task (the controller's backup, [`Context::backup`]) holds a `PROC`.
//!
//! The rule, as for an LS `CALL`: a call of a procedure of the module is read where the
//! procedure is; one of a `PROC` of another module of the task is read where it is called
//! (module `called`); a call of a procedure neither the module nor the task's modules given hold
//! is refused naming the call where it runs between two motions (it may move the robot off the
//! file's path), unless it is one of RAPID's instructions that cannot move the robot ([`INERT`]);
//! a late-bound call (`%name%`, `CallByVar`) is refused there too, and an instruction that shifts
//! the motions after it ([`shifts`]) wherever a motion follows it.

use crate::program::rapid::{statements, without_comments, Rapid};
use crate::program::Context;
use std::collections::HashMap;

/// RAPID's instructions that cannot move the robot (lower case): I/O, waits, data, messages,
/// interrupts, files and sockets, settings of the motions' speed, acceleration and
/// configuration monitoring, and the process options' set-up instructions (*Technical reference
/// manual - RAPID Instructions, Functions and Data types*).
pub(super) const INERT: &[&str] = &[
    "accset",
    "actunit",
    "add",
    "aliasio",
    "bitclear",
    "bitset",
    "bookerrno",
    "break",
    "cancelload",
    "checkprogref",
    "cirpathmode",
    "clear",
    "cleariobuff",
    "clearpath",
    "clearrawbytes",
    "clkreset",
    "clkstart",
    "clkstop",
    "close",
    "closedir",
    "confj",
    "confl",
    "connect",
    "copyfile",
    "copyrawbytes",
    "corrclear",
    "corrcon",
    "corrdiscon",
    "corrwrite",
    "deactunit",
    "decr",
    "eoffsoff",
    "erasemodule",
    "errlog",
    "errraise",
    "errwrite",
    "exit",
    "exitcycle",
    "getdataval",
    "getsysdata",
    "gettrapdata",
    "gripload",
    "idelete",
    "idisable",
    "ienable",
    "ierror",
    "incr",
    "ipers",
    "isignalai",
    "isignalao",
    "isignaldi",
    "isignaldo",
    "isignalgi",
    "isignalgo",
    "isleep",
    "itimer",
    "ivarvalue",
    "iwatch",
    "load",
    "makedir",
    "mechunitload",
    "motionsup",
    "open",
    "opendir",
    "packrawbytes",
    "pathacclim",
    "pathrecstart",
    "pathrecstop",
    "pathresol",
    "pdispoff",
    "pulsedo",
    "raise",
    "readanybin",
    "readblock",
    "readcfgdata",
    "readerrdata",
    "readrawbytes",
    "removedir",
    "removefile",
    "renamefile",
    "reset",
    "resetppmoved",
    "retry",
    "return",
    "rewind",
    "rmqemptyqueue",
    "rmqfindslot",
    "rmqgetmessage",
    "rmqgetmsgdata",
    "rmqgetmsgheader",
    "rmqreadwait",
    "rmqsendmessage",
    "rmqsendwait",
    "save",
    "set",
    "setalldataval",
    "setao",
    "setdatasearch",
    "setdataval",
    "setdo",
    "setgo",
    "setsysdata",
    "singarea",
    "skipwarn",
    "socketaccept",
    "socketbind",
    "socketclose",
    "socketconnect",
    "socketcreate",
    "socketlisten",
    "socketreceive",
    "socketreceivefrom",
    "socketsend",
    "socketsendto",
    "speedrefresh",
    "spystart",
    "spystop",
    "startload",
    "stop",
    "stopmove",
    "stopmovereset",
    "storepath",
    "syncmoveoff",
    "syncmoveon",
    "texttabinstall",
    "tperase",
    "tpreadfk",
    "tpreadnum",
    "tpreaddnum",
    "tpshow",
    "tpwrite",
    "triggcheckio",
    "triggequip",
    "triggint",
    "triggio",
    "triggrampao",
    "triggspeed",
    "triggstopproc",
    "tryint",
    "trynext",
    "tunereset",
    "tuneservo",
    "uimsgbox",
    "uishow",
    "unload",
    "unpackrawbytes",
    "velset",
    "waitai",
    "waitao",
    "waitdi",
    "waitdo",
    "waitgi",
    "waitgo",
    "waitload",
    "waitrob",
    "waitsynctask",
    "waittestandset",
    "waittime",
    "waituntil",
    "warmstart",
    "worldacclim",
    "write",
    "writeanybin",
    "writebin",
    "writeblock",
    "writecfgdata",
    "writerawbytes",
    "writestrbin",
    "wzboxdef",
    "wzcyldef",
    "wzdisable",
    "wzdoset",
    "wzenable",
    "wzfree",
    "wzhomejointdef",
    "wzlimjointdef",
    "wzlimsup",
    "wzsphdef",
    "egmgetid",
    "egmreset",
    "egmsetupai",
    "egmsetupao",
    "egmsetupgi",
    "egmsetupli",
    "egmsetupuc",
    "egmactjoint",
    "egmactpose",
    "egmstop",
    "egmstreamstart",
    "egmstreamstop",
];

/// Why an instruction (lower case) that shifts or softens the motions after it is not
/// followed, if it is one: program displacement (`PDispOn`, `PDispSet`), external axes' offsets
/// (`EOffsOn`, `EOffsSet`), soft servo (`SoftAct`: the axis yields to the load, no longer the
/// stiffness identified), and force control (`FCAct`: the path follows the contact force).
pub(super) fn shifts(first: &str) -> Option<&'static str> {
    Some(match first {
        "pdispon" | "pdispset" => "program displacement: every motion after it lands displaced by a frame the controller sets at run time (PDispOn: from the robot's position then), which stiffid does not follow; apply the displacement to the targets and remove it",
        "eoffson" | "eoffsset" => "an offset of the external axes: every motion after it moves them by an offset set at run time, which stiffid does not follow; remove it",
        "softact" => "soft servo: the axis yields to the load by a softness set at run time, not by the stiffness identified; not compensated: deactivate it (SoftDeact) around the compensated path",
        "fcact" => "force control: the motions after it follow the contact force, not the programmed path; not compensated",
        _ => return None,
    })
}

/// RAPID's words that start a statement and are no procedure (lower case).
const KEYWORDS: &[&str] = &[
    "if",
    "for",
    "while",
    "test",
    "goto",
    "return",
    "exit",
    "raise",
    "retry",
    "trynext",
    "connect",
    "const",
    "var",
    "pers",
    "local",
    "task",
    "else",
    "elseif",
    "endif",
    "endfor",
    "endwhile",
    "endtest",
    "case",
    "default",
    "error",
    "undo",
    "backward",
    "module",
    "endmodule",
    "proc",
    "endproc",
    "func",
    "endfunc",
    "trap",
    "endtrap",
    "record",
    "endrecord",
    "alias",
];

/// Whether `word` (lower case) is one of RAPID's instructions that cannot move the robot.
pub(super) fn inert(word: &str) -> bool {
    INERT.iter().any(|w| w.eq_ignore_ascii_case(word))
}

/// The procedure a statement `body` whose first word (lower case) is `first` calls: its name as
/// written, or `%` for a late-bound call (`%"name"%;`, `CallByVar`); `None` for a statement
/// that calls none (a keyword, an assignment, a label, a motion, RAPID's instruction that
/// cannot move the robot or shifts the motions, an editor's placeholder).
pub(super) fn called<'b>(body: &'b str, first: &str) -> Option<&'b str> {
    let t = body.trim_start();
    if t.starts_with('%') && !t.starts_with("%%%") {
        return Some("%");
    }
    if first == "callbyvar" {
        return Some("%");
    }
    let name = &t[..first.len().min(t.len())];
    let rest = t[name.len()..].trim_start();
    let identifier = name.starts_with(|c: char| c.is_ascii_alphabetic())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    let not_call = !identifier
        || rest.starts_with([':', '.', '{', '('])
        || KEYWORDS.contains(&first)
        || super::flow::is_motion(first)
        || inert(first)
        || shifts(first).is_some();
    (!not_call).then_some(name)
}

/// The task's `PROC`s: each one's name (lower case), the backup's module that holds it (its name
/// as given and its text); a module whose text is the program's (`own`) is not among them. And
/// each name two modules declare, with the second module's name (the controller refuses to load
/// the task: *RAPID kernel*, scope rules).
#[allow(clippy::type_complexity)]
pub(super) fn procedures<'a>(
    context: &Context<'a>,
    own: &str,
) -> (
    HashMap<String, (&'a str, &'a str)>,
    HashMap<String, &'a str>,
) {
    let modules = context.backup_with(|n| {
        let e = n.rsplit_once('.').map_or("", |(_, e)| e);
        Rapid::BACKUP.contains(&e.to_ascii_lowercase().as_str())
    });
    let mut out: HashMap<String, (&'a str, &'a str)> = HashMap::new();
    let mut twice = HashMap::new();
    for (file, text) in modules.into_iter().filter(|(_, t)| *t != own) {
        let code = without_comments(text);
        for s in statements(&code) {
            if let Some(name) = procedure(&code[s.span]) {
                match out.get(&name) {
                    Some((f, _)) if *f != file => _ = twice.insert(name, file),
                    Some(_) => {}
                    None => _ = out.insert(name, (file, text)),
                }
            }
        }
    }
    (out, twice)
}

/// The name (lower case) of the procedure a statement opens (`PROC name(..)`, also `LOCAL`),
/// `None` for any other statement (a `FUNC` or `TRAP` is not called as a statement).
pub(super) fn procedure(body: &str) -> Option<String> {
    let mut words = body.split_whitespace().map(str::to_ascii_lowercase);
    let mut w = words.next()?;
    while matches!(w.as_str(), "local" | "task") {
        w = words.next()?;
    }
    let name = (w == "proc").then(|| words.next())??;
    Some(name.split('(').next().unwrap_or(&name).to_string())
}

/// The header of `PROC name` (lower case) in the module `text`, comments blanked; empty where
/// the module holds none.
pub(super) fn header(text: &str, name: &str) -> String {
    let code = without_comments(text);
    (statements(&code).into_iter())
        .map(|s| code[s.span].to_string())
        .find(|b| procedure(b).as_deref() == Some(name))
        .unwrap_or_default()
}

/// The procedure a compact `IF cond instruction;` (`statement`, from its `IF`) calls as its
/// instruction (`IF ok Pick;`, `IF a > 1 AND ok Grip 2;`; [`called`]'s rules), whether or not
/// the module or the task holds it: its name as written and its byte in `statement`.
pub(super) fn in_compact_if(statement: &str) -> Option<(&str, usize)> {
    let at = super::flow::compact_instruction(statement)?;
    let inner = &statement[at..];
    called(inner, &super::first_word(inner)).map(|name| (name, at))
}

/// The name of the routine a statement opens (`PROC name()`, `FUNC type name()`, `TRAP name`).
pub(super) fn routine(body: &str) -> Option<String> {
    let words: Vec<String> = body
        .split_whitespace()
        .take(3)
        .map(str::to_ascii_lowercase)
        .collect();
    let w: Vec<&str> = words
        .iter()
        .map(String::as_str)
        .skip_while(|w| matches!(*w, "local" | "task"))
        .collect();
    match w.as_slice() {
        ["proc" | "trap", name, ..] | ["func", _, name, ..] => {
            Some(name.split('(').next().unwrap_or(name).to_string())
        }
        _ => None,
    }
}
