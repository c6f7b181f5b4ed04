//! Robot programs: the joint targets of KUKA KRL, ABB RAPID and FANUC LS programs, read in the
//! order the controller moves to them and written back with everything else byte for byte.
//!
//! - [`krl`]: `PTP`/`LIN` (and `SPTP`/`SLIN`) motions to an aggregate `{A1 .., ..., A6 ..}` or to
//!   a point declared in the same file as `E6AXIS`/`AXIS` (further members such as `E1` are kept
//!   as they are).
//! - [`rapid`]: `MoveAbsJ` (also `\Conc`) to a literal `[[j1,..,j6],[e1,..,e6]]` or to a
//!   `jointtarget` declared in the same module (over one line or several).
//! - [`ls`]: `J`/`L` motions in `/MN` to `P[i]` positions of `/POS` in joint representation
//!   (`J1= .. deg` to `J6`); `INC` after a motion that ends `FINE` is resolved (the increment from
//!   the previous target, written back as the increment between the compensated targets).
//!
//! Only joint targets are read. A Cartesian target (KRL `E6POS`/`POS`/`FRAME`, RAPID
//! `MoveL`/`MoveJ`/`MoveC`, LS positions with `X = .. mm`) is refused naming its line: turning it
//! into axis angles needs the controller's configuration flags (KUKA `S`/`T`, ABB `confdata`,
//! FANUC `CONFIG : 'N U T, ...'`) and its own kinematic conventions to pick the one of up to eight
//! inverse-kinematics solutions the controller would take, and a compensated target would have to
//! be written back with flags the controller agrees with. Joint targets are unambiguous in both
//! directions.
//!
//! Every other motion instruction is refused naming its line and what to do, never skipped: a
//! circular or spline motion (the path between the points is not the compensated one), a relative
//! motion the file cannot resolve exactly, an offset or target held in a register on the
//! controller (LS `Offset,PR[]`, `Tool_Offset`, `PR[]`), a point declared outside the file or
//! assigned at run time, a search or triggered motion (RAPID `SearchL`, `TriggL`, `MoveLDO`),
//! motions in more than one routine, and jumps, loops, branches and calls in a program with
//! motions (the order the controller runs would not be the file's).
//!
//! The targets come in the order of the motion instructions, which is the order the path follows;
//! a declared point moved to twice is one target per visit. [`JointProgram::write`] replaces the
//! six numbers of each target whose value changed (with [`DECIMALS`] decimals) and nothing else;
//! a point visited twice takes one value, so the two visits' compensations must agree.

pub mod generate;
pub mod krl;
pub mod ls;
pub mod rapid;
pub mod rename;

use crate::{Error, Result};
use std::ops::Range;

/// Decimals of a written joint value, deg (1e-9 deg: the compensation's precision; controllers
/// round to their own).
pub const DECIMALS: usize = 9;

/// The most joint targets a program may hold.
pub const MAX_TARGETS: usize = 1_000_000;

/// The robot-program language.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dialect {
    /// KUKA KRL (`.src`, `.dat`).
    Krl,
    /// ABB RAPID (`.mod`, `.modx`, `.prg`).
    Rapid,
    /// FANUC LS (`.ls`), joint representation.
    FanucLs,
}

impl Dialect {
    /// The dialect of a file name's extension (case-insensitive), if it is one of ours.
    pub fn from_extension(extension: &str) -> Option<Self> {
        match extension.to_ascii_lowercase().as_str() {
            "src" | "dat" => Some(Dialect::Krl),
            "mod" | "modx" | "prg" => Some(Dialect::Rapid),
            "ls" => Some(Dialect::FanucLs),
            _ => None,
        }
    }
}

/// One joint target of a program: one motion instruction's destination.
#[derive(Debug, Clone, PartialEq)]
pub struct JointTarget {
    /// The line of its motion instruction, 1-based.
    pub line: u64,
    /// Axis angles q1..q6, deg (an incremental target resolved to its absolute angles).
    pub q_deg: [f64; 6],
    /// Where each of the six numbers sits in the text (bytes): in the motion or in the point's
    /// declaration.
    spans: [Range<usize>; 6],
    /// The line of the six numbers (the declaration's for a named point).
    origin: u64,
    /// The numbers hold the increment from the previous target (LS `INC`).
    incremental: bool,
}

impl JointTarget {
    /// The same point as the target of the motion on `line`; `incremental` as it says.
    pub(crate) fn moved_to(&self, line: u64, incremental: bool) -> Self {
        JointTarget {
            line,
            incremental,
            ..self.clone()
        }
    }
}

/// A robot program and its joint targets.
#[derive(Debug, Clone, PartialEq)]
pub struct JointProgram {
    /// The language.
    pub dialect: Dialect,
    /// The targets, in the order of the motion instructions.
    pub targets: Vec<JointTarget>,
    text: String,
}

/// Parses the joint targets of `text` in `dialect`.
///
/// # Errors
/// [`Error::Program`] naming the line: every motion instruction outside the subset (module docs),
/// a joint target with a missing, repeated or non-numeric axis value, no motion to a joint target
/// at all, or more than [`MAX_TARGETS`].
pub fn parse(text: &str, dialect: Dialect) -> Result<JointProgram> {
    let targets = match dialect {
        Dialect::Krl => krl::targets(text)?,
        Dialect::Rapid => rapid::targets(text)?,
        Dialect::FanucLs => ls::targets(text)?,
    };
    if targets.is_empty() {
        let hint = match dialect {
            Dialect::Krl => "PTP or LIN to {A1 .., A6 ..} or to an E6AXIS declared in the file; a .dat holds declarations only: give the .src",
            Dialect::Rapid => "MoveAbsJ to a jointtarget",
            Dialect::FanucLs => "J or L to a P[i] of /POS in joint representation",
        };
        return Err(at(
            1,
            format!("no motion to a joint target found (expected {hint})"),
        ));
    }
    if targets.len() > MAX_TARGETS {
        return Err(at(
            targets[MAX_TARGETS].line,
            format!("more than {MAX_TARGETS} joint targets"),
        ));
    }
    Ok(JointProgram {
        dialect,
        targets,
        text: text.to_string(),
    })
}

impl JointProgram {
    /// The program with the axis angles of target `i` replaced by `q_deg[i]` (deg) where they
    /// differ from the ones read; every other byte as read.
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`q_deg`) when `q_deg` has another length than the targets or a
    /// value is not finite.
    pub fn write(&self, q_deg: &[[f64; 6]]) -> Result<String> {
        if q_deg.len() != self.targets.len() || q_deg.iter().flatten().any(|v| !v.is_finite()) {
            return Err(Error::InvalidField {
                field: "q_deg".into(),
                message: format!(
                    "expected {} rows of 6 finite axis angles, one per target",
                    self.targets.len()
                ),
            });
        }
        // Each number to write: its span, the target, the value, whether it changed.
        let mut edits: Vec<(Range<usize>, usize, f64, bool)> =
            Vec::with_capacity(6 * self.targets.len());
        for (i, (t, q)) in self.targets.iter().zip(q_deg).enumerate() {
            for k in 0..6 {
                let (value, changed) = match (t.incremental, i.checked_sub(1)) {
                    (true, Some(p)) => (
                        q[k] - q_deg[p][k],
                        q[k] != t.q_deg[k] || q_deg[p][k] != self.targets[p].q_deg[k],
                    ),
                    _ => (q[k], q[k] != t.q_deg[k]),
                };
                edits.push((t.spans[k].clone(), i, value, changed));
            }
        }
        edits.sort_by_key(|e| e.0.start);
        let mut out = String::with_capacity(self.text.len() + self.targets.len() * 24);
        let mut at = 0;
        for (j, (span, i, value, changed)) in edits.iter().enumerate() {
            let text = format!("{value:.DECIMALS$}");
            if let Some((_, first, other, _)) = edits[..j].last().filter(|e| e.0 == *span) {
                if format!("{other:.DECIMALS$}") != text {
                    let (a, b) = (&self.targets[*first], &self.targets[*i]);
                    return Err(Error::Program {
                        line: b.line,
                        message: format!(
                            "the motions of lines {} and {} go to the one point of line {}, but their compensated targets differ ({other:.DECIMALS$} and {text} deg): give each visit its own point",
                            a.line, b.line, b.origin
                        ),
                    });
                }
                continue;
            }
            let shared_change = edits[j..].iter().take_while(|e| e.0 == *span).any(|e| e.3);
            if *changed || shared_change {
                out.push_str(&self.text[at..span.start]);
                out.push_str(&text);
                at = span.end;
            }
        }
        out.push_str(&self.text[at..]);
        Ok(out)
    }
}

/// The error at `line`.
pub(crate) fn at(line: u64, message: String) -> Error {
    Error::Program { line, message }
}

/// The number at the start of `text[from..]` after blanks (line ends included): its value and
/// byte span.
pub(crate) fn number_at(text: &str, from: usize) -> Option<(f64, Range<usize>)> {
    let bytes = text.as_bytes();
    let mut start = from;
    while start < bytes.len() && matches!(bytes[start], b' ' | b'\t' | b'\n' | b'\r') {
        start += 1;
    }
    let mut end = start;
    if end < bytes.len() && matches!(bytes[end], b'+' | b'-') {
        end += 1;
    }
    let digits = |end: &mut usize| {
        let s = *end;
        while *end < bytes.len() && bytes[*end].is_ascii_digit() {
            *end += 1;
        }
        *end > s
    };
    let mut any = digits(&mut end);
    if end < bytes.len() && bytes[end] == b'.' {
        end += 1;
        any |= digits(&mut end);
    }
    if !any {
        return None;
    }
    if end < bytes.len() && matches!(bytes[end], b'e' | b'E') {
        let mut e = end + 1;
        if e < bytes.len() && matches!(bytes[e], b'+' | b'-') {
            e += 1;
        }
        if digits(&mut e) {
            end = e;
        }
    }
    let value: f64 = text[start..end].parse().ok()?;
    value.is_finite().then_some((value, start..end))
}

/// The 1-based line of each line start: `(line, start byte, the line without its end)`.
pub(crate) fn lines(text: &str) -> impl Iterator<Item = (u64, usize, &str)> {
    let mut start = 0;
    text.split_inclusive('\n').enumerate().map(move |(i, l)| {
        let s = start;
        start += l.len();
        (i as u64 + 1, s, l.trim_end_matches(['\n', '\r']))
    })
}

/// The six axis values of a target as found so far: value and span.
pub(crate) type Found = [Option<(f64, Range<usize>)>; 6];

/// Six axis values collected by name (`A1`.., `J1`..): the target, or what is missing.
pub(crate) fn six(
    line: u64,
    found: [Option<(f64, Range<usize>)>; 6],
    names: &str,
) -> Result<JointTarget> {
    let mut q_deg = [0.0; 6];
    let mut spans: [Range<usize>; 6] = Default::default();
    for (k, f) in found.into_iter().enumerate() {
        let (v, s) = f.ok_or_else(|| {
            at(
                line,
                format!("joint target without axis {} ({names}{})", k + 1, k + 1),
            )
        })?;
        q_deg[k] = v;
        spans[k] = s;
    }
    Ok(JointTarget {
        line,
        q_deg,
        spans,
        origin: line,
        incremental: false,
    })
}
