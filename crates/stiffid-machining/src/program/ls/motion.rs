//! One LS motion instruction's targets (module docs of [`super`]): `J P[i] ..`, `L P[i] ..`, and
//! the circular `C P[i] .. P[j] ..` whose via point and end are both targets (FANUC R-30iA/R-30iB
//! HandlingTool operator's manual, "Motion instructions": circular motion moves the TCP on the
//! arc through the start, the via point and the end, at the end's speed and termination).
//!
//! `A` (circular arc, R-30iB: the arc through three and more successive `A` points, blended into
//! one path) is refused naming the line: its path depends on the points before and after it.

use super::options;
use super::speed;
use crate::program::{at, JointTarget};
use std::collections::HashMap;
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// After `J `, `L `, `C ` or `A `, the rest of a motion instruction.
pub(super) fn rest(t: &str) -> Option<&str> {
    let mut chars = t.chars();
    let letter = chars.next()?;
    let rest = chars.as_str();
    let next = rest.trim_start();
    (matches!(letter, 'J' | 'L' | 'C' | 'A') && next.len() < rest.len() && next.starts_with('P'))
        .then_some(next)
}

/// The targets of the motion `t` on `line` (one, two for `C`: the via point then the end) to
/// the `/POS` `positions`, after the targets `before` (the last of which ended `FINE` when
/// `previous_fine`), and whether the motion ends `FINE`. A motion to a position register goes
/// to `copy`, the position of `positions` holding its copy ([`super::copies`]), if given.
///
/// # Errors
/// Naming the line: a motion outside the subset (module docs of [`super`], [`options`]), a
/// position missing from `/POS`, an `INC` motion stiffid cannot resolve.
pub(super) fn targets(
    line: u64,
    t: &str,
    positions: &HashMap<u64, JointTarget>,
    (before, previous_fine): (&[JointTarget], bool),
    copy: Option<u64>,
) -> Result<(Vec<JointTarget>, bool)> {
    let Some(rest) = rest(t) else {
        return Ok((Vec::new(), previous_fine));
    };
    let letter = &t[..1];
    if letter == "A" {
        return Err(at(line, "A: a circular arc motion (R-30iB), whose path blends the arcs through the A points around it; stiffid does not follow it: write the path as C or L motions".into()));
    }
    let (index, after) = match (copy, rest.strip_prefix("PR[")) {
        (Some(n), Some(inside)) => (n, inside.split_once(']').map_or("", |(_, a)| a)),
        _ => target(line, letter, rest)?,
    };
    if letter == "C" {
        let (options, end) = after.split_once('P').map_or((after, ""), |(o, e)| (o, e));
        if let Some(word) = options.split_whitespace().next() {
            return Err(at(line, format!("C P[{index}] {}: an option on the via point stiffid does not follow; remove it", short(word))));
        }
        let end = format!("P{end}");
        let (end_index, end_after) = target(line, "C", &end)?;
        return circular(line, (index, end_index), end_after, positions);
    }
    let words = words(after);
    let what = format!("{letter} P[{index}]");
    let o = options::read(line, &what, words.get(1..).unwrap_or(&[]))?;
    let mut target = position(line, letter, index, positions)?.moved_to(line, o.incremental);
    target.speed = speed::speed(line, letter, words.first().copied().unwrap_or(""))?;
    if o.incremental && o.offset.is_some() {
        return Err(at(line, format!("{what} INC: an incremental motion offset by a position register; write the position absolute")));
    }
    if o.incremental {
        increment(
            line,
            &what,
            &mut target,
            before.last().filter(|_| previous_fine),
        )?;
    }
    Ok((vec![target], o.fine))
}

/// The via point and end of `C P[via] .. P[end] <after>` on `line`.
fn circular(
    line: u64,
    (via, end): (u64, u64),
    after: &str,
    positions: &HashMap<u64, JointTarget>,
) -> Result<(Vec<JointTarget>, bool)> {
    let words = words(after);
    let what = format!("C P[{via}] P[{end}]");
    let o = options::read(line, &what, words.get(1..).unwrap_or(&[]))?;
    if o.incremental {
        return Err(at(line, format!("{what} INC: an incremental circular motion; stiffid follows circular motions to absolute positions: write P[{via}] and P[{end}] absolute")));
    }
    if o.offset.is_some() {
        return Err(at(line, format!("{what}: a circular motion offset by a position register; stiffid offsets linear and joint motions: apply the offset to P[{via}] and P[{end}]")));
    }
    let speed = speed::speed(line, "C", words.first().copied().unwrap_or(""))?;
    let mut out = Vec::with_capacity(2);
    for index in [via, end] {
        let mut t = position(line, "C", index, positions)?.moved_to(line, false);
        t.speed = speed.clone();
        out.push(t);
    }
    out[0].via = true;
    Ok((out, o.fine))
}

/// The words of `s` split at blanks outside brackets: a register's comment keeps its blanks
/// (`R[23:weld speed]mm/sec` is one word).
fn words(s: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let (mut depth, mut from) = (0usize, None);
    for (i, c) in s.char_indices() {
        match c {
            '[' => depth += 1,
            ']' => depth = depth.saturating_sub(1),
            c if c.is_whitespace() && depth == 0 => {
                if let Some(f) = from.take() {
                    out.push(&s[f..i]);
                }
                continue;
            }
            _ => {}
        }
        from.get_or_insert(i);
    }
    out.extend(from.map(|f| &s[f..]));
    out
}

/// The position `P[index]` of `/POS` that the motion `letter` on `line` goes to.
fn position<'p>(
    line: u64,
    letter: &str,
    index: u64,
    positions: &'p HashMap<u64, JointTarget>,
) -> Result<&'p JointTarget> {
    positions.get(&index).ok_or_else(|| {
        at(
            line,
            format!("{letter} P[{index}]: no position P[{index}] in /POS"),
        )
    })
}

/// `target` (an `INC` motion's increments) made absolute from `previous`, the target before it
/// when that motion ended `FINE` and it is a joint position (a Cartesian one's axis angles are
/// not known while reading: refused).
fn increment(
    line: u64,
    what: &str,
    target: &mut JointTarget,
    previous: Option<&JointTarget>,
) -> Result<()> {
    if target.cartesian.is_some() {
        return Err(at(line, format!("{what} INC: an increment of a Cartesian position; stiffid follows absolute Cartesian positions: write it absolute")));
    }
    let Some(previous) = previous else {
        return Err(at(line, format!("{what} INC: an increment from where the robot is, which only a previous motion ending FINE in this program fixes; end the previous motion FINE or write the position absolute")));
    };
    if previous.cartesian.is_some() {
        return Err(at(line, format!("{what} INC: an increment of the axis angles from the previous target (line {}), a Cartesian position: the angles the robot starts from are those the controller's inverse kinematics reaches it with, and stiffid adds an increment only to a joint position's angles; write this position absolute, or the previous one in joint representation", previous.line)));
    }
    for (q, p) in target.q_deg.iter_mut().zip(previous.q_deg) {
        *q += p;
    }
    for (e, p) in target.external.iter_mut().zip(&previous.external) {
        if let (Some(e), Some(p)) = (e.as_mut(), p) {
            *e += p;
        }
    }
    Ok(())
}

/// The position index of a motion's target `P[i]` or `P[i:comment]` and the text after it;
/// position registers and indirect indices refused.
fn target<'a>(line: u64, letter: &str, rest: &'a str) -> Result<(u64, &'a str)> {
    let inside = rest
        .strip_prefix("PR[")
        .map(|r| r.split([']', ':']).next().unwrap_or(""));
    if inside.is_some_and(|i| i.contains(',')) {
        return Err(at(line, format!("{letter} PR[{}]: an element of a position register is a number, not a target; the controller does not load such a motion: move to the register, PR[i]", short(inside.unwrap_or("")))));
    }
    if rest.starts_with("PR[") {
        return Err(at(line, format!("{letter} PR[..]: a position register holds its value on the controller, not in this program; copy it into a P[] position")));
    }
    let inner = rest
        .strip_prefix("P[")
        .ok_or_else(|| at(line, format!("{letter}: expected a target P[i]")))?;
    let close = inner
        .find(']')
        .ok_or_else(|| at(line, format!("{letter} P[: expected ']'")))?;
    let index = inner[..close].split(':').next().unwrap_or("").trim();
    let index: u64 = index.parse().map_err(|_| {
        at(line, format!("{letter} P[{}]: the index is computed on the controller (a register); stiffid follows positions by number", short(index)))
    })?;
    Ok((index, &inner[close + 1..]))
}
