//! ABB RAPID: `CONST jointtarget j1 := [[0,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]];` (also `VAR`,
//! `PERS`) and `MoveAbsJ [[..],[..]], v100, z10, tool0;`; `!` starts a comment.

use super::{at, number_at, six, JointTarget};
use crate::Result;

/// Every joint target of `text` (module docs).
pub(crate) fn targets(text: &str) -> Result<Vec<JointTarget>> {
    let mut out = Vec::new();
    for (line, start, l) in super::lines(text) {
        let code = l.split('!').next().unwrap_or("");
        let lower = code.to_ascii_lowercase();
        let first = lower.split_whitespace().next().unwrap_or("");
        if matches!(
            first,
            "movel" | "movej" | "movec" | "movelsync" | "movejsync"
        ) {
            return Err(at(line, format!("{first}: a Cartesian motion (robtarget); stiffid compensates joint targets (MoveAbsJ with jointtarget)")));
        }
        let declared = lower.contains("jointtarget");
        let moving = first.starts_with("moveabsj");
        if !(declared || moving) {
            continue;
        }
        let Some(open) = code.find("[[") else {
            continue; // MoveAbsJ to a named jointtarget: its declaration holds the numbers.
        };
        let mut found: [Option<(f64, std::ops::Range<usize>)>; 6] = Default::default();
        let mut from = open + 2;
        for (k, slot) in found.iter_mut().enumerate() {
            let (v, span) = number_at(code, from).ok_or_else(|| {
                at(
                    line,
                    format!(
                        "jointtarget: expected 6 numbers in its first bracket, axis {} is not one",
                        k + 1
                    ),
                )
            })?;
            let rest = code[span.end..].trim_start();
            let sep = if k < 5 { ',' } else { ']' };
            if !rest.starts_with(sep) {
                return Err(at(
                    line,
                    format!("jointtarget: expected '{sep}' after axis {}", k + 1),
                ));
            }
            from = code.len() - rest.len() + 1;
            *slot = Some((v, start + span.start..start + span.end));
        }
        out.push(six(line, found, "rax_")?);
    }
    Ok(out)
}
