//! Points a module assigns whole (`p2 := Offs(p1, 0, 0, 10);`, `p2 := RelTool(p1, ..);`,
//! `p2 := p1;`, `p2 := [[..],..];`, *RAPID kernel*: assignments): a `robtarget` or
//! `jointtarget` of the module that only such statements of its `PROC`s set is, at a motion, the
//! value the last assignment before it on every path gave, read at the assignment as a motion's
//! target is and written back there (the point `Offs` names, or the literal). Where the paths
//! to a motion disagree (an assignment in one branch only, in a loop before which a motion of the
//! loop moves to it, a routine's start, a call of a routine that assigns it, a routine with a
//! `GOTO`) the motion is refused naming the lines. A point set otherwise (a component
//! `p.trans.z := ..`, an element, in an error handler, a `TRAP` or `FUNC`, or by a compact `IF`)
//! stays refused at every motion (module `named`).

use super::{calls, first_word, is_header, named, words_of, Data, Statement};
use crate::program::JointTarget;
use std::collections::{BTreeMap, HashMap, HashSet};
use std::sync::atomic::{AtomicUsize, Ordering};
use stiffid_core::Error;

/// Each assigned point's value in force (lower-case name).
pub(super) type Bound = BTreeMap<String, Binding>;

/// The value of an assigned point at a statement: the assignment read (its number among the
/// assignments read, so that two readings of one line differ) and its target, or why the file
/// does not say.
#[derive(Debug, Clone)]
pub(super) struct Binding {
    id: usize,
    pub target: Result<JointTarget, String>,
}

impl PartialEq for Binding {
    fn eq(&self, other: &Self) -> bool {
        self.id == other.id
            && match (&self.target, &other.target) {
                (Ok(_), Ok(_)) => true,
                (Err(a), Err(b)) => a == b,
                _ => false,
            }
    }
}

/// The module's points assigned whole (module docs): each one's assignments (line and
/// routine, lower case), whether each is a `robtarget`, the routines with a `GOTO`, and the
/// points set otherwise with the line that does.
#[derive(Debug, Default)]
pub(super) struct Rebound {
    names: HashMap<String, Vec<(u64, String)>>,
    kinds: HashMap<String, bool>,
    jumping: HashSet<String>,
    other: Vec<(String, u64)>,
}

impl Rebound {
    /// The points of the module `code` (its `statements`) assigned whole (module docs).
    pub(super) fn of(code: &str, statements: &[Statement]) -> Rebound {
        let mut out = Rebound::default();
        let (mut routine, mut plain) = (String::new(), false);
        let mut whole: Vec<(String, u64, String)> = Vec::new();
        for s in statements {
            let body = &code[s.span.clone()];
            let first = first_word(body);
            if let Some(name) = calls::routine(body) {
                routine = name.to_ascii_lowercase();
                plain = calls::procedure(body).is_some();
                continue;
            }
            match first.as_str() {
                "error" | "undo" | "backward" if is_header(body) => plain = false,
                _ if super::numflow::jumps(body, &first, s.line) => {
                    _ = out.jumping.insert(routine.clone())
                }
                _ => {}
            }
            let lower = body.to_ascii_lowercase();
            if let ["const" | "var" | "pers", kind @ ("robtarget" | "jointtarget"), name, ..] =
                words_of(&lower).as_slice()
            {
                let name = name.trim_end_matches(';');
                if !name.contains('{') {
                    out.kinds.insert(name.to_string(), *kind == "robtarget");
                }
                continue;
            }
            let compact = (first == "if" && !is_header(body))
                .then(|| super::flow::compact_instruction(body))
                .flatten();
            let statement = compact.map_or(body, |at| &body[at..]);
            match (assigned(statement), compact) {
                (Some((name, true)), None) if plain => whole.push((name, s.line, routine.clone())),
                (Some((name, _)), _) => out.other.push((name, s.line)),
                (None, _) => {}
            }
        }
        let set_otherwise: HashSet<&String> = out.other.iter().map(|(n, _)| n).collect();
        for (name, line, routine) in whole {
            if out.kinds.contains_key(&name) && !set_otherwise.contains(&name) {
                out.names.entry(name).or_default().push((line, routine));
            }
        }
        out
    }

    /// Whether the module assigns no point whole.
    pub(super) fn is_empty(&self) -> bool {
        self.names.is_empty()
    }

    /// The points set otherwise than whole, with a line that sets each, into `assigned` (a
    /// compact `IF`'s assignment included: refused at every motion).
    pub(super) fn refuse_others(&self, assigned: &mut HashMap<String, u64>) {
        for (name, line) in &self.other {
            if self.kinds.contains_key(name) {
                assigned.entry(name.clone()).or_insert(*line);
            }
        }
    }

    /// The values in force at the start of `routine` (lower case): every assigned point's is
    /// the run's.
    pub(super) fn at_start(&self, routine: &str, line: u64) -> Bound {
        let why = |name: &str, l: u64| {
            format!("{name} is assigned on line {l}, and at the start of the routine on line {line} ({routine}) it holds what the run assigned before; assign it in the routine before the motion")
        };
        self.forget(|_| true, why)
    }

    /// The values after a call of the module's routine `called` (lower case) on `line` from
    /// `routine`: a point another routine assigns is the run's.
    pub(super) fn after_call(&self, (called, line): (&str, u64), routine: &str, bound: &mut Bound) {
        let why = |name: &str, l: u64| {
            format!("{name} is assigned on line {l}, outside this routine, and the call of {called} on line {line} may run that assignment: its value after the call is the run's")
        };
        let others = |list: &[(u64, String)]| list.iter().any(|(_, r)| r != routine);
        bound.extend(self.forget(others, why));
    }

    /// The values at the start of a loop whose body is `statements[k + 1..]` up to its end
    /// (`code`): a point the body assigns holds another value at the body's motions before the
    /// assignment on every pass after the first.
    pub(super) fn at_loop(
        &self,
        (code, statements): (&str, &[Statement]),
        k: usize,
        bound: &mut Bound,
    ) {
        let open = statements[k].line;
        let mut depth = 0;
        for s in &statements[k..] {
            let body = &code[s.span.clone()];
            match first_word(body).as_str() {
                "while" | "for" => depth += 1,
                "endwhile" | "endfor" => depth -= 1,
                _ => {}
            }
            if depth == 0 {
                break;
            }
            if let Some((name, true)) = assigned(body).filter(|(n, _)| self.names.contains_key(n)) {
                let why = format!("{name} is assigned on line {} inside the loop on line {open}: on every pass after the first the loop's motions before the assignment move to that value; assign it before them in the loop, or before the loop", s.line);
                bound.insert(
                    name,
                    Binding {
                        id: 0,
                        target: Err(why),
                    },
                );
            }
        }
    }

    /// The forgotten values of the points whose assignments `which` takes, each naming why.
    fn forget(
        &self,
        which: impl Fn(&[(u64, String)]) -> bool,
        why: impl Fn(&str, u64) -> String,
    ) -> Bound {
        (self.names.iter().filter(|(_, list)| which(list)))
            .map(|(name, list)| {
                let target = Err(why(name, list[0].0));
                (name.clone(), Binding { id: 0, target })
            })
            .collect()
    }
}

/// The point a statement assigns (lower case, the name before any component or element) and
/// whether it assigns it whole (`p := ..`); `None` for any other statement.
fn assigned(statement: &str) -> Option<(String, bool)> {
    let t = statement.trim_start();
    let ident: String = (t.chars())
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
        .collect();
    let rest = t[ident.len()..].trim_start();
    if ident.is_empty() || !t.starts_with(|c: char| c.is_ascii_alphabetic()) {
        return None;
    }
    let name = ident.to_ascii_lowercase();
    match rest {
        r if r.starts_with(":=") => Some((name, true)),
        r if r.starts_with(['.', '{']) && r.contains(":=") => Some((name, false)),
        _ => None,
    }
}

/// The number of the next assignment read (each reading's own, [`Binding`]).
static READS: AtomicUsize = AtomicUsize::new(1);

/// Reads the assignment statement `s` of `code` (its first word `first`, lower case) of a point
/// the module assigns whole, in the routine `routine`: its value into `bound`. Any other
/// statement: nothing.
pub(super) fn statement(
    (s, code, first): (&Statement, &str, &str),
    routine: &str,
    data: &Data,
    bound: &mut Bound,
) {
    if !data.rebound.names.contains_key(first) {
        return;
    }
    let id = READS.fetch_add(1, Ordering::Relaxed);
    let target = match data.rebound.jumping.contains(routine) {
        true => Err(format!("{first} is assigned on line {} in a routine with a GOTO: which assignment ran before the motion is the run's", s.line)),
        false => value((s, code, first), data.rebound.kinds[first], data),
    };
    bound.insert(first.to_string(), Binding { id, target });
}

/// The value the assignment `s` of `code` gives the point `name` (a `robtarget` where
/// `cartesian`), read as a motion's target is.
fn value(
    (s, code, name): (&Statement, &str, &str),
    cartesian: bool,
    data: &Data,
) -> Result<JointTarget, String> {
    let body = &code[s.span.clone()];
    let eq = body.find(":=").unwrap_or(0);
    let from = s.span.start + eq + 2;
    let end = s.span.end - usize::from(body.ends_with(';'));
    let text = &code[from..end];
    let kind = if cartesian {
        "robtarget"
    } else {
        "jointtarget"
    };
    let written = &body.trim_start()[..name.len()];
    let named = |ident: &str| named::target(data, (s.line, written), (kind, cartesian), ident);
    let read = match cartesian {
        true => super::cartesian::point(s.line, code, from, text, (&named, &data.nums)),
        false => joint(s.line, (code, from, text), &named),
    };
    read.map_err(|e| match e {
        Error::Program { message, .. } => format!(
            "{name} is assigned on line {} a value stiffid does not read: {message}",
            s.line
        ),
        other => other.to_string(),
    })
}

/// A `jointtarget` assigned: a literal, or a declared one (or an array's element).
fn joint(
    line: u64,
    (code, from, text): (&str, usize, &str),
    named: &dyn Fn(&str) -> stiffid_core::Result<JointTarget>,
) -> stiffid_core::Result<JointTarget> {
    let lead = text.len() - text.trim_start().len();
    let t = text.trim();
    if t.starts_with("[[") {
        return super::literal(line, code, from + lead);
    }
    let plain = t.starts_with(|c: char| c.is_ascii_alphabetic())
        && (t.chars()).all(|c| c.is_ascii_alphanumeric() || c == '_');
    let element = t.ends_with('}') && t.contains('{');
    match (plain, element) {
        (true, _) => named(t).map(|j| super::at_reference(j, from + lead..from + lead + t.len())),
        (false, true) => named(t),
        _ => Err(crate::program::at(line, format!("'{}': a value the controller computes; stiffid reads a literal or a declared jointtarget", stiffid_core::common::limits::short(t)))),
    }
}
