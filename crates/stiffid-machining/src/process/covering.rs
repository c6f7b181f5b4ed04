//! Which operation of the process covers each point of a program: a G-code point the operation
//! its `(operation: NAME)` comment names, else the one whose `tool_number` is the `T` in force;
//! a robot program's target the one whose `lines` hold its line; else the one operation without
//! a selector.

use crate::process::{Kind, Operation, Process};
use crate::Program;
use stiffid_core::{Error, Result};

/// The operation covering each point (module docs of the crate), whether or not the tool cuts
/// there ([`crate::cutting::cutting`] decides).
pub(crate) fn operations<'a>(
    program: &Program,
    process: &'a Process,
) -> Result<Vec<Option<(usize, &'a Operation)>>> {
    let ops = &process.operations;
    let fallback = |line: u64| fallback(ops, line);
    match program {
        Program::GCode(g) => g
            .points
            .iter()
            .map(|p| {
                let op = match &p.operation {
                    Some(name) => Some(
                        ops.iter()
                            .enumerate()
                            .find(|(_, o)| o.name == **name)
                            .ok_or_else(|| Error::Program {
                                line: p.line,
                                message: format!(
                                    "(operation: {name}): the process has no operation of that name"
                                ),
                            })?,
                    ),
                    None => p
                        .tool_number
                        .and_then(|t| {
                            ops.iter()
                                .enumerate()
                                .find(|(_, o)| o.selector.tool_number == Some(t))
                        })
                        .map_or_else(|| fallback(p.line), |op| Ok(Some(op)))?,
                };
                match (p.cycle, op) {
                    (Some(c), Some((_, o))) if !matches!(o.kind, Kind::Drilling(_)) => {
                        Err(Error::Program {
                            line: p.line,
                            message: format!(
                                "G{}: a drilling cycle in the milling operation '{}': select a drilling operation for it ((operation: NAME) or T)",
                                g.cycles[c].code,
                                o.name
                            ),
                        })
                    }
                    _ => Ok(op),
                }
            })
            .collect(),
        Program::Robot(r) => (r.targets.iter())
            .map(|t| {
                let by_line = ops.iter().enumerate().find(|(_, o)| {
                    o.selector
                        .lines
                        .is_some_and(|(a, b)| (a..=b).contains(&t.line))
                });
                by_line.map_or_else(|| fallback(t.line), |op| Ok(Some(op)))
            })
            .collect(),
    }
}

/// The operation covering a point on `line` that no selector covers: the one operation without
/// a selector; none without one; refused naming the line when several have none (each is
/// chosen by `(operation: NAME)` only, and this point names none).
fn fallback(ops: &[Operation], line: u64) -> Result<Option<(usize, &Operation)>> {
    let mut free = (ops.iter().enumerate())
        .filter(|(_, o)| o.selector.tool_number.is_none() && o.selector.lines.is_none());
    match (free.next(), free.next()) {
        (one, None) => Ok(one),
        (Some((_, a)), Some((_, b))) => Err(Error::Program {
            line,
            message: format!(
                "no operation covers this point: the process has several without a selector ('{}', '{}'{}), each chosen by an (operation: NAME) comment, and none is in force here; name one before this line, or give the operations a tool_number or lines",
                stiffid_core::common::limits::short(&a.name),
                stiffid_core::common::limits::short(&b.name),
                if free.next().is_some() { ", ..." } else { "" }
            ),
        }),
        (None, Some(_)) => Ok(None),
    }
}
