//! The values an LS program gives its registers itself, found along every path that reaches a
//! motion ([`super::flow`]), so that a motion to a position register, or offset by one, reads the
//! value the program leaves in it (FANUC R-30iA/R-30iB HandlingTool operator's manual, "Register
//! instructions", "Position register instructions", "Position register element").
//!
//! - `R[i]=` arithmetic (`+`, `-`, `*`, `/`, parentheses) of numbers, `R[j]` and `PR[j,k]` the
//!   program states; `FOR R[i]=..` and anything else (`R[i]=DI[1]`, `DIV`, `MOD`) leave it to the
//!   run, as does a call or run of another program (it may set it). At the program's start every
//!   `R[i]` is the controller's.
//! - `PR[i,j]=` the same arithmetic, element `j` (`X`..`R`, then the extended axes; `J1`.. of a
//!   joint register); `PR[i]=PR[j]`, `PR[i]=PR[j]+PR[k]-PR[l]..` element by element, in the first
//!   one's representation (two representations mixed: the run's); `PR[i]=LPOS`, `JPOS`, `P[..]`
//!   and anything else: the run's.
//! - A register no instruction of the program sets is the backup's (`POSREG.VA`,
//!   [`super::registers`]). One it sets starts each run with what the run before left: an element
//!   the program sets anywhere is known only after it sets it on every path; one it never sets
//!   is the backup's.
//! - `OFFSET CONDITION PR[i]` (`,UFRAME[j]`) and `TOOL_OFFSET CONDITION PR[i]` (`,UTOOL[j]`):
//!   the register a motion's bare `Offset` (`Tool_Offset`) moves by, and the frame it is in.
//!
//! Where paths meet with different values, the value is the run's, named with both lines.

use super::flow::Graph;

/// The position registers' file in a backup.
pub(super) const FILE: &str = "POSREG.VA";

use super::statements::english;
use super::va::{Entry, Value};
use std::collections::BTreeMap;

/// One number as the run holds it before an instruction.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Num {
    /// Its value, and the line that sets it (0: the backup's).
    Known(f64, u64),
    /// Why the file does not say it.
    Run(String),
}

/// A position register's representation.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Repr {
    /// Cartesian, with its `Config` text.
    Cartesian(String),
    /// Joint.
    Joint,
    /// Not the file's to say: why.
    Run(String),
}

/// A position register the program sets: its representation, its nine elements, the units of
/// its extended axes as the backup gives them.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Reg {
    pub repr: Repr,
    pub elements: [Num; 9],
    pub units: Vec<&'static str>,
}

/// An offset condition in force (`OFFSET CONDITION PR[i]`, `,UFRAME[j]`).
#[derive(Debug, Clone, PartialEq, Default)]
pub(super) enum Condition {
    /// None set by the program: the controller's.
    #[default]
    None,
    /// Register `register`, in frame `frame` where the condition names one, set on `line`.
    Set {
        register: u32,
        frame: Option<u32>,
        line: u64,
    },
    /// Paths disagree, or the register is chosen at run time: why.
    Run(String),
}

/// What the program has given its registers before an instruction.
#[derive(Debug, Clone, PartialEq, Default)]
pub(super) struct State {
    /// The position registers the program sets, by number.
    pub pr: BTreeMap<u32, Reg>,
    /// The numeric registers known, by number (a missing one is the run's).
    pub r: BTreeMap<u32, Num>,
    /// `OFFSET CONDITION` and `TOOL_OFFSET CONDITION` in force.
    pub conditions: [Condition; 2],
}

/// What an instruction assigns.
enum Assign<'a> {
    /// `PR[i]=rhs`.
    Whole(u32, &'a str),
    /// `PR[i,j]=rhs`, `j` from 1.
    Element(u32, usize, &'a str),
    /// `R[i]=rhs`.
    Number(u32, &'a str),
    /// `OFFSET CONDITION` (`false`) or `TOOL_OFFSET CONDITION` (`true`): register, frame.
    Condition(bool, Option<u32>, Option<u32>),
}

/// The backup's `POSREG.VA` entries and its name, if given.
type Held<'a> = Option<(&'a str, &'a [Entry])>;

/// The state before each instruction of `instructions` ordered by `graph`, registers not set by
/// the program taken from `held` (the backup's `POSREG.VA`: its name and entries); `inherited`,
/// the registers the programs calling this one set (the run's at its start), and why.
pub(super) fn states(
    instructions: &[(u64, String)],
    graph: &Graph,
    held: Held,
    inherited: &[(u32, String)],
) -> Vec<Option<State>> {
    let uppers: Vec<String> = (instructions.iter())
        .map(|(_, t)| english(&t.trim().to_ascii_uppercase()))
        .collect();
    let mut start = start(instructions, &uppers, held);
    for (n, why) in inherited {
        let reg = start.pr.entry(*n).or_insert_with(|| backup(*n, held));
        reg.elements = std::array::from_fn(|_| Num::Run(why.clone()));
    }
    let step = |k: usize, s: &State| {
        let mut s = s.clone();
        step(&instructions[k], &uppers[k], &mut s, held);
        s
    };
    let join = |a: &mut State, b: &State, k: usize| join(a, b, instructions[k].0);
    graph.states(start, step, join)
}

/// The state at the program's start: every register it sets, as the backup holds it, with the
/// elements it sets the run's.
fn start(instructions: &[(u64, String)], uppers: &[String], held: Held) -> State {
    let mut s = State::default();
    for ((line, t), upper) in instructions.iter().zip(uppers) {
        let why = |what: String| {
            Num::Run(format!("the position register is set on line {line} as the program runs ({}), and not on every path from the program's start before the motion ({what}): a run starts with what the run before left; set it on every path before the motion, or move to a P[] position", stiffid_core::common::limits::short(t.trim())))
        };
        let (n, element) = match assign(upper) {
            Some(Assign::Whole(n, _)) => (n, None),
            Some(Assign::Element(n, e, _)) => (n, Some(e)),
            _ => match assigned(upper) {
                Some(Some(n)) => (n, None),
                _ => continue,
            },
        };
        let reg = s.pr.entry(n).or_insert_with(|| backup(n, held));
        match element.filter(|e| (1..=9).contains(e)) {
            Some(e) => reg.elements[e - 1] = why(format!("PR[{n},{e}]")),
            None => reg
                .elements
                .iter_mut()
                .for_each(|h| *h = why(format!("PR[{n}]"))),
        }
    }
    s
}

/// Register `n` as the backup's entries `held` (of file `file`) give it.
fn backup(n: u32, held: Held) -> Reg {
    let none = |why: String| Reg {
        repr: Repr::Run(why.clone()),
        elements: std::array::from_fn(|_| Num::Run(why.clone())),
        units: Vec::new(),
    };
    let Some((file, held)) = held else {
        return none(format!("PR[{n}] holds the value the controller gives it: give the controller's backup with its {}", FILE));
    };
    let Some(entry) = held.iter().find(|e| e.group == 1 && e.number == n) else {
        return none(format!("{file} holds no PR[{n}] of motion group 1"));
    };
    let (repr, six) = match &entry.value {
        Ok(Some(Value::Cartesian(v, config))) => (Repr::Cartesian(config.clone()), v),
        Ok(Some(Value::Joint(v))) => (Repr::Joint, v),
        Ok(None) => {
            return none(format!(
                "{file} line {} gives PR[{n}] no value (Uninitialized)",
                entry.line
            ))
        }
        Err((l, why)) => return none(format!("{file} line {l}: {why}")),
    };
    let elements =
        std::array::from_fn(
            |i| match (six.get(i), entry.extended.get(i.wrapping_sub(6))) {
                (Some(v), _) => Num::Known(*v, 0),
                (None, Some((v, _))) => Num::Known(*v, 0),
                _ => Num::Run(format!(
                    "{file} line {} gives PR[{n}] no element {}",
                    entry.line,
                    i + 1
                )),
            },
        );
    Reg {
        repr,
        elements,
        units: entry.extended.iter().map(|(_, u)| *u).collect(),
    }
}

/// The assignment instruction `upper` (upper case, English) makes, if one stiffid follows.
fn assign(upper: &str) -> Option<Assign<'_>> {
    for (word, tool) in [("OFFSET CONDITION", false), ("TOOL_OFFSET CONDITION", true)] {
        if let Some(rest) = upper.strip_prefix(word) {
            let (register, frame) = rest.split_once(',').unwrap_or((rest, ""));
            let number = |s: &str, w: &str| {
                let inside = s.trim().strip_prefix(w)?.strip_suffix(']')?;
                index(inside).filter(|(_, e)| e.is_none()).map(|(n, _)| n)
            };
            let frame_word = if tool { "UTOOL[" } else { "UFRAME[" };
            let frame = (!frame.trim().is_empty()).then(|| number(frame, frame_word));
            return match frame {
                Some(None) => Some(Assign::Condition(tool, None, Some(u32::MAX))),
                f => Some(Assign::Condition(
                    tool,
                    number(register, "PR["),
                    f.flatten(),
                )),
            };
        }
    }
    let (lhs, rhs) = upper.split_once('=')?;
    let inside = lhs.trim().strip_suffix(']')?;
    if let Some(inside) = inside.strip_prefix("PR[") {
        return match index(inside)? {
            (n, None) => Some(Assign::Whole(n, rhs)),
            (n, Some(e)) => Some(Assign::Element(n, e, rhs)),
        };
    }
    let (n, e) = index(inside.strip_prefix("R[")?)?;
    e.is_none().then_some(Assign::Number(n, rhs))
}

/// The register number and element of the inside of `PR[..]` or `R[..]`, `5`, `5:name`,
/// `GP1:5`, `5,3`, `GP1:5,3:name`; `None` where taken from a register or of another group.
fn index(inside: &str) -> Option<(u32, Option<usize>)> {
    let inside = inside.trim();
    let inside = match inside.strip_prefix("GP1:") {
        Some(r) => r,
        None if inside.starts_with("GP") => return None,
        None => inside,
    };
    let digits = inside
        .find(|c: char| !c.is_ascii_digit())
        .unwrap_or(inside.len());
    let n = inside[..digits].parse().ok()?;
    let rest = inside[digits..].trim_start();
    let Some(e) = rest.strip_prefix(',') else {
        return (rest.is_empty() || rest.starts_with(':')).then_some((n, None));
    };
    let e = e.trim_start();
    let d = e.find(|c: char| !c.is_ascii_digit()).unwrap_or(e.len());
    Some((n, Some(e[..d].parse().ok()?)))
}

/// `s` after the instruction `(line, as written)` runs; `upper` is its text in upper case, English.
fn step((line, written): &(u64, String), upper: &str, s: &mut State, held: Held) {
    let line = *line;
    let text = stiffid_core::common::limits::short(written.trim());
    let run = |_: &str| {
        Num::Run(format!("the position register is set on line {line} as the program runs ({text}): its value is the run's, not the file's; move to a P[] position"))
    };
    if super::calls::called(upper).is_some() || upper.starts_with("RUN ") {
        s.r.clear();
    }
    if let Some(rest) = upper.strip_prefix("FOR ") {
        let inside = rest
            .trim_start()
            .strip_prefix("R[")
            .and_then(|r| r.split_once(']'));
        if let Some((n, _)) = inside.and_then(|(i, _)| index(i)) {
            s.r.remove(&n);
        }
        return;
    }
    match assign(upper) {
        Some(Assign::Number(n, rhs)) => {
            let v = evaluate(rhs, s).map_or_else(
                |e| Num::Run(format!("R[{n}] is set on line {line} from {e}")),
                |v| Num::Known(v, line),
            );
            s.r.insert(n, v);
        }
        Some(Assign::Element(n, e, rhs)) => {
            let v = evaluate(rhs, s).map_or_else(|why| Num::Run(format!("the position register is set on line {line} as the program runs ({text}) from a value the run gives ({why}); move to a P[] position")), |v| Num::Known(v, line));
            if let (Some(reg), true) = (s.pr.get_mut(&n), (1..=9).contains(&e)) {
                reg.elements[e - 1] = v;
            }
        }
        Some(Assign::Whole(n, rhs)) => {
            let value = whole(rhs, s, held).map(|value| Reg {
                elements: value.elements.map(|h| match h {
                    Num::Known(v, _) => Num::Known(v, line),
                    Num::Run(why) => Num::Run(format!("the position register is set on line {line} as the program runs ({text}) from a value not the file's ({why})")),
                }),
                ..value
            });
            let value = value.unwrap_or_else(|| Reg {
                repr: Repr::Run(format!("PR[{n}] is set on line {line} as the program runs")),
                elements: std::array::from_fn(|_| run(&format!("PR[{n}]"))),
                units: Vec::new(),
            });
            s.pr.insert(n, value);
        }
        Some(Assign::Condition(tool, register, frame)) => {
            s.conditions[usize::from(tool)] = match (register, frame) {
                (Some(register), f) if f != Some(u32::MAX) => Condition::Set { register, frame: f, line },
                _ => Condition::Run(format!("the offset condition on line {line} names a register or frame chosen as the program runs")),
            };
        }
        None => {
            if let Some(Some(n)) = assigned(upper)
                && let Some(reg) = s.pr.get_mut(&n)
            {
                reg.elements
                    .iter_mut()
                    .for_each(|h| *h = run(&format!("PR[{n}]")));
                reg.repr = Repr::Run(format!("PR[{n}] is set on line {line} as the program runs"));
            }
        }
    }
}

/// The value of `PR[j]` (+ or - `PR[k]` ..) with `s` in force; `None` where it is not that.
fn whole(rhs: &str, s: &State, held: Held) -> Option<Reg> {
    let rhs: String = rhs
        .split(';')
        .next()?
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect();
    let mut out: Option<Reg> = None;
    let mut rest = rhs.as_str();
    let mut sign = 1.0;
    loop {
        let inside = rest.strip_prefix("PR[")?;
        let close = inside.find(']')?;
        let (n, e) = index(&inside[..close])?;
        if e.is_some() {
            return None;
        }
        let term = s.pr.get(&n).cloned().unwrap_or_else(|| backup(n, held));
        out = Some(match out {
            None => term,
            Some(mut acc) => {
                if acc.repr != term.repr {
                    acc.repr = Repr::Run(format!("'{rhs}' mixes representations"));
                }
                for (a, b) in acc.elements.iter_mut().zip(term.elements) {
                    *a = match (&*a, &b) {
                        (Num::Known(x, l), Num::Known(y, _)) => Num::Known(x + sign * y, *l),
                        (Num::Run(w), _) | (_, Num::Run(w)) => Num::Run(w.clone()),
                    };
                }
                acc
            }
        });
        rest = &inside[close + 1..];
        sign = match rest.chars().next() {
            None => return out,
            Some('+') => 1.0,
            Some('-') => -1.0,
            Some(_) => return None,
        };
        rest = &rest[1..];
    }
}

/// The value of the arithmetic `rhs` with the registers `s` holds.
fn evaluate(rhs: &str, s: &State) -> Result<f64, String> {
    let rhs = rhs.split(';').next().unwrap_or("");
    let mut text = String::new();
    let mut values: Vec<Result<f64, String>> = Vec::new();
    let mut rest = rhs;
    while let Some(open) = rest.find('[') {
        let name_start = rest[..open]
            .rfind(|c: char| !c.is_ascii_alphanumeric() && c != '_')
            .map_or(0, |i| i + 1);
        let close = rest[open..]
            .find(']')
            .map(|c| open + c)
            .ok_or("an unclosed '['")?;
        let (name, inside) = (&rest[name_start..open], &rest[open + 1..close]);
        let value = match (name, index(inside)) {
            ("R", Some((n, None))) => match s.r.get(&n) {
                Some(Num::Known(v, _)) => Ok(*v),
                Some(Num::Run(why)) => Err(why.clone()),
                None => Err(format!("R[{n}] is not set by the program on every path before it: its value is the controller's or the run's")),
            },
            ("PR", Some((n, Some(e)))) => match s.pr.get(&n).and_then(|r| r.elements.get(e.wrapping_sub(1))) {
                Some(Num::Known(v, _)) => Ok(*v),
                Some(Num::Run(why)) => Err(why.clone()),
                None => Err(format!("PR[{n},{e}] is the backup's")),
            },
            _ => return Err(format!("'{}' is not arithmetic of numbers and registers", rhs.trim())),
        };
        text.push_str(&rest[..name_start]);
        text.push_str(&format!(" x{} ", values.len()));
        values.push(value);
        rest = &rest[close + 1..];
    }
    text.push_str(rest);
    let lookup = |name: &str| {
        let i: usize = name.strip_prefix('x')?.parse().ok()?;
        values.get(i).cloned()
    };
    crate::program::arithmetic::value(&text, &lookup)
}

/// `a` joined with `b` where paths meet on `line`; whether `a` changed.
fn join(a: &mut State, b: &State, line: u64) -> bool {
    let mut changed = false;
    for (n, x) in a.pr.iter_mut() {
        let Some(y) = b.pr.get(n) else { continue };
        if x.repr != y.repr && !matches!(x.repr, Repr::Run(_)) {
            x.repr = Repr::Run(format!(
                "PR[{n}]'s representation depends on the path taken to line {line}"
            ));
            changed = true;
        }
        for (e, (p, q)) in x.elements.iter_mut().zip(&y.elements).enumerate() {
            changed |= join_held(p, q, &format!("PR[{n},{}]", e + 1), line);
        }
    }
    let before = a.r.len();
    a.r.retain(|n, _| b.r.contains_key(n));
    changed |= a.r.len() != before;
    for (n, x) in a.r.iter_mut() {
        changed |= join_held(x, &b.r[n], &format!("R[{n}]"), line);
    }
    for (x, y) in a.conditions.iter_mut().zip(&b.conditions) {
        if x != y && !matches!(x, Condition::Run(_)) {
            *x = Condition::Run(format!(
                "the offset condition in force depends on the path taken to line {line}"
            ));
            changed = true;
        }
    }
    changed
}

/// `a` joined with `b` (of `what`) where paths meet on `line`; whether `a` changed.
fn join_held(a: &mut Num, b: &Num, what: &str, line: u64) -> bool {
    match (&*a, b) {
        (Num::Run(_), _) => false,
        (Num::Known(x, _), Num::Known(y, _)) if x == y => false,
        (_, Num::Run(why)) => {
            *a = Num::Run(why.clone());
            true
        }
        (Num::Known(x, l), Num::Known(y, m)) => {
            *a = Num::Run(format!("{what} depends on the path taken to line {line}: one path leaves {x} ({}), another {y} ({})", source(*l), source(*m)));
            true
        }
    }
}

/// Where a known value comes from: its line, or the backup.
pub(super) fn source(line: u64) -> String {
    match line {
        0 => "the backup's".into(),
        l => format!("line {l}"),
    }
}

/// Register `n` as `state` holds it, as the backup's entry would give it (its number, its value,
/// its extended axes, where the values come from), where the program sets it; `None` where it
/// does not (the backup's); why not, where its value is the run's.
pub(super) fn register(state: &State, n: u32) -> Option<Result<(Entry, String), String>> {
    let reg = state.pr.get(&n)?;
    Some(value_of(reg, n))
}

/// The register `reg` (number `n`) as a backup's entry, or why its value is the run's.
fn value_of(reg: &Reg, n: u32) -> Result<(Entry, String), String> {
    let known = |i: usize| {
        match reg.elements.get(i) {
        Some(Num::Known(v, l)) => Ok((*v, *l)),
        Some(Num::Run(why)) => Err(why.clone()),
        None => Err(format!("PR[{n}] has more than 3 extended axes in the backup; a position register holds up to 3")),
    }
    };
    let six: Vec<(f64, u64)> = (0..6).map(known).collect::<Result<_, _>>()?;
    let mut lines: Vec<u64> = six.iter().map(|(_, l)| *l).collect();
    let mut extended = Vec::with_capacity(reg.units.len());
    for (i, unit) in reg.units.iter().enumerate() {
        let (v, l) = known(6 + i)?;
        extended.push((v, *unit));
        lines.push(l);
    }
    for i in 6 + reg.units.len()..9 {
        if let Num::Known(_, l @ 1..) = reg.elements[i] {
            return Err(format!("PR[{n},{}] is set on line {l}, an extended axis the backup's {} does not give the register", i + 1, FILE));
        }
    }
    let six: [f64; 6] = std::array::from_fn(|i| six[i].0);
    let value = match &reg.repr {
        Repr::Cartesian(config) => Value::Cartesian(six, config.clone()),
        Repr::Joint => Value::Joint(six),
        Repr::Run(why) => {
            return Err(format!(
                "its representation (Cartesian or joint) is not the file's to say: {why}"
            ))
        }
    };
    lines.sort_unstable();
    lines.dedup();
    let own: Vec<String> = lines
        .iter()
        .filter(|l| **l > 0)
        .map(u64::to_string)
        .collect();
    let source = match (own.is_empty(), lines.first() == Some(&0)) {
        (true, _) => "the backup".to_string(),
        (false, false) => format!("the program's line {}", own.join(", ")),
        (false, true) => format!("the program's line {} over the backup", own.join(", ")),
    };
    let entry = Entry {
        group: 1,
        number: n,
        line: 0,
        value: Ok(Some(value)),
        extended,
    };
    Ok((entry, source))
}

/// Whether instruction `upper` (upper case, English) sets a position register: `Some(Some(n))`
/// register `n` (or one of its elements), `Some(None)` one chosen at run time (`PR[R[1]]=`);
/// `None` where it sets none. An assignment is a `PR[..]` followed by `=` outside a condition
/// (`IF`, `WAIT`, `SELECT` and its cases compare): a statement `PR[1]=LPOS`, a motion's skip
/// option `Skip,LBL[2],PR[6]=LPOS`.
pub(super) fn assigned(upper: &str) -> Option<Option<u32>> {
    let compares = ["IF", "WAIT", "SELECT", "=", "ELSE"];
    if compares.iter().any(|w| upper.starts_with(w)) {
        return None;
    }
    let mut from = 0;
    while let Some(i) = upper[from..].find("PR[").map(|i| from + i) {
        from = i + 3;
        if upper[..i].ends_with(|c: char| c.is_ascii_alphanumeric() || c == '_' || c == '$') {
            continue;
        }
        let Some(close) = closing(&upper[i + 3..]).map(|c| i + 3 + c) else {
            continue;
        };
        if !upper[close + 1..].trim_start().starts_with('=') {
            continue;
        }
        let inside = upper[i + 3..close].trim();
        let inside = match inside.strip_prefix("GP") {
            Some(r) => r.split_once(':').map_or(r, |(_, r)| r),
            None => inside,
        };
        let number = inside.split([':', ',']).next().map(str::trim);
        return Some(number.and_then(|d| d.parse().ok()));
    }
    None
}

/// The byte of the `]` closing the bracket opened before `s`, brackets inside counted.
fn closing(s: &str) -> Option<usize> {
    let mut depth = 0usize;
    for (i, c) in s.char_indices() {
        match c {
            '[' => depth += 1,
            ']' if depth == 0 => return Some(i),
            ']' => depth -= 1,
            _ => {}
        }
    }
    None
}
