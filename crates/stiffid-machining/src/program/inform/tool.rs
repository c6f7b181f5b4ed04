//! The tool file a job moves with (`///TOOL n` before its positions, `TOOL#(n)` on a motion)
//! checked against the setup's tool (module docs of [`super`]).

use super::inst::Motion;
use super::pos::{Kind, Position};
use super::Context;
use crate::program::at;
use crate::program::cartesian::{same, words};
use std::collections::HashMap;
use stiffid_core::Result;

/// Checks the tool file of each motion: one the setup's `[controller] tools` gives is the
/// setup's tool (refused otherwise); one it does not give is taken as the setup's tool only in a
/// job that never changes its tool file (refused naming the line where it changes).
///
/// # Errors
/// [`stiffid_core::Error::Program`] naming the line of the tool file refused.
pub(super) fn check(
    motions: &[Motion],
    positions: &HashMap<(Kind, u64), Position>,
    context: &Context,
) -> Result<()> {
    let mut first: Option<(u64, u32, bool)> = None;
    for m in motions {
        let taught = positions.get(&(Kind::Robot, m.robot)).and_then(|p| p.tool);
        let Some((line, n)) = m.tool.map(|n| (m.line, n)).or(taught) else {
            continue;
        };
        let held = context
            .tool
            .and_then(|(setup, tools)| tools.get(n).map(|t| (setup, t)));
        if let Some((setup, held)) = held.filter(|(setup, held)| !same(setup, held)) {
            return Err(at(line, format!("tool file {n}, which the setup's [controller] tools gives as {}, is not the setup's tool ({}: its [tool] tcp_mm, after [robot_flange]); compensation moves the setup's tool: write the job for it", words(held), words(&setup))));
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
