//! The modules of the controller's backup a program calls (`MY_PATH( )` with `MY_PATH.src` and
//! its `.dat` in the backup, [`super::calls::module`]), read where they are called, as the LS
//! reader reads the programs a program calls: each one's motions compensated in place in its
//! own files, which follow the program's in the text written ([`Read::called`]), with what is
//! in force at its calls (joined over them) at its start; after each call, what its first
//! routine leaves in force (its frames, frame data and path speed), so the caller's motions
//! after it move with those. A module is read once (again where a later call joins other
//! values into its start); a module that calls itself, through any chain, is refused naming the
//! call; a refusal inside it names the call, its file and its line.
//!
//! [`Read::called`]: crate::program::Read::called

use super::calls::{EventKind, Events, Module};
use super::state::State;
use crate::program::paths::Join;
use crate::program::{at, Context, JointTarget, Left};
use stiffid_core::{Error, Result};

/// How deep calls are followed, as the LS reader does.
const DEPTH: usize = 16;

/// A module read: its name and `.src`'s file, where its text begins in the whole text, the
/// line of its first call, its start state, targets (spans in the whole text), motions left
/// (named by the call) and the state it leaves, and its events.
struct Callee {
    name: String,
    file: String,
    offset: usize,
    line: u64,
    entry: State,
    targets: Vec<JointTarget>,
    left: Vec<Left>,
    exit: State,
    events: Events,
}

/// What one module read gives: its own targets and motions left (spans in its text), the
/// state in force where its first routine ends (after a call of it), and its events
/// ([`super::calls::Events`]).
pub(super) struct One {
    pub targets: Vec<JointTarget>,
    pub left: Vec<Left>,
    pub exit: State,
    pub events: Events,
}

/// What reads a module's text with what is in force at its start (`super::read::module`).
pub(super) type ReadModule = fn(&str, &Context, State, &mut Calls) -> Result<One>;

/// The modules of the backup read so far (module docs).
pub(super) struct Calls {
    module: ReadModule,
    files: Vec<(String, String)>,
    total: usize,
    chain: Vec<String>,
    read: Vec<Callee>,
}

impl Calls {
    /// Before any call: the program's text (and its `.dat`) `total` bytes long, its first
    /// routine `main` (a call of it is a call of itself), each module read by `module`.
    pub(super) fn new(total: usize, main: Option<String>, module: ReadModule) -> Self {
        Calls {
            module,
            files: Vec::new(),
            total,
            chain: main.into_iter().collect(),
            read: Vec::new(),
        }
    }

    /// The targets of the modules read, in the order of their first call, the motions left in
    /// them, and their files (each `.src`, then its `.dat`), in the order their texts follow
    /// the program's.
    pub(super) fn finish(self) -> (Vec<JointTarget>, Vec<Left>, Vec<(String, String)>) {
        let mut targets = Vec::new();
        let mut left = Vec::new();
        for c in self.read {
            targets.extend(c.targets);
            left.extend(c.left);
        }
        (targets, left, self.files)
    }
}

/// The module `m` called on `line` with `state` in force, read (or joined into its earlier
/// read): the state after the call and the call's event.
///
/// # Errors
/// Naming `line`: a module that calls itself, a refusal inside it (its file and line).
pub(super) fn call(
    line: u64,
    m: &Module,
    state: &State,
    context: &Context,
    calls: &mut Calls,
) -> Result<(State, EventKind)> {
    let name = &m.name;
    if calls.chain.contains(name) || calls.chain.len() >= DEPTH {
        return Err(at(line, format!("{name}( ): the module calls itself through {}; stiffid follows calls that end ({DEPTH} deep)", calls.chain.join(", "))));
    }
    let k = match calls.read.iter().position(|c| c.name == *name) {
        Some(k) => {
            let first = calls.read[k].line;
            let construct = format!("the calls of {name} (lines {first} and {line})");
            joined(k, m, state, (&construct, line), context, calls)?;
            k
        }
        None => {
            let offset = calls.total;
            let dat = m.dat.map(|d| d.1);
            calls.total += m.src.1.len() + dat.map_or(0, str::len);
            calls.files.push((m.src.0.to_string(), m.src.1.to_string()));
            if let Some((file, text)) = m.dat {
                calls.files.push((file.to_string(), text.to_string()));
            }
            let c = read(line, m, state.clone(), (offset, line), context, calls)?;
            calls.read.push(c);
            calls.read.len() - 1
        }
    };
    let c = &calls.read[k];
    let moves = !c.targets.is_empty() || !c.left.is_empty();
    let event = EventKind::Held(
        name.clone(),
        crate::program::file_name(&c.file).to_string(),
        Box::new(c.events.clone()),
        moves,
    );
    Ok((c.exit.clone(), event))
}

/// Module `name`, read already, run again with `state` at its start where the construct
/// `(word, line)` of its caller closes (a loop whose body ends with other frames than it began,
/// around the call): `state` joined into its start.
///
/// # Errors
/// Those of [`call`].
pub(super) fn again(
    name: &str,
    state: &State,
    construct: (&str, u64),
    context: &Context,
    calls: &mut Calls,
) -> Result<()> {
    let (Some(k), Some(m)) = (
        calls.read.iter().position(|c| c.name == name),
        super::calls::module(name, context),
    ) else {
        return Ok(());
    };
    joined(k, &m, state, construct, context, calls)
}

/// Module `m`, read as `calls.read[k]`, with `state` joined into its start after `construct`:
/// read again where that changes it.
fn joined(
    k: usize,
    m: &Module,
    state: &State,
    construct: (&str, u64),
    context: &Context,
    calls: &mut Calls,
) -> Result<()> {
    let mut entry = calls.read[k].entry.clone();
    entry.join(state, construct);
    if !entry.agrees(&calls.read[k].entry) {
        let (offset, first) = (calls.read[k].offset, calls.read[k].line);
        calls.read[k] = read(first, m, entry, (offset, first), context, calls)?;
    }
    Ok(())
}

/// The module `m` read with `entry` at its start, its text at `offset` of the whole text,
/// called first on `first` (a call on `line` read it).
fn read(
    line: u64,
    m: &Module,
    entry: State,
    (offset, first): (usize, u64),
    context: &Context,
    calls: &mut Calls,
) -> Result<Callee> {
    let inner = Context {
        data: m.dat.map(|d| d.1),
        ..*context
    };
    let file = crate::program::file_name(m.src.0);
    let krl = crate::program::Dialect::Krl;
    crate::program::ends::check(m.src.1, krl).map_err(|e| within(line, &m.name, file, e))?;
    if let Some((dat, text)) = m.dat {
        let dat = crate::program::file_name(dat);
        crate::program::ends::check_data(text, dat, krl).map_err(|e| match e {
            Error::Program { message, .. } => at(line, format!("{}( ): {message}", m.name)),
            other => other,
        })?;
    }
    calls.chain.push(m.name.clone());
    let one = (calls.module)(m.src.1, &inner, entry.clone(), calls);
    calls.chain.pop();
    let one = one.map_err(|e| within(line, &m.name, file, e))?;
    let left = (one.left.into_iter())
        .map(|l| Left {
            line,
            why: format!("{}( ): {file} line {}: {}", m.name, l.line, l.why),
            point: l.point.map(|p| p.shifted(offset)),
        })
        .collect();
    Ok(Callee {
        name: m.name.clone(),
        file: m.src.0.to_string(),
        offset,
        line: first,
        entry,
        targets: one.targets.into_iter().map(|t| t.shifted(offset)).collect(),
        left,
        exit: one.exit,
        events: one.events,
    })
}

/// An error `e` of module `name` (its `.src` `file`) called on `line`, named as the call's.
fn within(line: u64, name: &str, file: &str, e: Error) -> Error {
    match e {
        Error::Program { line: l, message } => {
            at(line, format!("{name}( ): {file} line {l}: {message}"))
        }
        other => other,
    }
}
