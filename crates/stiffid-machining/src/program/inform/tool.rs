//! The tool file a job moves with (`///TOOL n` before its positions, `TOOL#(n)` on a motion)
//! checked against the setup's tool (module docs of [`super`]).

use super::inst::Motion;
use super::pos::{Form, Kind, Position};
use super::Context;
use crate::program::at;
use crate::program::cartesian::{same, words, SAME_M};
use nalgebra::Isometry3;
use std::collections::HashMap;
use stiffid_core::Result;

/// Tool file `n` (selected on `line`) as the controller holds it, and which says so: the
/// backup's `TOOL.CND` (`backup`) or the setup's `[controller] tools`; refused where both give
/// it and differ (one controller holds one tool file per number).
fn held(
    context: &Context,
    backup: Option<&(Isometry3<f64>, String)>,
    (line, n): (u64, u32),
) -> Result<Option<(Isometry3<f64>, String)>> {
    let table = context.tool.and_then(|(_, tools)| tools.get(n));
    match (backup, table) {
        (Some((b, source)), Some(t)) if !same(b, t) => Err(at(line, format!("tool file {n}: the backup's {source} gives {}, the setup's [controller] tools {}; one controller holds one tool file per number: remove the setup's entry or make the two agree", words(b), words(t)))),
        (Some((b, source)), _) => Ok(Some((*b, format!("the backup's {source}")))),
        (None, Some(t)) => Ok(Some((*t, "the setup's [controller] tools".into()))),
        (None, None) => Ok(None),
    }
}

/// Checks the tool file of each motion but a `MOVJ` to a position in pulses (a joint motion to
/// pulses does not use it): one the backup's `TOOL.CND` or the setup's
/// `[controller] tools` gives has the setup's tool centre point (within 1 um: a job's pulse
/// positions do not depend on the tool's orientation; refused otherwise); one neither gives is
/// taken as the setup's tool only in a job that never changes its tool file (refused naming
/// the line where it changes).
///
/// # Errors
/// [`stiffid_core::Error::Program`] naming the line of the tool file refused.
pub(super) fn check(
    motions: &[Motion],
    positions: &HashMap<(Kind, u64), Position>,
    context: &Context,
) -> Result<()> {
    let backup = super::toolcnd::tools(context)?;
    let mut first: Option<(u64, u32, bool)> = None;
    for m in motions {
        let position = positions.get(&(Kind::Robot, m.robot));
        if m.word == "MOVJ" && position.is_some_and(|p| p.form == Form::Pulse) {
            // A joint motion to pulses ends at the pulses and moves its axes, whatever the
            // tool file: the controller does not use it.
            continue;
        }
        let taught = position.and_then(|p| p.tool);
        let Some((line, n)) = m.tool.map(|n| (m.line, n)).or(taught) else {
            continue;
        };
        let held = held(context, backup.get(&n), (line, n))?;
        if let (Some((setup, _)), Some((held, said))) = (context.tool, &held) {
            let off = (setup.translation.vector - held.translation.vector).norm();
            if off > SAME_M {
                let before = match first {
                    Some((at_line, was, _)) if was != n => format!("; the job moved with tool file {was} (line {at_line}), the setup's tool, before it: a job with two tool files whose centre points differ moves two tools, and one setup compensates one; compensate the motions of each tool file with a setup of that tool"),
                    _ => ": write the job for it".into(),
                };
                return Err(at(line, format!("tool file {n}, which {said} gives as {}, is not the setup's tool ({}: its [tool] tcp_mm, after [robot_flange]); compensation moves the setup's tool{before}", words(held), words(&setup))));
            }
        }
        match first {
            None => first = Some((line, n, held.is_some())),
            Some((at_line, was, both)) if was != n && !(both && held.is_some()) => {
                return Err(at(line, format!("tool file {n} after tool file {was} (line {at_line}): a job that changes its tool file is compensated only with each tool file in the setup's [controller] tools ({{ number = {n}, xyz_mm = [..], rpy_deg = [..] }}), checked against the setup's tool")));
            }
            Some(_) => {}
        }
    }
    Ok(())
}
