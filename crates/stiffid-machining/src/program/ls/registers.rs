//! A motion to a position register (`J PR[i] ..`, `L PR[i:name] ..`): refused naming its line,
//! saying why. A position register is the controller's, shared by every program on it, and a
//! program may set it as it runs: stiffid does not compensate a motion to one, whose value a
//! compensation would have to change for every program that uses it. Where the program assigns
//! the register (`PR[i]=LPOS`, `PR[i,3]=..`, `PR[i]=PR[j]+..`), the refusal names that line (its
//! value is the run's); where the controller's backup gives `POSREG.VA`, it says the register's
//! value there is not one stiffid changes; otherwise, that the value is the controller's.

use super::statements::english;
use crate::program::{at, Context};
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// Refuses the first motion of `instructions` (`motions` says which) to a position register
/// (module docs).
///
/// # Errors
/// Naming the motion's line (module docs).
pub(super) fn check(
    instructions: &[(u64, String)],
    motions: &[bool],
    context: &Context,
) -> Result<()> {
    for (k, (line, t)) in instructions.iter().enumerate() {
        let Some(n) = motions[k].then(|| register(t)).flatten() else {
            continue;
        };
        let what = format!("{} PR[{n}]", &t.trim()[..1]);
        let assigned = instructions.iter().find(|(_, a)| assigns(a, n));
        let why = match (assigned, context.backup_file("POSREG.VA")) {
            (Some((l, a)), _) => format!("the position register is set on line {l} as the program runs ({}): its value is the run's, not the file's; move to a P[] position", short(a.trim())),
            (None, Some((file, _))) => format!("a position register is the controller's, shared by every program on it ({file} holds its value): stiffid does not change it, since every program that moves to it would move elsewhere; copy its value into a P[] position of this program to have the motion compensated"),
            (None, None) => "a position register holds its value on the controller, not in this program; copy it into a P[] position".into(),
        };
        return Err(at(*line, format!("{what}: {why}")));
    }
    Ok(())
}

/// The register number of a motion `t` to a position register (`J PR[3:home] ..`), if it is one.
fn register(t: &str) -> Option<u32> {
    let rest = t.trim().get(1..)?.trim_start().strip_prefix("PR[")?;
    rest.split([']', ':', ',']).next()?.trim().parse().ok()
}

/// Whether instruction `t` assigns position register `n` (or one of its elements).
fn assigns(t: &str, n: u32) -> bool {
    let upper = english(&t.trim().to_ascii_uppercase());
    let Some((lhs, _)) = upper.split_once('=') else {
        return false;
    };
    let Some(inner) = lhs.trim().strip_prefix("PR[") else {
        return false;
    };
    inner
        .split([']', ':', ','])
        .next()
        .and_then(|d| d.trim().parse::<u32>().ok())
        == Some(n)
}
