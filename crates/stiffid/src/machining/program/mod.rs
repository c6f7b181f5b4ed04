//! Robot programs: the joint targets of KUKA KRL, ABB RAPID and FANUC LS programs, read and
//! written back with everything else byte for byte.
//!
//! - [`krl`]: `PTP`/`LIN` motions and `E6AXIS`/`AXIS` declarations with an aggregate
//!   `{A1 .., A2 .., ..., A6 ..}` (further members such as `E1` are kept as they are).
//! - [`rapid`]: `jointtarget` declarations and `MoveAbsJ` with a literal `[[j1,..,j6],[e1,..,e6]]`.
//! - [`ls`]: the `/POS` section's positions in joint representation, `J1= .. deg` to `J6`.
//!
//! Only joint targets are read. A Cartesian target (KRL `E6POS`/`POS`/`FRAME` aggregates in a
//! motion, RAPID `MoveL`/`MoveJ`/`MoveC`, LS positions with `X = .. mm`) is refused naming its
//! line: turning it into axis angles needs the controller's configuration flags (KUKA `S`/`T`,
//! ABB `confdata`, FANUC `CONFIG : 'N U T, ...'`) and its own kinematic conventions to pick the
//! one of up to eight inverse-kinematics solutions the controller would take, and a compensated
//! target would have to be written back with flags the controller agrees with. Joint targets are
//! unambiguous in both directions.
//!
//! The targets come in the order they appear in the file (KRL, RAPID: declarations and literal
//! motions as they come; LS: the `/POS` table), which is the order the path follows.
//! [`JointProgram::write`] replaces the six numbers of each target whose value changed (with
//! [`DECIMALS`] decimals) and nothing else.

pub mod generate;
pub mod krl;
pub mod ls;
pub mod rapid;

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

/// One joint target of a program.
#[derive(Debug, Clone, PartialEq)]
pub struct JointTarget {
    /// Its line, 1-based.
    pub line: u64,
    /// Axis angles q1..q6, deg, as written.
    pub q_deg: [f64; 6],
    /// Where each of the six numbers sits in the text (bytes).
    spans: [Range<usize>; 6],
}

/// A robot program and its joint targets.
#[derive(Debug, Clone, PartialEq)]
pub struct JointProgram {
    /// The language.
    pub dialect: Dialect,
    /// The targets, in file order.
    pub targets: Vec<JointTarget>,
    text: String,
}

/// Parses the joint targets of `text` in `dialect`.
///
/// # Errors
/// [`Error::Program`] naming the line: a Cartesian or relative motion, a joint target with a
/// missing, repeated or non-numeric axis value, no joint target at all, or more than
/// [`MAX_TARGETS`].
pub fn parse(text: &str, dialect: Dialect) -> Result<JointProgram> {
    let targets = match dialect {
        Dialect::Krl => krl::targets(text)?,
        Dialect::Rapid => rapid::targets(text)?,
        Dialect::FanucLs => ls::targets(text)?,
    };
    if targets.is_empty() {
        return Err(at(1, "no joint target found".into()));
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
        let mut out = String::with_capacity(self.text.len() + self.targets.len() * 24);
        let mut at = 0;
        for (t, q) in self.targets.iter().zip(q_deg) {
            for ((new, old), span) in q.iter().zip(&t.q_deg).zip(&t.spans) {
                if new == old {
                    continue;
                }
                out.push_str(&self.text[at..span.start]);
                out.push_str(&format!("{new:.DECIMALS$}"));
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

/// The number at the start of `text[from..]` after blanks: its value and byte span.
pub(crate) fn number_at(text: &str, from: usize) -> Option<(f64, Range<usize>)> {
    let bytes = text.as_bytes();
    let mut start = from;
    while start < bytes.len() && matches!(bytes[start], b' ' | b'\t') {
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
    Ok(JointTarget { line, q_deg, spans })
}
