//! An LS program's targets read along its order of run ([`super::flow`]): each motion where it
//! is in the file, with the frame numbers in force on every path that reaches it (joined where
//! paths meet: numbers the paths select differently refuse the Cartesian positions that use them,
//! naming the lines, or leave them as found with [`crate::program::Context::leave_refused`]) and
//! the motion before it (an `INC` motion's start: one motion on every path, ending `FINE`).

use super::copies::{self, Copies};
use super::flow::{self, Graph};
use super::numbered::Declared;
use super::registers::Used;
use super::statements::{self, Number, Place, Selected};
use super::{calls, instructions, motion, numbered, offsets, positions, registers};
use super::{set_frames, sysframe};
use crate::program::cartesian::Frame;
use crate::program::{at, Context, JointTarget, Left, Units};
use std::collections::HashMap;
use stiffid_core::common::limits::short;
use stiffid_core::{Error, Result};

/// The motion that ran before an instruction on every path to it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Previous {
    /// None: the program's start.
    Start,
    /// The motion instruction of this index.
    Motion(usize),
    /// Paths come from different motions (or from the start and a motion).
    Many,
}

/// What is in force before an instruction.
#[derive(Debug, Clone)]
struct State {
    selected: Selected,
    previous: Previous,
}

/// What an LS program holds ([`targets`]): its targets (then those of the programs it calls),
/// its external axes and their units, the motions left as found, and the programs of the backup
/// it calls that move (each file's name as given and its text).
pub(super) struct Program {
    pub targets: Vec<JointTarget>,
    pub axes: Vec<String>,
    pub units: Units,
    pub left: Vec<Left>,
    pub called: Vec<(String, String)>,
    pub notes: Vec<String>,
}

/// One program read: its own targets (spans in its text), those of the programs it calls
/// (spans in the whole text), its axes and units, the motions left.
struct One {
    /// The frame numbers its remarks (or its callers') declare the setup's own.
    declared: Declared,
    own: Vec<JointTarget>,
    nested: Vec<JointTarget>,
    axes: Vec<String>,
    units: Units,
    left: Vec<Left>,
    notes: Vec<String>,
}

/// The programs of the backup called so far: their files in the order their texts follow the
/// program's, each one's frames in force where it is called and the first call's line, the
/// length of every text so far, and the chain of calls being read.
struct Calls {
    files: Vec<(String, String)>,
    read: HashMap<String, (Selected, u64, Place, Declared)>,
    total: usize,
    chain: Vec<String>,
    /// The position registers the programs being read set, and where: the run's in the programs
    /// they call.
    inherited: Vec<(u32, String)>,
}

/// A call of a program of the backup that moves: its name, file and text, and what it leaves
/// selected after it (a frame number it selects, which stiffid does not follow out of it).
struct Call<'a> {
    name: String,
    file: &'a str,
    text: &'a str,
    leaves: Selected,
    /// Where the call sits among the motions of the path that reaches it (the callers'
    /// included): its instructions sit there too.
    place: Place,
}

/// Every joint target of `text`, in the order of the `/MN` motions, then those of the programs
/// of the backup it calls that move (module docs), each compensated in place in its own file;
/// the frames the `context`'s backup holds by number taken from it (`sysframe`).
///
/// # Errors
/// Naming the line: a construct refused ([`flow`], [`statements`], [`motion`]), a motion no path
/// reaches; in a called program, naming the call's line, the program's file and its line.
pub(super) fn targets(text: &str, context: &Context) -> Result<Program> {
    let mut calls = Calls {
        files: Vec::new(),
        read: HashMap::new(),
        total: text.len(),
        chain: Vec::new(),
        inherited: Vec::new(),
    };
    let start = Place {
        after_first: false,
        before_last: false,
    };
    let entry = (Selected::default(), Declared::of(text)?);
    let one = read_one(text, context, entry, start, &mut calls)?;
    let mut targets = one.own;
    targets.extend(one.nested);
    Ok(Program {
        targets,
        axes: one.axes,
        units: one.units,
        left: one.left,
        called: calls.files,
        notes: one.notes,
    })
}

/// The program `text` read with `entry` in force at its start (the frame numbers selected and
/// declared; module docs).
fn read_one(
    text: &str,
    context: &Context,
    (entry, declared): (Selected, Declared),
    outer: Place,
    calls: &mut Calls,
) -> Result<One> {
    let (mut positions, mut axes, mut units) = positions(text)?;
    let instructions = instructions(text)?;
    let motions: Vec<bool> = (instructions.iter())
        .map(|(_, t)| motion::rest(t.trim()).is_some())
        .collect();
    super::mask::check(text, motions.iter().any(|m| *m))?;
    let graph = flow::graph(&instructions, &motions)?;
    // The frames the program sets at its start, read where no motion of a caller follows.
    let set = match outer.after_first || outer.before_last {
        true => set_frames::Set::default(),
        false => set_frames::read(&instructions, context)?,
    };
    let (effects, called) = effects(
        &instructions,
        (&motions, &set.handled),
        &graph,
        context,
        outer,
    )?;
    let reached = graph.reached();
    if let Some(k) = (0..motions.len()).find(|&k| motions[k] && !reached[k]) {
        return Err(never_run(&instructions, &graph, k));
    }
    let step = |k: usize, s: &State| {
        let mut s = s.clone();
        if motions[k] {
            s.previous = Previous::Motion(k);
        }
        let e: &Selected = match &called[k] {
            Some(c) => {
                s.previous = Previous::Many;
                &c.leaves
            }
            None => &effects[k],
        };
        s.selected.user = e.user.clone().or(s.selected.user);
        s.selected.tool = e.tool.clone().or(s.selected.tool);
        s
    };
    let join = |a: &mut State, b: &State, k: usize| {
        let changed = a.selected.join(&b.selected, instructions[k].0);
        let many = a.previous != b.previous && a.previous != Previous::Many;
        if many {
            a.previous = Previous::Many;
        }
        changed || many
    };
    let start = State {
        selected: entry,
        previous: Previous::Start,
    };
    let states = graph.states(start, step, join);
    let registers = registers::read(&instructions, (&motions, &graph), &calls.inherited, context)?;
    let largest = positions.keys().max().copied().unwrap_or(0);
    let selected = |k: usize| states[k].as_ref().map(|s| s.selected.clone());
    let copies = copies::build(text, &instructions, &registers.targets, selected, largest)?;
    let own_positions = !positions.is_empty();
    (axes, units) = copies::axes(&instructions, &copies, (own_positions, axes, units))?;
    positions.extend(copies.positions.iter().map(|(k, t)| (*k, t.clone())));
    // The motions left as found (their register set as the program runs) are not read.
    let mut reading = motions.clone();
    registers.left.iter().for_each(|(k, _)| reading[*k] = false);
    let read = (&positions, &copies, &registers);
    let (mut own, in_force) = motions_read(&instructions, &reading, &states, read)?;
    numbered::apply(declared, &mut own, &in_force);
    sysframe::apply(context, &mut own)?;
    set_frames::apply(&set, &mut own);
    let mut left: Vec<Left> = registers.left.iter().map(|(_, l)| l.clone()).collect();
    if context.leave_refused {
        own = leave_paths(own, &in_force, &mut left);
    }
    let mut notes: Vec<(usize, String)> = (copies.by_motion.iter())
        .map(|(k, c)| (*k, c.note.clone()))
        .collect();
    notes.sort();
    let mut one = One {
        declared,
        own,
        nested: Vec::new(),
        axes,
        units,
        left,
        notes: notes.into_iter().map(|(_, n)| n).collect(),
    };
    read_calls(&instructions, (&called, &states), context, calls, &mut one)?;
    Ok(one)
}

/// The programs `called` (per instruction of `instructions`, with the `states` before it) read
/// into `one`, each with the frames in force at every call of it joined, and the registers
/// `instructions` set the run's in them.
fn read_calls(
    instructions: &[(u64, String)],
    (called, states): (&[Option<Call>], &[Option<State>]),
    context: &Context,
    calls: &mut Calls,
    one: &mut One,
) -> Result<()> {
    let mark = calls.inherited.len();
    let caller = calls
        .chain
        .last()
        .map_or("the calling program", String::as_str);
    let sets = registers::sets(instructions, caller);
    calls.inherited.extend(sets);
    for (k, call) in called.iter().enumerate() {
        let (Some(call), Some(state)) = (call, states[k].as_ref()) else {
            continue;
        };
        // The frames in force at every call of the program, joined.
        let mut entry = state.selected.clone();
        for (j, other) in called.iter().enumerate().skip(k + 1) {
            if let (Some(o), Some(s)) = (other, states[j].as_ref())
                && o.name == call.name
            {
                entry.join(&s.selected, instructions[j].0);
            }
        }
        read_called(instructions[k].0, call, entry, context, calls, one)?;
    }
    calls.inherited.truncate(mark);
    Ok(())
}

/// The targets of the motions of `instructions` (`motions` says which), each with the state
/// before it (`states`), to the `/POS` `positions` (a motion to a position register: to its
/// copy among `copies`; offset by one: by its value, `registers`); per target, the frame
/// numbers in force.
fn motions_read(
    instructions: &[(u64, String)],
    motions: &[bool],
    states: &[Option<State>],
    (positions, copies, registers): (&HashMap<u64, JointTarget>, &Copies, &Used),
) -> Result<(Vec<JointTarget>, Vec<Selected>)> {
    let mut out: Vec<JointTarget> = Vec::new();
    let mut in_force: Vec<Selected> = Vec::new();
    // Per motion read, the end of its targets in `out` and whether it ended `FINE`.
    let mut read: HashMap<usize, (usize, bool)> = HashMap::new();
    for (k, (line, instruction)) in instructions.iter().enumerate() {
        let Some(state) = states[k].as_ref().filter(|_| motions[k]) else {
            continue;
        };
        let before = match state.previous {
            Previous::Motion(j) => read.get(&j).copied(),
            _ => None,
        };
        let (before, fine) = before.map_or((&[][..], false), |(end, f)| (&out[..end], f));
        let copy = copies.by_motion.get(&k);
        let (mut targets, fine) = motion::targets(
            *line,
            instruction.trim(),
            positions,
            (before, fine),
            copy.map(|c| c.index),
        )?;
        if let (Some(c), Some(first)) = (copy, targets.first_mut()) {
            *first = c.attach(first.clone());
        }
        if let (Some(o), Some(first)) = (registers.offsets.get(&k), targets.first_mut()) {
            offsets::apply(*line, first, o, registers.frames.get(&k))?;
        }
        in_force.extend(std::iter::repeat_n(state.selected.clone(), targets.len()));
        out.extend(targets);
        read.insert(k, (out.len(), fine));
    }
    Ok((out, in_force))
}

/// The program `call` called on `line` with `entry` in force, read into `one` (its targets after
/// the caller's, its text after every text so far), once: called again with other frames in
/// force, or in a loop of calls, refused naming the line.
fn read_called(
    line: u64,
    call: &Call,
    entry: Selected,
    context: &Context,
    calls: &mut Calls,
    one: &mut One,
) -> Result<()> {
    let name = &call.name;
    if calls.chain.contains(name) || calls.chain.len() >= 16 {
        return Err(at(
            line,
            format!(
                "CALL {name}: the program calls itself through {}; stiffid follows calls that end",
                calls.chain.join(", ")
            ),
        ));
    }
    crate::program::ends::check(call.text, crate::program::Dialect::FanucLs)
        .map_err(|e| within(line, call, e))?;
    let declared = one.declared.within(call.text, line)?;
    if let Some((first, first_line, place, first_declared)) = calls.read.get(name) {
        let mut same = first.clone();
        return match same.join(&entry, line) || *first_declared != declared {
            false => again(call, *place, context).map_err(|e| within(line, call, e)),
            true => Err(at(line, format!("CALL {name}: called on line {first_line} too, with other frame numbers in force or declared; its Cartesian positions would be in other frames on each: select UFRAME_NUM and UTOOL_NUM alike before every call, or in {name}"))),
        };
    }
    let offset = calls.total;
    calls.total += call.text.len();
    calls
        .files
        .push((call.file.to_string(), call.text.to_string()));
    calls
        .read
        .insert(name.clone(), (entry.clone(), line, call.place, declared));
    calls.chain.push(name.clone());
    let inner = read_one(call.text, context, (entry, declared), call.place, calls)
        .map_err(|e| within(line, call, e))?;
    calls.chain.pop();
    if inner.axes != one.axes {
        return Err(at(line, format!("CALL {name}: {} moves the external axes [{}], this program [{}]; stiffid compensates one set of axes: give both programs the same groups and extended axes", call.file, inner.axes.join(", "), one.axes.join(", "))));
    }
    one.nested
        .extend(inner.own.into_iter().map(|t| t.shifted(offset)));
    one.nested.extend(inner.nested);
    let file = call.file;
    (one.notes).extend(
        inner
            .notes
            .iter()
            .map(|n| format!("CALL {name}: {file} {n}")),
    );
    one.left.extend(inner.left.into_iter().map(|l| Left {
        line,
        why: format!("CALL {name}: {} line {}: {}", call.file, l.line, l.why),
        point: None,
    }));
    Ok(())
}

/// Per instruction, the frame numbers it selects (its own only) and, through
/// [`statements::instruction`], the refusal of what it may not do where it runs: after a motion
/// on some path, before one on some path ([`Place`]); and the calls of programs of the backup
/// that move ([`calls::moving`]). A call of a program of the backup that moves nothing is
/// passed over ([`calls`]), and so are the instructions `handled` ([`set_frames`]).
fn effects<'a>(
    instructions: &[(u64, String)],
    (motions, handled): (&[bool], &[usize]),
    graph: &Graph,
    context: &Context<'a>,
    outer: Place,
) -> Result<(Vec<Selected>, Vec<Option<Call<'a>>>)> {
    let after = graph.after(motions);
    let leads = graph.leads_to(motions);
    let mut out = vec![Selected::default(); instructions.len()];
    let mut called: Vec<Option<Call>> = (0..instructions.len()).map(|_| None).collect();
    for (k, (line, instruction)) in instructions.iter().enumerate() {
        let t = instruction.trim();
        if motions[k] || handled.contains(&k) || calls::passed_over(t, context) {
            continue;
        }
        let place = Place {
            after_first: after[k] || outer.after_first,
            before_last: leads[k] || outer.before_last,
        };
        if let Some((name, file, text)) = calls::moving(t, context) {
            let leaves = leaves(*line, &name, calls::selections(text, context, 0));
            called[k] = Some(Call {
                name,
                file,
                text,
                leaves,
                place,
            });
            continue;
        }
        statements::instruction(*line, t, place, &mut out[k])?;
    }
    Ok((out, called))
}

/// An error `e` of program `call` called on `line`, named as the call's.
fn within(line: u64, call: &Call, e: Error) -> Error {
    match e {
        Error::Program { line: l, message } => at(
            line,
            format!("CALL {}: {} line {l}: {message}", call.name, call.file),
        ),
        other => other,
    }
}

/// Program `call` called again where it was first called at `first`: where the call sits among
/// the motions adds to what it was read with, its instructions checked there too (a call of a
/// program the backup does not hold, at the start of a program first called before any
/// motion, sits between two motions when it is called again between them).
fn again(call: &Call, first: Place, context: &Context) -> Result<()> {
    let place = call.place;
    if (place.after_first && !first.after_first) || (place.before_last && !first.before_last) {
        let instructions = instructions(call.text)?;
        let motions: Vec<bool> = (instructions.iter())
            .map(|(_, t)| motion::rest(t.trim()).is_some())
            .collect();
        let graph = flow::graph(&instructions, &motions)?;
        effects(&instructions, (&motions, &[]), &graph, context, place)?;
    }
    Ok(())
}

/// What a call on `line` of program `name` leaves selected: each frame number it selects (its
/// lines `selects`: user, tool) unknown after it, saying why.
fn leaves(line: u64, name: &str, selects: (Option<u64>, Option<u64>)) -> Selected {
    let why = |word: &str, l: u64| {
        Number::Paths(format!("line {line} calls {name}, which selects {word} (its line {l}): the frame in force after the call is the one it leaves, which stiffid does not follow; select {word} again after the call"))
    };
    Selected {
        user: selects.0.map(|l| why("UFRAME_NUM", l)),
        tool: selects.1.map(|l| why("UTOOL_NUM", l)),
    }
}

/// The refusal of the motion `k` that no path from the program's start reaches: naming the
/// instruction before it that ends the program or jumps away (`END`, `ABORT`, `JMP`).
fn never_run(instructions: &[(u64, String)], graph: &Graph, k: usize) -> Error {
    let motion_line = instructions[k].0;
    match (0..k).rev().find(|&j| graph.stops[j]) {
        Some(j) => {
            let (line, t) = &instructions[j];
            let jump = t.trim().to_ascii_uppercase().contains("LBL[");
            match jump {
                true => at(*line, format!("{}: the motion on line {motion_line} after it is reached by no path (no label leads to it): the controller never runs it; remove it", short(t.trim()))),
                false => at(*line, format!("{}: the program ends here, before the motions after it: remove them or the instruction", short(t.trim()))),
            }
        }
        None => at(motion_line, "the motion is reached by no path from the program's start: the controller never runs it; remove it".into()),
    }
}

/// The targets of `out` whose frame or tool is unknown because the paths that reach their motion
/// select it differently (`in_force`) moved to `left`, left as found.
fn leave_paths(
    out: Vec<JointTarget>,
    in_force: &[Selected],
    left: &mut Vec<Left>,
) -> Vec<JointTarget> {
    let mut kept = Vec::with_capacity(out.len());
    for (t, s) in out.into_iter().zip(in_force) {
        let paths = |n: &Option<Number>| matches!(n, Some(Number::Paths(_)));
        let why = t
            .cartesian
            .as_deref()
            .and_then(|c| match (&c.frame, &c.tool) {
                (Frame::Unknown(_, why), _) if paths(&s.user) => Some(why.clone()),
                (_, Frame::Unknown(_, why)) if paths(&s.tool) => Some(why.clone()),
                _ => None,
            });
        match why {
            Some(why) => left.push(Left::of(&t, why)),
            None => kept.push(t),
        }
    }
    kept
}
