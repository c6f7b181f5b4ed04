//! A KRL program read line by line (module docs of [`super`]): its motions in order, each with
//! its frames ([`super::frames`]) and speed ([`super::speed`]), its points from the `.src` or its
//! `.dat` ([`super::declare`]), what is in force at each followed through loops, branches and
//! the routines of the file ([`super::state`], [`crate::program::paths`]).

use super::assign;
use super::called::{Calls, One};
use super::calls::{routine_name, EventKind, Events, Place};
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
/// from `context`), in the order of its motions, then those of the modules of the backup it
/// calls ([`super::called`]), the program's external axes (`E1` to the highest `E`n any target
/// gives) and the motions left as found ([`crate::program::Context::leave_refused`]).
///
/// # Errors
/// [`stiffid_core::Error::Program`] naming the line: a motion outside the subset, to a point
/// neither file declares, a `GOTO` in a program with motions; a motion whose frames or point
/// only the run decides (paths that set different frames, a value assigned at run time), unless
/// the context leaves it as found; a call between two motions of a routine neither the files
/// nor the backup hold ([`super::calls`]), unless the context leaves it.
pub(crate) fn targets(text: &str, context: &crate::program::Context) -> Result<Read> {
    let main = (crate::program::lines(text))
        .find_map(|(_, _, l)| routine_name(&words(l.split(';').next().unwrap_or(""))));
    let mut calls = Calls::new(text.len() + context.data.map_or(0, str::len), main, module);
    let mut state = State {
        frames: Frames::new(unset),
        speed: speed::Krl::new(),
        points: Default::default(),
    };
    state.frames.table = super::backup::tables(context)?;
    let one = module(text, context, state, &mut calls)?;
    let (mut out, mut left) = (one.targets, one.left);
    for (line, what) in one.events.between(Place::default()) {
        let e = match what.ends_with(')') && !what.ends_with("( )") {
            // Held in the backup, not as a module stiffid reads.
            true => at(line, format!("{what}: a call between two motions of a routine stiffid does not read; it may move the robot between them, off the path the file gives: call it before the first motion or after the last, or give it a module of its own (NAME.src whose first routine is NAME)")),
            false => at(line, format!("{what}: a call between two motions of a routine neither the files nor the backup given hold; it may move the robot between them, off the path the file gives: give the controller's backup holding its module (its .src and .dat, --backup), or call it before the first motion or after the last")),
        };
        context.leave(&mut left, e)?;
    }
    let (nested, nested_left, called) = calls.finish();
    out.extend(nested);
    left.extend(nested_left);
    let n = out.iter().map(|t| t.external.len()).max().unwrap_or(0);
    Ok(Read {
        targets: out,
        axes: (1..=n).map(|k| format!("E{k}")).collect(),
        left,
        called,
        ..Read::default()
    })
}

/// The module `text` (with the `.dat` of `context`) read with `entry` in force at its start,
/// the modules of the backup it calls read into `calls`.
pub(super) fn module(
    text: &str,
    context: &crate::program::Context,
    entry: State,
    calls: &mut Calls,
) -> Result<One> {
    let data = context.data;
    let declared = declarations(text, data, &super::declare::global_lists(context, data))?;
    let mut entry = entry;
    entry.points = assign::initial(&declared.assigned);
    let setters = assign::setters(text, &entry.points);
    let insert = match data {
        Some(d) => text.len() + super::declare::after_line(d, "DEFDAT"),
        None => super::declare::after_line(text, "DEF"),
    };
    let eol = match data.unwrap_or(text).contains("\r\n") {
        true => "\r\n",
        false => "\n",
    };
    let mut r = Reader {
        writer: assign::Writer {
            declared: &declared,
            insert,
            texts: [text, data.unwrap_or("")],
            eol,
            taken: Vec::new(),
            computed: HashMap::new(),
        },
        point_setters: setters,
        at_motion: Context {
            declared: &declared,
            data: data.is_some(),
            routine: 0,
        },
        setters: frame_routines(text, &declared),
        local: routines(text),
        local_lines: HashMap::new(),
        call_lines: HashMap::new(),
        tables: super::backup::tables(context)?,
        state: entry,
        paths: Paths::default(),
        calls: HashMap::new(),
        out: Vec::new(),
        left: Vec::new(),
        events: Events::default(),
        jump: None,
        exit: None,
        loops: Vec::new(),
        labels: HashMap::new(),
        branches: super::branches::Branches::new(text),
        unrolled: (0, 0),
    };
    r.local_lines = (r.local.iter())
        .map(|(k, (l, _))| (k.clone(), *l))
        .collect();
    r.call_lines = call_lines(text, &r.local_lines);
    let lines: Vec<(u64, usize, &str)> = crate::program::lines(text).collect();
    r.run(&lines, (0, lines.len()), context, calls)?;
    r.branches.close_all()?;
    r.events.end_routine();
    if let (Some(line), false) = (r.jump, r.out.is_empty()) {
        return Err(at(line, "GOTO: a jump in a program with motions; the order the controller runs them would not be the file's: write the path as straight-line code".into()));
    }
    if context.leave_refused {
        r.out = leave_unknown(r.out, &mut r.left);
    }
    Ok(One {
        exit: r.exit.unwrap_or(r.state),
        targets: r.out,
        left: r.left,
        events: r.events,
    })
}

/// A module being read line by line ([`module`]).
struct Reader<'d> {
    at_motion: Context<'d>,
    /// Computes the points the program assigns.
    writer: assign::Writer<'d>,
    /// The points each routine after the first and each loop assign.
    point_setters: assign::Setters,
    /// The routines after the first that set a frame, by name, with that line.
    setters: HashMap<String, u64>,
    /// The routines after the first, by name: their line and number.
    local: HashMap<String, (u64, usize)>,
    /// The same, with their line only.
    local_lines: HashMap<String, u64>,
    call_lines: HashMap<String, Vec<u64>>,
    tables: HashMap<(bool, u32), Frame>,
    state: State,
    paths: Paths<State>,
    /// The state at each call of a routine of the file, by its upper-case name.
    calls: HashMap<String, Vec<(u64, State)>>,
    out: Vec<JointTarget>,
    left: Vec<Left>,
    events: Events,
    jump: Option<u64>,
    /// The state where the first routine ended (its `END`, a `RETURN` in it unsettling it).
    exit: Option<State>,
    /// Per loop open, the modules of the backup its body calls.
    loops: Vec<Vec<String>>,
    /// The labels (`NAME:`) of the routine read so far, by upper-case name, with their line.
    labels: HashMap<String, u64>,
    /// The branches the files decide ([`super::branches`]).
    branches: super::branches::Branches,
    /// The motions and statements the loops unrolled so far give ([`super::unroll`]).
    unrolled: (usize, usize),
}

impl Reader<'_> {
    /// Reads the lines `from..to`, the `FOR` loops whose body reads their variable unrolled
    /// ([`super::unroll`]).
    fn run(
        &mut self,
        lines: &super::unroll::Lines,
        (from, to): (usize, usize),
        context: &crate::program::Context,
        calls: &mut Calls,
    ) -> Result<()> {
        let mut k = from;
        while k < to {
            let (line, start, l) = lines[k];
            let routine = self.at_motion.routine;
            let eval = |t: &str| self.writer.evaluate(t, routine, &self.state.points);
            let unrolled = match self.branches.dead() {
                true => None,
                false => super::unroll::at_line(lines, (k, to), &eval, self.unrolled)?,
            };
            let Some(u) = unrolled else {
                self.statement((line, start), l, context, calls)?;
                k += 1;
                continue;
            };
            self.unrolled.0 += u.motions * u.values.len();
            self.unrolled.1 += u.steps;
            for v in &u.values {
                let value = assign::Value::Number(line, *v, true);
                self.state.points.insert(u.var.clone(), value);
                self.run(lines, (k + 1, u.end), context, calls)?;
            }
            let why = format!("is the variable of the FOR loop on line {line}, whose value after the loop stiffid does not take; set it after the loop");
            self.state.points.insert(u.var, assign::Value::Unknown(why));
            k = u.end + 1;
        }
        Ok(())
    }

    /// Reads the line `l` (number, first byte) of the module.
    fn statement(
        &mut self,
        (line, start): (u64, usize),
        l: &str,
        context: &crate::program::Context,
        calls: &mut Calls,
    ) -> Result<()> {
        let code = l.split(';').next().unwrap_or("");
        let words = words(code);
        let first = words.first().map(String::as_str).unwrap_or("");
        well_formed(line, first)?;
        let routine = self.at_motion.routine;
        self.label(line, code)?;
        if let Some(name) = routine_name(&words) {
            self.branches.close_all()?;
            self.routine_starts(&name, line);
            return Ok(());
        }
        let eval = |t: &str| self.writer.evaluate(t, routine, &self.state.points);
        if self.branches.pass(line, first, code, &eval) {
            return Ok(());
        }
        let closed_loop = self.loop_word(line, first, &words, routine);
        if let Some(closed) = flow(
            line,
            first,
            (&mut self.paths, &mut self.state),
            &mut self.out,
        ) {
            // The modules the loop's body calls run again with what its end leaves.
            if let (Some(c), Some(names)) = (closed, closed_loop)
                && let Some((_, end)) = &c.changed
            {
                for name in names {
                    super::called::again(&name, end, (&c.word, c.line), context, calls)?;
                }
            }
            return Ok(());
        }
        if first == "GOTO" {
            self.jump.get_or_insert(line);
        }
        if matches!(first, "FOR" | "WHILE" | "REPEAT" | "LOOP") {
            self.assigned_in_loop(line, first);
        }
        let values = &self.state.points;
        if let Some((name, value)) = self.writer.assignment(line, code, routine, values) {
            self.state.points.insert(name, value);
            return Ok(());
        }
        self.local_call(line, routine, code);
        let framed = self
            .state
            .frames
            .set(line, code, &self.at_motion.declared.fdats);
        if let Some((name, l)) = called(code, &self.setters) {
            self.state.frames.unsettle(line, format!("line {line} calls {name}, which sets a frame (line {l}): the frames after the call are the ones it leaves, which stiffid does not follow; set them again after the call"));
        }
        if self.state.speed.set(line, code)? || framed {
            return Ok(());
        }
        let values = (routine, &self.state.points);
        let found = match self.writer.operated((line, start), code, first, values)? {
            Some(found) => found,
            None => motion(
                (line, start),
                code,
                first,
                (&self.at_motion, &self.state.points),
            )?,
        };
        let targets = match found {
            Found::Nothing => return self.call((line, routine), code, context, calls),
            Found::RunTime(why, point) => {
                self.events.push(line, routine, EventKind::Motion);
                context.leave(&mut self.left, at(line, why))?;
                if let (Some(l), Some(p)) = (self.left.last_mut(), point) {
                    l.point = Some(p);
                }
                return Ok(());
            }
            Found::Home(what) => {
                self.events.push(line, routine, EventKind::Motion);
                self.left.push(Left::passed(line, what));
                return Ok(());
            }
            Found::Targets(t) => t,
        };
        self.events.push(line, routine, EventKind::Motion);
        self.moved(line, code, first, targets)
    }

    /// A word (`first`, the line's `words`) on `line` of `routine` that opens or closes a
    /// loop or returns: the modules the body of a loop it closes calls.
    fn loop_word(
        &mut self,
        line: u64,
        first: &str,
        words: &[String],
        routine: usize,
    ) -> Option<Vec<String>> {
        match first {
            "FOR" | "WHILE" | "REPEAT" | "LOOP" => {
                self.events.open_loop();
                self.loops.push(Vec::new());
                if let (Some(var), "FOR") = (words.get(1), first) {
                    let why = format!("is the variable of the FOR loop on line {line}, another on each run of its body, which stiffid reads once");
                    (self.state.points).insert(var.clone(), assign::Value::Unknown(why));
                }
            }
            "ENDFOR" | "ENDWHILE" | "UNTIL" | "ENDLOOP" => {
                self.events.close_loop();
                return self.loops.pop();
            }
            "RETURN" if routine == 1 => {
                let why = format!("its first routine returns on line {line} as well as at its END: which frames it leaves is the run's");
                self.exit
                    .get_or_insert_with(|| self.state.clone())
                    .frames
                    .unsettle(line, why);
            }
            _ => {}
        }
        None
    }

    /// The routine `name` whose `DEF` is on `line` starts: what is in force at its calls.
    fn routine_starts(&mut self, name: &str, line: u64) {
        self.labels.clear();
        self.at_motion.routine += 1;
        self.paths.clear();
        self.events.end_routine();
        if self.at_motion.routine > 1 {
            let mut next = entry(name, line, &self.calls, &self.call_lines);
            for (k, l) in &self.at_motion.declared.assigned {
                (next.points.entry(k.clone())).or_insert(assign::Value::Assigned(*l));
            }
            let done = std::mem::replace(&mut self.state, next);
            self.exit.get_or_insert(done);
            for (k, f) in &self.tables {
                self.state
                    .frames
                    .table
                    .entry(*k)
                    .or_insert_with(|| f.clone());
            }
        }
    }

    /// A call (`code`, on `line` of `routine`) of a routine of the file: the state at it kept
    /// for the routine's start; the points the routine assigns are the run's after it.
    fn local_call(&mut self, line: u64, routine: usize, code: &str) {
        let Some((name, _)) = called(code, &self.local_lines) else {
            return;
        };
        self.calls
            .entry(name.to_string())
            .or_default()
            .push((line, self.state.clone()));
        let number = self.local.get(name).map_or(0, |(_, n)| *n);
        self.events.push(line, routine, EventKind::Local(number));
        for (point, l) in self.point_setters.0.get(name).into_iter().flatten() {
            let why = format!("is assigned on line {l} in {name}, which line {line} calls: the value it leaves is the run's, which stiffid does not follow; assign it again after the call");
            self.state
                .points
                .insert(point.clone(), assign::Value::Unknown(why));
        }
    }

    /// The points the loop opening on `line` (its word `first`) assigns: their value at its
    /// motions before the assignment is the previous run's, so unknown from its start.
    fn assigned_in_loop(&mut self, line: u64, first: &str) {
        for (point, l) in self.point_setters.1.get(&line).into_iter().flatten() {
            let why = format!("is assigned on line {l} in the {first} loop of line {line}: at a motion of the loop before that line it holds the previous run's value; assign it before the motion in the loop");
            self.state
                .points
                .insert(point.clone(), assign::Value::Unknown(why));
        }
    }

    /// Refuses a label (`NAME:` alone on its line, a `GOTO`'s target) its routine defines twice:
    /// which line a `GOTO NAME` jumps to would not be sure (the controller refuses to load it).
    fn label(&mut self, line: u64, code: &str) -> Result<()> {
        let t = code.trim();
        let Some(name) = t.strip_suffix(':') else {
            return Ok(());
        };
        let word = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '$';
        if name.is_empty()
            || !name.chars().all(word)
            || name.starts_with(|c: char| c.is_ascii_digit())
        {
            return Ok(());
        }
        match self.labels.insert(name.to_ascii_uppercase(), line) {
            Some(first) if first != line => Err(at(line, format!("{name}: a label defined twice in one routine, on lines {first} and {line}; which one a GOTO {name} jumps to is not sure (the controller refuses the module): name each label once"))),
            _ => Ok(()),
        }
    }

    /// A statement on `line` of `routine` that is no motion: a call of a module of the backup,
    /// read there ([`super::called`]), or of a routine no file holds, placed among the motions.
    fn call(
        &mut self,
        (line, routine): (u64, usize),
        code: &str,
        context: &crate::program::Context,
        calls: &mut Calls,
    ) -> Result<()> {
        let Some(name) = super::calls::called(code) else {
            return Ok(());
        };
        let io = (context.io.into_iter())
            .flat_map(|io| io.routines())
            .any(|r| r.eq_ignore_ascii_case(&name));
        if self.local.contains_key(&name) || super::calls::passed(&name) || io {
            return Ok(());
        }
        match super::calls::module(&name, context) {
            Some(m) => {
                let (after, event) = super::called::call(line, &m, &self.state, context, calls)?;
                // The module's own points are its own: the program's stay as they were.
                let points = std::mem::take(&mut self.state.points);
                self.state = after;
                self.state.points = points;
                self.loops.iter_mut().for_each(|l| l.push(name.clone()));
                self.events.push(line, routine, event);
            }
            None => {
                let what = super::calls::unheld(&name, context);
                self.events.push(line, routine, EventKind::Unheld(what));
            }
        }
        Ok(())
    }

    /// The `targets` of the motion on `line` (its code, first word), with the frames and speed
    /// in force.
    fn moved(
        &mut self,
        line: u64,
        code: &str,
        first: &str,
        targets: Vec<JointTarget>,
    ) -> Result<()> {
        let fdats = &self.at_motion.declared.fdats;
        let (base, tool) = self.state.frames.motion(line, code, fdats);
        let speed = self.state.speed.motion(line, first, code)?;
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
            self.out.push(target);
        }
        Ok(())
    }
}

/// A frame not set before a motion: the controller's.
fn unset(name: &str) -> Frame {
    Frame::Unknown(0, format!("no {name} set before this Cartesian motion: its frame is the controller's, which the program does not state; set it in the program (an inline form's FDAT, {name} = {{X .., Y .., Z .., A .., B .., C ..}} or {}_DATA[n])", &name[1..]))
}

/// Takes a line whose first word (upper case) is `first` that opens, divides or closes a loop
/// or branch ([`crate::program::paths`]); `None` where it does none, else the construct it
/// closes, if any. A loop whose body ends with other frames than it began makes the frames of
/// its motions before the change unknown.
fn flow(
    line: u64,
    first: &str,
    (paths, state): (&mut Paths<State>, &mut State),
    out: &mut [JointTarget],
) -> Option<Option<Closed<State>>> {
    let kind = match first {
        "IF" => Some(Kind::Branches),
        "SWITCH" => Some(Kind::Cases),
        "FOR" | "WHILE" | "REPEAT" | "LOOP" => Some(Kind::Loop),
        _ => None,
    };
    if let Some(kind) = kind {
        paths.open((first, line), state, kind, out.len());
        return None;
    }
    match first {
        "ELSE" | "DEFAULT" => paths.branch(state, true),
        "CASE" => paths.branch(state, false),
        "ENDIF" | "ENDSWITCH" | "ENDFOR" | "ENDWHILE" | "UNTIL" | "ENDLOOP" => {
            let closed = paths.close(state);
            if let Some(closed) = &closed {
                repeated(closed, &mut out[closed.mark..]);
            }
            return Some(closed);
        }
        _ => return None,
    }
    Some(None)
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
        points: Default::default(),
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

/// The routines of the file after its first (`DEF`, `DEFFCT`), by upper-case name, with their
/// line and number (2 the second).
fn routines(text: &str) -> HashMap<String, (u64, usize)> {
    let mut out = HashMap::new();
    let mut seen = 0usize;
    for (line, _, l) in crate::program::lines(text) {
        let code = l.split(';').next().unwrap_or("");
        if let Some(name) = routine_name(&words(code)) {
            seen += 1;
            if seen > 1 {
                out.entry(name).or_insert((line, seen));
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
