//! Points the program assigns as it runs, computed where the file says their value: `XP2 = XP1`
//! (a copy), `XP2 = XP1 : {X .., Y .., Z .., A .., B .., C ..}` (the geometric operator, each
//! operand a point or a literal frame with all six members, their product left to right),
//! `XP2 = {X .., ..}` (a literal aggregate: the members it gives, the others kept) and
//! `XP2.Z = XP2.Z + 10` (a member set to arithmetic of numbers and members of points whose value
//! is known). KSS 8.x SI manual: "Geometric operator" (the result takes the type of the right
//! operand: a `FRAME` on the right sets `X`..`C` only, a `POS`/`E6POS` its `S`, `T` too),
//! "Data lists" (a point of a data list keeps its last value between runs).
//!
//! A point the module assigns anywhere holds, where the program starts, the value its last run
//! left (the data list keeps it): its value is known only after an assignment on every path that
//! reaches the motion ([`crate::program::paths`]); a loop that assigns it makes it unknown at the
//! loop's start (its next run sees the body's value), a routine of the file that assigns it makes
//! it unknown after the call. A motion to a computed point moves to a declaration stiffid writes
//! for it ([`target`]): compensated, a new point beside the data list's (`XP2_S15`, the line of the
//! assignment), which the motion names; the assignment stays as it is.

use super::declare::{aggregate_at, words, Declarations};
use super::frames::split_top;
use crate::program::points::holds_word;
use crate::program::points::Foreign;
use crate::program::JointTarget;
use nalgebra::{Isometry3, Translation3};
use std::collections::{BTreeMap, HashMap};
use stiffid_core::common::limits::short;

/// A member's value: a number, or its text (`S 'B010'`).
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Item {
    /// A number.
    Num(f64),
    /// Any other text, as written.
    Text(String),
}

/// A point's type word (`E6POS`, upper case) and members in order (upper-case names).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Members {
    /// `E6POS`, `POS`, `FRAME`, `E6AXIS` or `AXIS`.
    pub kind: String,
    /// The members.
    pub items: Vec<(String, Item)>,
}

/// What the program's assignments leave in a point.
#[derive(Debug, Clone)]
pub(super) enum Value {
    /// Computed from the assignment on this line: its members and the target a motion to it
    /// takes.
    Known(u64, Members, Box<JointTarget>),
    /// Assigned on this line somewhere in the module, not yet on the path read: the last run's.
    Assigned(u64),
    /// Only the run gives it: why, the words after the point's name (`is assigned on ..`).
    Unknown(String),
    /// A number ([`super::numbers`]) computed from the assignment on this line: its value and
    /// whether it is an `INT`.
    Number(u64, f64, bool),
}

impl Value {
    /// Whether two values are one (the lines aside for computed ones).
    pub(super) fn same(&self, other: &Value) -> bool {
        match (self, other) {
            (Value::Known(_, a, _), Value::Known(_, b, _)) => a == b,
            (Value::Assigned(a), Value::Assigned(b)) => a == b,
            (Value::Unknown(a), Value::Unknown(b)) => a == b,
            (Value::Number(_, a, _), Value::Number(_, b, _)) => a == b,
            _ => false,
        }
    }

    /// The value on one path, in words, for a refusal.
    fn describe(&self) -> String {
        match self {
            Value::Known(l, ..) | Value::Number(l, ..) => format!("the value line {l} gives"),
            Value::Assigned(_) => "the value a previous run left".into(),
            Value::Unknown(_) => "a value only the run gives".into(),
        }
    }
}

/// The points assigned so far, by upper-case name (one absent is as declared).
pub(super) type Values = BTreeMap<String, Value>;

/// `a` joined with `b` after the construct `(word, line)`: a point the paths leave differently
/// is unknown, naming the construct.
pub(super) fn join(a: &mut Values, b: &Values, (word, line): (&str, u64)) {
    let keys: Vec<String> = a.keys().chain(b.keys()).cloned().collect();
    for k in keys {
        let joined = match (a.get(&k), b.get(&k)) {
            (Some(x), Some(y)) if x.same(y) => continue,
            (Some(Value::Unknown(w)), _) | (_, Some(Value::Unknown(w))) => {
                Value::Unknown(w.clone())
            }
            (x, y) => {
                let say =
                    |v: Option<&Value>| v.map_or("the declared value".into(), Value::describe);
                Value::Unknown(format!("holds a value that depends on the path taken through {word} (line {line}): one path leaves {}, another {}; assign it alike on every path, or before {word}", say(x), say(y)))
            }
        };
        a.insert(k, joined);
    }
}

/// What the reader of a module needs to compute assignments: its declarations, where a computed
/// point's declaration goes, and the words its files hold (a new name holds none of them).
pub(super) struct Writer<'a> {
    /// The declarations.
    pub declared: &'a Declarations,
    /// The byte of the program's text where a new declaration goes.
    pub insert: usize,
    /// The `.src` and its `.dat`.
    pub texts: [&'a str; 2],
    /// The line end of the file the declarations go into.
    pub eol: &'static str,
    /// The names given so far (upper case), and a count that keeps each declaration's bytes apart.
    pub taken: Vec<String>,
    /// The declarations written so far, by the line that computed them and their values: a
    /// statement read again (a loop unrolled) with the same values names the same point.
    pub computed: HashMap<(u64, String), JointTarget>,
}

/// The points the module `text` assigns (`assigned`: each with the first line that does), made
/// the last run's where the program starts.
pub(super) fn initial(assigned: &HashMap<String, u64>) -> Values {
    (assigned.iter())
        .map(|(k, l)| (k.clone(), Value::Assigned(*l)))
        .collect()
}

/// Per routine after the first (by upper-case name) and per loop (by its line): the points of
/// `tracked` its statements assign, each with the line.
pub(super) type Setters = (
    HashMap<String, Vec<(String, u64)>>,
    HashMap<u64, Vec<(String, u64)>>,
);

/// The [`Setters`] of the module `text`.
pub(super) fn setters(text: &str, tracked: &Values) -> Setters {
    let (mut routines, mut loops) = (HashMap::new(), HashMap::new());
    let mut open: Vec<u64> = Vec::new();
    let mut routine: Option<String> = None;
    for (line, _, l) in crate::program::lines(text) {
        let code = l.split(';').next().unwrap_or("");
        let w = words(code);
        if let Some(name) = super::calls::routine_name(&w) {
            routine = Some(name);
            open.clear();
            continue;
        }
        match w.first().map(String::as_str) {
            Some("FOR" | "WHILE" | "REPEAT" | "LOOP") => open.push(line),
            Some("ENDFOR" | "ENDWHILE" | "UNTIL" | "ENDLOOP") => _ = open.pop(),
            _ => {}
        }
        let Some((name, _)) = target_of(code).filter(|(n, _)| tracked.contains_key(n)) else {
            continue;
        };
        for l in &open {
            let list: &mut Vec<(String, u64)> = loops.entry(*l).or_default();
            list.push((name.clone(), line));
        }
        if let Some(r) = &routine {
            let list: &mut Vec<(String, u64)> = routines.entry(r.clone()).or_default();
            list.push((name, line));
        }
    }
    (routines, loops)
}

/// The point a statement assigns (`NAME = ..` or `NAME.M = ..`, not an array's element): its
/// upper-case name and member, and the byte after the `=`.
fn target_of(code: &str) -> Option<(String, (Option<String>, usize))> {
    let eq = code.find('=')?;
    let after = code[eq + 1..].chars().next();
    if matches!(after, Some('=')) || code[..eq].ends_with(['<', '>', '=']) {
        return None;
    }
    let lhs = code[..eq].trim();
    let word = |s: &str| {
        !s.is_empty()
            && s.chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '$')
            && !s.starts_with(|c: char| c.is_ascii_digit())
    };
    let (name, member) = match lhs.split_once('.') {
        Some((n, m)) => (n.trim(), Some(m.trim().to_ascii_uppercase())),
        None => (lhs, None),
    };
    (word(name) && member.as_deref().is_none_or(word))
        .then(|| (name.to_ascii_uppercase(), (member, eq + 1)))
}

impl Writer<'_> {
    /// The statement `code` on `line` of routine `routine` when it assigns a point `values`
    /// tracks: the point's upper-case name and the value it holds after.
    pub(super) fn assignment(
        &mut self,
        line: u64,
        code: &str,
        routine: usize,
        values: &Values,
    ) -> Option<(String, Value)> {
        let (name, (member, from)) = target_of(code).filter(|(n, _)| values.contains_key(n))?;
        let rhs = code[from..].trim();
        if self.declared.num_types.contains_key(&name) && !self.declared.raw.contains_key(&name) {
            let value = match member {
                None => self.number_assigned(line, &name, rhs, routine, values),
                Some(m) => Value::Unknown(format!(
                    "is assigned on line {line} a member {m}, which a number has not"
                )),
            };
            return Some((name, value));
        }
        let computed = match &member {
            None => self.whole(&name, rhs, routine, values),
            Some(m) => self.member(&name, m, rhs, routine, values),
        };
        let value = computed
            .and_then(|m| self.target(line, &name, m))
            .map_or_else(
                |why| Value::Unknown(format!("is assigned on line {line} {why}, so its value at the motion is the controller's, not the file's: give the motion its own declared point")),
                |(m, t)| Value::Known(line, m, Box::new(t)),
            );
        Some((name, value))
    }

    /// The members of the point `name` where it is read in `routine`: computed, or declared
    /// with a value in the module's data (not a routine's own declaration of that name).
    pub(super) fn current(
        &self,
        name: &str,
        routine: usize,
        values: &Values,
    ) -> Result<Members, String> {
        match values.get(name) {
            Some(Value::Known(_, m, _)) => return Ok(m.clone()),
            Some(Value::Assigned(l)) => return Err(format!("from {name}, which holds the value a previous run left (it is assigned on line {l})")),
            Some(Value::Unknown(w)) => return Err(format!("from {name}, which {w}")),
            Some(Value::Number(..)) => return Err(format!("from {name}, a number, not a point")),
            None => {}
        }
        let d = self.declared;
        let own = d.of(routine).get(name).map(|v| &v.0);
        match (d.raw.get(name), own == d.points.get(name).map(|v| &v.0)) {
            (Some((kind, aggregate)), true) => members(kind, aggregate)
                .ok_or_else(|| format!("from {name}, whose declared value stiffid does not read")),
            _ => Err(format!(
                "from '{}', which is not a point declared with a value",
                short(name)
            )),
        }
    }

    /// `NAME = rhs`: a point, a literal aggregate, or operands linked by `:`.
    fn whole(
        &self,
        name: &str,
        rhs: &str,
        routine: usize,
        values: &Values,
    ) -> Result<Members, String> {
        let lhs = self.current(name, routine, values).ok();
        let kind = self.kind(name).ok_or("to a point of no known type")?;
        let operands = split_top(rhs, ':');
        let operand = |o: &str| -> Result<Members, String> {
            let o = o.trim();
            match o.starts_with('{') {
                true => members("", o).ok_or_else(|| {
                    format!(
                        "from the aggregate '{}', which stiffid does not read",
                        short(o)
                    )
                }),
                false => self.current(&o.to_ascii_uppercase(), routine, values),
            }
        };
        if operands.len() == 1 {
            let from = operand(&operands[0])?;
            let axes = |k: &str| k.ends_with("AXIS");
            if !from.kind.is_empty() && axes(&from.kind) != axes(&kind) {
                return Err(format!(
                    "from '{}', a {}, to a point of type {kind}",
                    short(rhs.trim()),
                    from.kind
                ));
            }
            return Ok(merged(
                &kind,
                lhs.as_ref(),
                &from,
                rhs.trim_start().starts_with('{'),
            ));
        }
        let mut frame = Isometry3::identity();
        let mut last = None;
        for o in &operands {
            let m = operand(o)?;
            frame *= pose(&m).ok_or_else(|| format!("with the geometric operator, whose operand '{}' is not a Cartesian value with X, Y, Z, A, B and C", short(o.trim())))?;
            last = Some(m);
        }
        let last = last.ok_or("from nothing")?;
        // The result takes the right operand's type: a point's S, T and external axes with it.
        let right_point = last.items.iter().any(|(k, _)| k == "S" || k == "T");
        let mut out = match (right_point, lhs) {
            (true, _) => merged(&kind, None, &last, false),
            (false, Some(l)) => l,
            (false, None) if kind == "FRAME" => Members { kind: kind.clone(), items: Vec::new() },
            (false, None) => return Err(format!("with the geometric operator to a FRAME, which keeps {name}'s S and T, and those are the run's")),
        };
        set_pose(&mut out, &frame);
        Ok(out)
    }

    /// `NAME.M = rhs`: arithmetic of numbers and members of points of known value.
    fn member(
        &self,
        name: &str,
        m: &str,
        rhs: &str,
        routine: usize,
        values: &Values,
    ) -> Result<Members, String> {
        let mut out = self.current(name, routine, values)?;
        let mut text = String::new();
        let mut rest = rhs;
        while let Some(dot) = rest.find('.') {
            let before = &rest[..dot];
            let start = before
                .rfind(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == '$'))
                .map_or(0, |i| i + 1);
            let point = &before[start..];
            let after = &rest[dot + 1..];
            let len = after
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .unwrap_or(after.len());
            if point.is_empty() || point.starts_with(|c: char| c.is_ascii_digit()) {
                text.push_str(&rest[..=dot]);
                rest = after;
                continue;
            }
            let of = self.current(&point.to_ascii_uppercase(), routine, values)?;
            let key = after[..len].to_ascii_uppercase();
            let v = match of.items.iter().find(|(k, _)| *k == key) {
                Some((_, Item::Num(v))) => *v,
                _ => {
                    return Err(format!(
                        "from {point}.{key}, which stiffid does not read as a number"
                    ))
                }
            };
            text.push_str(&before[..start]);
            // A member is a REAL (`5.0`, never the INT `5`: KRL divides INTs as integers).
            text.push_str(&format!("({v:?})"));
            rest = &after[len..];
        }
        text.push_str(rest);
        let v = (self.evaluate(&text, routine, values))
            .map_err(|w| format!("from '{}' ({w})", short(rhs.trim())))?
            .0;
        let allowed = member_of(&out.kind, m);
        match out.items.iter_mut().find(|(k, _)| k == m) {
            Some((_, item)) => *item = Item::Num(v),
            None if allowed => out.items.push((m.to_string(), Item::Num(v))),
            None => {
                return Err(format!(
                    "to {name}.{m}, not a member of its type {}",
                    out.kind
                ))
            }
        }
        Ok(out)
    }

    /// The type word of the point `name` as declared in the module's data.
    fn kind(&self, name: &str) -> Option<String> {
        self.declared.raw.get(name).map(|(k, _)| k.clone())
    }

    /// The target a motion to the point `name` holding `m` (computed on `line`) takes: a new
    /// declaration ([`Foreign`]) of a fresh name, written where compensating moves it.
    pub(super) fn target(
        &mut self,
        line: u64,
        name: &str,
        m: Members,
    ) -> Result<(Members, JointTarget), String> {
        let items: Vec<String> = (m.items.iter())
            .map(|(k, v)| match v {
                Item::Num(x) => format!("{k} {x:.9}"),
                Item::Text(t) => format!("{k} {t}"),
            })
            .collect();
        let key = (line, format!("{} {}", m.kind, items.join(",")));
        if let Some(t) = self.computed.get(&key) {
            return Ok((m, t.clone()));
        }
        let fresh = self
            .fresh(name, line)
            .ok_or("and no name for its compensated copy is free")?;
        let head = format!("DECL {} {fresh}=", m.kind);
        let text = format!("{head}{{{}}}{}", items.join(","), self.eol);
        // Each declaration's bytes apart from every text's (called modules shift them on).
        let at = (1usize << 48) + (self.taken.len() << 32);
        let t = aggregate_at(line, at, &text, head.len()).map_err(|e| match e {
            stiffid_core::Error::Program { message, .. } => {
                format!("to a value stiffid does not take ({message})")
            }
            other => other.to_string(),
        })?;
        let name_at = head.len() - 1 - fresh.len()..head.len() - 1;
        let t = t.declared_elsewhere(
            Foreign {
                text,
                at,
                computed: true,
            },
            name_at,
            self.insert,
        );
        self.taken.push(fresh.to_ascii_uppercase());
        self.computed.insert(key, t.clone());
        Ok((m, t))
    }

    /// A name for the copy of `name` assigned on `line` that no file holds as a word and no
    /// other copy took: `NAME_S15`, shortened to KRL's 24 characters.
    fn fresh(&self, name: &str, line: u64) -> Option<String> {
        (1..100).find_map(|k| {
            let suffix = match k {
                1 => format!("_S{line}"),
                _ => format!("_S{line}_{k}"),
            };
            let keep = 24usize.checked_sub(suffix.len())?.min(name.len());
            let n = format!("{}{suffix}", &name[..keep]);
            let free = !self.taken.contains(&n) && self.texts.iter().all(|t| !holds_word(t, &n));
            free.then_some(n)
        })
    }
}

/// `from` assigned to a point of type `kind` whose members were `lhs`: a point's members as its
/// type holds them, a literal aggregate's over the point's (the ones it leaves out kept).
pub(super) fn merged(kind: &str, lhs: Option<&Members>, from: &Members, literal: bool) -> Members {
    let mut out = match (literal, lhs) {
        (true, Some(l)) => l.clone(),
        _ => Members {
            kind: kind.to_string(),
            items: Vec::new(),
        },
    };
    out.kind = kind.to_string();
    for (k, v) in &from.items {
        if !member_of(kind, k) {
            continue;
        }
        match out.items.iter_mut().find(|(n, _)| n == k) {
            Some((_, item)) => *item = v.clone(),
            None => out.items.push((k.clone(), v.clone())),
        }
    }
    out
}

/// Whether `member` (upper case) is one of the type `kind`'s.
fn member_of(kind: &str, member: &str) -> bool {
    let pose = ["X", "Y", "Z", "A", "B", "C"].contains(&member);
    let turn = member == "S" || member == "T";
    let numbered = |letter: u8| matches!(member.as_bytes(), [l, b'1'..=b'6'] if *l == letter);
    let (axis, external) = (numbered(b'A'), numbered(b'E'));
    match kind {
        "FRAME" => pose,
        "POS" => pose || turn,
        "E6POS" => pose || turn || external,
        "AXIS" => axis,
        "E6AXIS" => axis || external,
        _ => false,
    }
}

/// The members of the aggregate `{..}` (an optional type `{E6POS: ..}` read over `kind`).
pub(super) fn members(kind: &str, aggregate: &str) -> Option<Members> {
    let inner = aggregate.trim().strip_prefix('{')?.split('}').next()?;
    let (kind, inner) = match inner.split_once(':') {
        Some((k, r)) => (k.trim().to_ascii_uppercase(), r),
        None => (kind.to_string(), inner),
    };
    let mut items = Vec::new();
    for item in inner.split(',') {
        let item = item.trim();
        let len = item
            .find(|c: char| !c.is_ascii_alphanumeric())
            .unwrap_or(item.len());
        let (k, v) = (item[..len].to_ascii_uppercase(), item[len..].trim());
        if k.is_empty() || v.is_empty() || items.iter().any(|(n, _)| *n == k) {
            return None;
        }
        let value = match crate::program::number_at(v, 0) {
            Some((x, span)) if span.end == v.len() => Item::Num(x),
            _ if k == "S" || k == "T" => Item::Text(v.to_string()),
            _ => return None,
        };
        items.push((k, value));
    }
    Some(Members { kind, items })
}

/// The frame of members `X`..`C` (mm, deg), m; `None` without all six.
pub(super) fn pose(m: &Members) -> Option<Isometry3<f64>> {
    let get = |k: &str| match m.items.iter().find(|(n, _)| n == k) {
        Some((_, Item::Num(v))) => Some(*v),
        _ => None,
    };
    let v: Vec<f64> = ["X", "Y", "Z", "A", "B", "C"]
        .iter()
        .map(|k| get(k))
        .collect::<Option<_>>()?;
    Some(Isometry3::from_parts(
        Translation3::new(v[0] * 1e-3, v[1] * 1e-3, v[2] * 1e-3),
        super::abc(v[3], v[4], v[5]),
    ))
}

/// `m`'s members `X`..`C` set to the frame `f` (m), in KUKA's A, B, C.
pub(super) fn set_pose(m: &mut Members, f: &Isometry3<f64>) {
    let [a, b, c] = crate::program::generate::zyx_deg(&f.rotation);
    let t = f.translation.vector * 1e3;
    for (k, v) in ["X", "Y", "Z", "A", "B", "C"]
        .iter()
        .zip([t.x, t.y, t.z, a, b, c])
    {
        match m.items.iter_mut().find(|(n, _)| n == k) {
            Some((_, item)) => *item = Item::Num(v),
            None => m.items.push((k.to_string(), Item::Num(v))),
        }
    }
}
