//! Calls of routines of other modules (`MY_PATH( )`, `GRIPPER(1)`): a statement that calls a
//! routine the `.src` does not define. A module the controller's backup holds (`MY_PATH.src`,
//! with its `MY_PATH.dat`: KSS names a module's files and its main routine alike) is read where
//! it is called (`super::read`); a call of a routine neither the files nor the backup hold is
//! refused where it sits between two motions (the routine may move the robot between them, off
//! the file's path), as an LS `CALL` of a program the backup does not hold is, unless it is
//! one of the controller's own routines that cannot move the robot ([`PASSED`]) or one the
//! setup's `[controller.io]` calls for a process event (`Context::io`).

use super::frames::compact;
use crate::program::Context;

/// The controller's own routines called as statements that move neither the robot nor a frame
/// (KSS 8.x SI manual and the KUKA option manuals): the BAS package (whose frame and speed
/// settings the reader follows), the message routines of `MsgLib`/`KrlMsg`, the serial and
/// string channel routines, `PULSE`, and the Ethernet KRL (`EKI_`) routines, which exchange
/// data only.
const PASSED: &[&str] = &[
    "BAS",
    "PULSE",
    "CWRITE",
    "CREAD",
    "SWRITE",
    "SREAD",
    "COPEN",
    "CCLOSE",
    "MSGNOTIFY",
    "MSGQUIT",
    "MSGDIALOG",
    "MSGLOOP",
    "MSGSTATE",
    "SET_KRLMSG",
    "SET_KRLDLG",
    "SET_KRLDLGANSWER",
    "EXISTS_KRLMSG",
    "EXISTS_KRLDLG",
    "CLEAR_KRLMSG",
    "ON_ERROR_PROCEEDING",
    "STRCLEAR",
    "STRCOPY",
    "STRADD",
    "STRFIND",
    "STRCOMP",
];

/// The routine a statement `code` (its comment removed) calls, upper case, where it is a call
/// (`NAME( .. )` as the whole statement); `None` for any other statement.
pub(super) fn called(code: &str) -> Option<String> {
    let c = compact(code);
    let (name, rest) = c.split_once('(')?;
    let word = |ch: char| ch.is_ascii_alphanumeric() || ch == '_' || ch == '$';
    let starts = name.chars().next().is_some_and(|ch| !ch.is_ascii_digit());
    (starts && name.chars().all(word) && rest.ends_with(')')).then(|| name.to_string())
}

/// The name of the routine a `DEF`/`DEFFCT` line opens (`GLOBAL DEF name( )`).
pub(super) fn routine_name(words: &[String]) -> Option<String> {
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

/// Whether the controller's routine `name` (upper case) is passed over ([`PASSED`]).
pub(super) fn passed(name: &str) -> bool {
    PASSED.contains(&name) || name.starts_with("EKI_")
}

/// A module of the controller's backup called by its name: its `.src` (the file's name as
/// given and its text) and its `.dat` where the backup holds one (same folder first).
pub(super) struct Module<'a> {
    pub name: String,
    pub src: (&'a str, &'a str),
    pub dat: Option<(&'a str, &'a str)>,
}

/// The module `name` (upper case) of the `context`'s backup: `NAME.src` (any case) whose first
/// routine is `name`, and its `.dat`.
pub(super) fn module<'a>(name: &str, context: &Context<'a>) -> Option<Module<'a>> {
    let src = context.backup_file(&format!("{name}.src"))?;
    let first = src.1.lines().find_map(|l| {
        let words = super::declare::words(l.split(';').next().unwrap_or(""));
        routine_name(&words)
    });
    if first.as_deref() != Some(name) {
        return None;
    }
    let folder = |f: &str| f.len() - crate::program::file_name(f).len();
    let dats = context.backup_with(|n| n.eq_ignore_ascii_case(&format!("{name}.dat")));
    let dat = (dats.iter())
        .find(|(f, _)| f[..folder(f)] == src.0[..folder(src.0)])
        .or(dats.first())
        .copied();
    Some(Module {
        name: name.to_string(),
        src,
        dat,
    })
}

/// A call of `name` (upper case) that no module of the `context`'s backup answers
/// ([`module`]), in words: `NAME( )`, and where the backup holds the routine all the same (a
/// `GLOBAL DEF` that is not its module's first routine, or `NAME.src` whose first routine has
/// another name), which stiffid does not read.
pub(super) fn unheld(name: &str, context: &Context) -> String {
    let first = |text: &str| {
        (crate::program::lines(text)).find_map(|(line, _, l)| {
            routine_name(&super::declare::words(l.split(';').next().unwrap_or("")))
                .map(|n| (line, n))
        })
    };
    if let Some((file, text)) = context.backup_file(&format!("{name}.src"))
        && let Some((line, other)) = first(text)
    {
        return format!("{name}( ) ({file} of the backup opens with the routine {other} on line {line}, not {name}: KSS names a module's first routine after its file, and stiffid reads a module so)");
    }
    for (file, text) in context.backup_with(|n| n.to_ascii_lowercase().ends_with(".src")) {
        let global = (crate::program::lines(text)).find(|(_, _, l)| {
            let w = super::declare::words(l.split(';').next().unwrap_or(""));
            w.first().is_some_and(|g| g == "GLOBAL") && routine_name(&w).as_deref() == Some(name)
        });
        if let Some((line, ..)) =
            global.filter(|(line, ..)| first(text).is_some_and(|f| f.0 != *line))
        {
            return format!("{name}( ) (a GLOBAL routine of {file}, line {line}, that is not its module's first: stiffid reads a module's first routine only)");
        }
    }
    format!("{name}( )")
}

/// Where a statement sits among the motions of the paths that reach it (the callers' included):
/// after a motion on some path, before one on some path.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(super) struct Place {
    pub after_first: bool,
    pub before_last: bool,
}

impl Place {
    /// Whether a statement there runs between two motions.
    pub(super) fn between(self) -> bool {
        self.after_first && self.before_last
    }

    /// Either place.
    pub(super) fn or(self, other: Place) -> Place {
        Place {
            after_first: self.after_first || other.after_first,
            before_last: self.before_last || other.before_last,
        }
    }
}

/// A statement the reader places among the motions once the module is read: a call (of a
/// routine of the file or of another module) or a motion.
#[derive(Debug, Clone)]
pub(super) struct Event {
    pub line: u64,
    /// The routine of the file it is in (1 its first).
    pub routine: usize,
    pub kind: EventKind,
    /// Whether a loop around it, or a loop around the routine's call, also holds a motion.
    pub in_loop: bool,
}

/// What an [`Event`] is.
#[derive(Debug, Clone)]
pub(super) enum EventKind {
    /// A motion.
    Motion,
    /// A call of a routine of the file (its routine number).
    Local(usize),
    /// A call of a routine no file read holds, in words ([`unheld`]).
    Unheld(String),
    /// A call of a module of the backup, read: its name and file, the events of its text, and
    /// whether it moves.
    Held(String, String, Box<Events>, bool),
}

/// The events of a module in the order of its lines, and the loops open.
#[derive(Debug, Clone, Default)]
pub(super) struct Events {
    pub list: Vec<Event>,
    /// Per open loop: the number of motions read when it opened and the events inside it so far.
    loops: Vec<(usize, Vec<usize>)>,
    motions: usize,
}

impl Events {
    /// Adds an event.
    pub(super) fn push(&mut self, line: u64, routine: usize, kind: EventKind) {
        if matches!(kind, EventKind::Motion | EventKind::Held(.., true)) {
            self.motions += 1;
        }
        if let Some((_, inside)) = self.loops.last_mut() {
            inside.push(self.list.len());
        }
        self.list.push(Event {
            line,
            routine,
            kind,
            in_loop: false,
        });
    }

    /// A loop opens.
    pub(super) fn open_loop(&mut self) {
        self.loops.push((self.motions, Vec::new()));
    }

    /// A loop closes: its events run between motions when its body holds one (the next run's
    /// motion after, the last run's before); otherwise they are the enclosing loop's.
    pub(super) fn close_loop(&mut self) {
        let Some((at_open, inside)) = self.loops.pop() else {
            return;
        };
        match self.motions > at_open {
            true => inside.iter().for_each(|&k| self.list[k].in_loop = true),
            false => {
                if let Some((_, outer)) = self.loops.last_mut() {
                    outer.extend(inside);
                }
            }
        }
    }

    /// A routine starts, or the text ends: the loops open are closed.
    pub(super) fn end_routine(&mut self) {
        while !self.loops.is_empty() {
            self.close_loop();
        }
    }

    /// Per routine of the file (1 its first), whether it moves: a motion, or a call of a
    /// routine or module that moves.
    fn moving(&self, routines: usize) -> Vec<bool> {
        let mut out = vec![false; routines + 1];
        for _ in 0..=routines {
            for e in &self.list {
                let moves = match &e.kind {
                    EventKind::Motion | EventKind::Held(.., true) => true,
                    EventKind::Local(r) => out.get(*r).copied().unwrap_or(false),
                    _ => false,
                };
                out[e.routine] |= moves;
            }
        }
        out
    }

    /// The unheld calls that run between two motions, each its line and what it calls: in a
    /// module called at `outer`, with each routine of the file placed at its calls (a routine no
    /// line of the file calls: where the module is), and so in the modules it calls.
    pub(super) fn between(&self, outer: Place) -> Vec<(u64, String)> {
        let routines = self.list.iter().map(|e| e.routine).max().unwrap_or(0);
        let moving = self.moving(routines);
        let mut places: Vec<Option<Place>> = vec![None; routines + 1];
        let mut out = Vec::new();
        for r in 1..=routines {
            let place = match r {
                1 => outer,
                _ => places[r].unwrap_or(outer),
            };
            let own: Vec<&Event> = self.list.iter().filter(|e| e.routine == r).collect();
            let moves = |e: &&Event| match &e.kind {
                EventKind::Motion | EventKind::Held(.., true) => true,
                EventKind::Local(c) => moving.get(*c).copied().unwrap_or(false),
                _ => false,
            };
            for (k, e) in own.iter().enumerate() {
                let here = Place {
                    after_first: e.in_loop || own[..k].iter().any(moves),
                    before_last: e.in_loop || own[k + 1..].iter().any(moves),
                }
                .or(place);
                match &e.kind {
                    EventKind::Local(callee) if *callee < places.len() => {
                        places[*callee] = Some(places[*callee].map_or(here, |p| p.or(here)));
                    }
                    EventKind::Unheld(what) if here.between() => {
                        out.push((e.line, what.clone()));
                    }
                    EventKind::Held(name, file, inner, _) => {
                        for (l, what) in inner.between(here) {
                            out.push((e.line, format!("{name}( ): {file} line {l} calls {what}")));
                        }
                    }
                    _ => {}
                }
            }
        }
        out
    }
}
