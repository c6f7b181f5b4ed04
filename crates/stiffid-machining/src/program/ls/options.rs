//! The words after an LS motion's speed: its termination and its options, which stiffid follows
//! where they cannot change the path or its end, and refuses naming the line where they can
//! (FANUC R-30iA/R-30iB HandlingTool operator's manual, "Motion instructions": the motion
//! options; ArcTool's "Arc instructions").
//!
//! - Termination: `FINE`, `CNTn`, `CNT R[i]`, `CRn`, `CDn` (the corner's rounding is the
//!   controller's, as for every program stiffid reads).
//! - Followed: `ACCn` (acceleration), `PTH` (the path planned for short segments), `INC`
//!   (resolved by the reader), `Arc Start[..]`/`Arc End[..]` (ArcTool: the arc switched on or
//!   off at the point), `EVn%`/`Ind.EVn%` (extended axes' speed), `TB`/`TA`/`DB` with the
//!   instruction they run early or late (an output, a point-logic or a program call: a program
//!   called there runs without a motion group, so it cannot move the robot).
//! - Offsets by a position register, `Offset,PR[i]` (in the user frame) and `Tool_Offset,PR[i]`
//!   (in the tool frame; `WKZ_Offset,PR[i]` in a German program): read, the register's value
//!   from the backup ([`super::registers`]).
//! - Refused: `COORD` (coordinated motion: the path is relative to the leader group, a
//!   positioner that moves during it), `Offset` and `Tool_Offset` without a register (the
//!   `OFFSET CONDITION` in force), `VOFFSET` (an offset held on the controller), `Skip,LBL[..]` and any option naming
//!   a label (`Interrupt,LABEL[..]` in a German program: a jump), and every other option
//!   (`Wjnt`, `RTCP`, `Weave`, `CTV`, ...): stiffid does not follow them.

use crate::program::at;
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// What a motion's words after its speed say: whether it ends `FINE` and whether it is `INC`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(super) struct Options {
    /// The motion ends `FINE`: the robot stops on the target.
    pub fine: bool,
    /// The position holds the increment from the previous target (`INC`).
    pub incremental: bool,
    /// `Offset,PR[i]` (`false`: in the user frame) or `Tool_Offset,PR[i]` (`true`: in the
    /// tool frame), the register's number.
    pub offset: Option<(bool, u32)>,
}

/// The termination and options of the motion `what` (`L P[3]`) on `line`, from the words after
/// its speed (module docs).
///
/// # Errors
/// Naming the line: no termination, or an option stiffid refuses (module docs).
pub(super) fn read(line: u64, what: &str, words: &[&str]) -> Result<Options> {
    let upper: Vec<String> = words.iter().map(|w| w.to_ascii_uppercase()).collect();
    let termination = upper.first().map(String::as_str).unwrap_or("");
    let mut rest = upper.get(1..).unwrap_or(&[]);
    let fine = termination == "FINE";
    let terminated = fine
        || ["CNT", "CR", "CD"]
            .iter()
            .any(|p| termination.starts_with(p));
    if !terminated {
        return Err(at(
            line,
            format!("{what}: expected a speed and a termination (FINE, CNTn, CRn, CDn)"),
        ));
    }
    // `CNT R[i]`: the value in a register, its own word.
    if termination == "CNT" && rest.first().is_some_and(|w| w.starts_with("R[")) {
        rest = &rest[1..];
    }
    let mut options = Options {
        fine,
        incremental: false,
        offset: None,
    };
    let mut i = 0;
    while let Some(w) = rest.get(i) {
        i += 1 + option(line, what, w, &rest[i + 1..], &mut options)?;
    }
    Ok(options)
}

/// One option word `w` (upper case) and the words after it: how many of those it takes too.
fn option(line: u64, what: &str, w: &str, after: &[String], o: &mut Options) -> Result<usize> {
    let refuse = |why: &str| Err(at(line, format!("{what} {}: {why}", short(w))));
    match w {
        "INC" => o.incremental = true,
        "PTH" => {}
        "ARC" => {
            return match after.first() {
                Some(n) if n.starts_with("START[") || n.starts_with("END[") => Ok(1),
                _ => refuse("expected Arc Start[..] or Arc End[..]"),
            }
        }
        "TB" | "TA" | "DB" => {
            // The time or distance and the instruction, `.10sec,DO[1]=ON`, `0.5sec,CALL X`.
            let takes_name = after.first().is_some_and(|a| a.ends_with(",CALL"));
            return Ok(1 + usize::from(takes_name));
        }
        "COORD" => {
            return refuse("coordinated motion: the path is relative to the leader group (a positioner) that moves during it; stiffid reads a positioner's axes as the program's targets, not a path relative to it: write the motion without COORD")
        }
        a if a.starts_with("ACC") || a.starts_with("EV") || a.starts_with("IND.EV") => {}
        w if offset(w).is_some() => o.offset = offset(w),
        // The register written apart from its option (`Tool_Offset ,PR[2]`): one option.
        w if conditioned(w).is_some() && after.first().is_some_and(|a| a.starts_with(',')) => {
            let Some(named) = offset(&format!("{w}{}", after[0])) else {
                return refuse("the offset is held on the controller (a register stiffid cannot read), not in this program; apply it to the positions and remove it");
            };
            o.offset = Some(named);
            return Ok(1);
        }
        w if conditioned(w).is_some() => o.offset = conditioned(w).map(|tool| (tool, 0)),
        o if o.starts_with("OFFSET")
            || o.starts_with("TOOL_OFFSET")
            || o.starts_with("WKZ_OFFSET")
            || o.starts_with("VOFFSET") =>
        {
            return refuse("the offset is held on the controller (a position register or vision offset), not in this program; apply it to the positions and remove it")
        }
        s if s.starts_with("SKIP") || s.contains("LBL[") || s.contains("LABEL[") => {
            return refuse("a jump to a label when its condition holds (a skip); the path the controller runs would not be the file's: remove it")
        }
        _ => {
            return refuse("an option stiffid does not follow (the path or its end would not be the program's); remove it or compensate the program without it")
        }
    }
    Ok(0)
}

/// The offset option `w` (upper case) names with its register: `OFFSET,PR[i]` (in the user frame,
/// `false`) or `TOOL_OFFSET,PR[i]` (`WKZ_OFFSET,PR[i]` in a German program: in the tool frame,
/// `true`), `i` a number.
pub(super) fn offset(w: &str) -> Option<(bool, u32)> {
    let (kind, register) = w.split_once(",PR[")?;
    let tool = match kind {
        "OFFSET" => false,
        "TOOL_OFFSET" | "WKZ_OFFSET" => true,
        _ => return None,
    };
    let n = register.split([']', ':']).next()?.trim().parse().ok()?;
    Some((tool, n))
}

/// The offset option `w` (upper case) names without a register, `OFFSET` (`false`) or
/// `TOOL_OFFSET` (`WKZ_OFFSET`: `true`): by the register the `OFFSET CONDITION` (`TOOL_OFFSET
/// CONDITION`) in force names ([`super::values`]).
pub(super) fn conditioned(w: &str) -> Option<bool> {
    match w {
        "OFFSET" => Some(false),
        "TOOL_OFFSET" | "WKZ_OFFSET" => Some(true),
        _ => None,
    }
}
