//! The user and tool frames an LS program sets itself before anything else runs, as RoboDK's
//! FANUC post writes a reference frame: each element of a position register set to a number,
//! then the frame set from the register (FANUC HandlingTool operator's manual, "Position
//! register element", "Frame instructions"):
//!
//! ```text
//!   8:  PR[9,1]=2000    ;
//!   9:  PR[9,2]=(-9500)    ;
//!  ..   PR[9,6]=90    ;
//!  15:  UFRAME[9:STRIP_DRILL]=PR[9] ;
//! ```
//!
//! Read only at the program's start, before its first motion, label, jump, branch or call
//! (remarks and `UFRAME_NUM`/`UTOOL_NUM` between them), so that it runs once on every path
//! before every motion: the frame is then the program's on every run, whatever the controller
//! held before. The register's six elements `X`..`R` must each be set there, and the register
//! must be in Cartesian representation in the backup's `POSREG.VA` (an element of a joint
//! register is an axis angle): otherwise the frame is the controller's, and the instruction is
//! refused as any other that sets a frame's value ([`super::statements`]).

use super::registers::FILE;
use super::va::{entries, Value};
use crate::program::cartesian::Frame;
use crate::program::{Context, JointTarget};
use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use std::collections::HashMap;
use stiffid_core::Result;

/// The frames set at the program's start: per number, the frame and the line that sets it; and
/// the indexes of the instructions read here (not refused as setting a frame).
#[derive(Debug, Default)]
pub(super) struct Set {
    users: HashMap<u32, (Isometry3<f64>, u64)>,
    tools: HashMap<u32, (Isometry3<f64>, u64)>,
    pub handled: Vec<usize>,
}

/// What one instruction of the start is.
enum Step {
    /// `PR[j,e]=value`: register `j`, element `e` counted from 0 (`X`..`R`, then `E1`..).
    Element(u32, usize, f64),
    /// `UFRAME[i]=PR[j]` (`true`: `UTOOL[i]=PR[j]`).
    Frame(bool, u32, u32),
    /// A remark, an empty line, a frame number selected.
    Passed,
}

/// The frames `instructions` set at their start (module docs), with the registers' representation
/// from the `context`'s backup.
///
/// # Errors
/// Two `POSREG.VA` files that differ ([`super::va::the_file`]).
pub(super) fn read(instructions: &[(u64, String)], context: &Context) -> Result<Set> {
    let mut set = Set::default();
    let Some((_, text)) = super::va::the_file(context, FILE)? else {
        return Ok(set);
    };
    let cartesian = |j: u32| {
        let held = entries(text, "$POSREG");
        let entry = held.into_iter().find(|e| e.group == 1 && e.number == j);
        matches!(entry.map(|e| e.value), Some(Ok(Some(Value::Cartesian(..)))))
    };
    let mut elements: HashMap<u32, [Option<f64>; 6]> = HashMap::new();
    for (k, (line, t)) in instructions.iter().enumerate() {
        match step(t) {
            Some(Step::Passed) => {}
            Some(Step::Element(j, e, v)) => {
                // Elements 7 to 9 are the extended axes', no part of a frame.
                if let Some(slot) = elements.entry(j).or_default().get_mut(e) {
                    *slot = Some(v);
                }
                set.handled.push(k);
            }
            Some(Step::Frame(tool, i, j)) => {
                let values = elements.get(&j).and_then(|v| {
                    let all: Option<Vec<f64>> = v.iter().copied().collect();
                    all.filter(|_| cartesian(j))
                });
                let Some(v) = values else {
                    return Ok(set);
                };
                let frame = pose(&v);
                match tool {
                    false => set.users.insert(i, (frame, *line)),
                    true => set.tools.insert(i, (frame, *line)),
                };
                set.handled.push(k);
            }
            None => break,
        }
    }
    Ok(set)
}

/// The pose of `X`..`R` (mm, deg, `Rz(R) Ry(P) Rx(W)`), m.
fn pose(v: &[f64]) -> Isometry3<f64> {
    let (w, p, r) = (v[3].to_radians(), v[4].to_radians(), v[5].to_radians());
    let position = Translation3::new(v[0] * 1e-3, v[1] * 1e-3, v[2] * 1e-3);
    Isometry3::from_parts(position, UnitQuaternion::from_euler_angles(w, p, r))
}

/// What instruction `t` is at the program's start; `None`: it ends the start.
fn step(t: &str) -> Option<Step> {
    let upper = super::statements::english(&t.trim().to_ascii_uppercase());
    let u = upper.trim();
    if u.is_empty() || u.starts_with('!') || u.starts_with("//") {
        return Some(Step::Passed);
    }
    if u.starts_with("UFRAME_NUM") || u.starts_with("UTOOL_NUM") {
        return Some(Step::Passed);
    }
    let (lhs, rhs) = u.split_once('=')?;
    let (lhs, rhs) = (lhs.trim(), rhs.trim());
    if let Some(inside) = lhs.strip_prefix("PR[").and_then(|r| r.strip_suffix(']')) {
        let (j, e) = inside.split_once(',')?;
        let (j, e): (u32, usize) = (j.trim().parse().ok()?, e.trim().parse().ok()?);
        let v = rhs.trim_start_matches('(').trim_end_matches(')').trim();
        let v: f64 = v.parse().ok().filter(|v: &f64| v.is_finite())?;
        return (1..=9).contains(&e).then_some(Step::Element(j, e - 1, v));
    }
    let tool = match lhs {
        _ if lhs.starts_with("UFRAME[") => false,
        _ if lhs.starts_with("UTOOL[") => true,
        _ => return None,
    };
    let i = lhs.split(['[', ':', ']']).nth(1)?.trim().parse().ok()?;
    let j = rhs.strip_prefix("PR[")?.split([':', ']']).next()?.trim();
    Some(Step::Frame(tool, i, j.parse().ok()?))
}

/// The Cartesian `targets` in a frame `set` gives by number: in it, as the program states it
/// ([`Frame::Stated`] on the line that sets it).
pub(super) fn apply(set: &Set, targets: &mut [JointTarget]) {
    let taken = |frame: &mut Frame, held: &HashMap<u32, (Isometry3<f64>, u64)>| {
        let n = match frame {
            Frame::Numbered(_, n) | Frame::Held(_, n, ..) => *n,
            _ => return,
        };
        if let Some((f, line)) = held.get(&n) {
            *frame = Frame::Stated(*line, *f);
        }
    };
    for c in targets
        .iter_mut()
        .filter_map(|t| t.cartesian.as_deref_mut())
    {
        taken(&mut c.frame, &set.users);
        taken(&mut c.tool, &set.tools);
    }
}

#[cfg(test)]
#[path = "set_frames_tests.rs"]
mod tests;
