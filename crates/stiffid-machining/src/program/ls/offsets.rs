//! A motion offset by a position register whose value the backup's `POSREG.VA` holds
//! ([`super::registers`]): `Offset,PR[i]` moves the target by the register's `X`, `Y`, `Z` in
//! the user frame the position is in, `Tool_Offset,PR[i]` in its tool frame (FANUC R-30iA/R-30iB
//! HandlingTool operator's manual, "Position offset instruction", "Tool offset instruction").
//! The offset is the register's translation: a register that also turns (`W`, `P`, `R` not 0),
//! one in joint representation, one that moves an extended axis, and an offset of a position
//! in joint representation are refused naming the line, their composition not being the file's
//! to say. Compensated, the position is written so that the offset lands the tool on the
//! compensated pose; the register is left as it is.

use super::registers::Register;
use super::va::Value;
use crate::program::cartesian::Frame;
use crate::program::{at, JointTarget};
use nalgebra::{Isometry3, Translation3};
use stiffid_core::Result;

/// The offset `(tool, r)` (in the tool frame where `tool`, register `r`) applied to `target`, the
/// motion's on `line` (module docs).
///
/// # Errors
/// Naming the line (module docs).
pub(super) fn apply(
    line: u64,
    target: &mut JointTarget,
    (tool, r): &(bool, Register),
    frame: Option<&(u32, u64)>,
) -> Result<()> {
    let word = if *tool { "Tool_Offset" } else { "Offset" };
    let what = format!("{word},PR[{}] ({})", r.number, r.source);
    let refuse = |why: &str| Err(at(line, format!("{what}: {why}")));
    let Some(c) = target.cartesian.as_deref_mut() else {
        return refuse("an offset of a position in joint representation; stiffid offsets Cartesian positions: give the position in Cartesian representation, or apply the offset to it");
    };
    let own = if *tool { &c.tool } else { &c.frame };
    if let Some((n, l)) = frame
        && number(own) != Some(*n)
    {
        let (word, frames) = if *tool {
            ("UTOOL", "UT")
        } else {
            ("UFRAME", "UF")
        };
        return refuse(&format!("the offset condition on line {l} puts the offset in {word}[{n}], the position is in another ({frames} : {}); stiffid offsets in the position's own frame: name its frame in the condition, or none", number(own).map_or("F".into(), |m| m.to_string())));
    }
    let p = match &r.entry.value {
        Ok(Some(Value::Cartesian(p, _))) => p,
        _ => return refuse(
            "a register in joint representation; stiffid offsets by a Cartesian register's X, Y, Z",
        ),
    };
    if p[3..].iter().any(|a| a.abs() > 1e-9) {
        return refuse("the register turns (W, P, R not 0); stiffid offsets by a translation: apply the offset to the position");
    }
    if r.entry.extended.iter().any(|(v, _)| v.abs() > 1e-9) {
        return refuse("the register moves an extended axis (EXT1 not 0); stiffid offsets the robot's pose alone: apply the offset to the position");
    }
    let shift = Isometry3::from(Translation3::new(p[0] * 1e-3, p[1] * 1e-3, p[2] * 1e-3));
    match tool {
        true => c.after = shift,
        false => c.before = shift,
    }
    Ok(())
}

/// The number of a position's frame `f` (`UF : n`, `UT : n`), 0 for the world or the flange.
fn number(f: &Frame) -> Option<u32> {
    match f {
        Frame::World => Some(0),
        Frame::Numbered(_, n) | Frame::Held(_, n, ..) | Frame::Declared(_, n) => Some(*n),
        _ => None,
    }
}
