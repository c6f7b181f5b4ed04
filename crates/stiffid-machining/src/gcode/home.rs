//! `G28` and `G30`: to the home position the setup states, as LinuxCNC runs them (its manual,
//! "G28, G28.1"): a rapid to the intermediate point the block's `X Y Z` give (in the distance
//! mode in force: `G28 G91 Z0` passes where the tool is), then the axes named (every axis when
//! none is) rapid to the home position's coordinates in the frame in force. The block is
//! written back as found: the controller goes where its own stored position is.

use super::machine::convert;
use super::modal::{end_point, push_points};
use super::{at, Block, GCode, Motion, State};
use nalgebra::Vector3;
use std::ops::Range;
use stiffid_core::Result;

/// Why a `G28`/`G30` before the tool's length is known leaves the axes it moves unknown.
const HOME_UNPLACED: &str = "a home return (G28/G30) there, while no tool length placed the tip in the program's coordinates";

/// A `G28`/`G30` block: its points added to `out`, its block kept as found.
pub(super) fn home(
    line: u64,
    span: Range<usize>,
    (target, other): ([Option<f64>; 3], bool),
    code: u8,
    s: &mut State,
    out: &mut GCode,
) -> Result<()> {
    let frames = &s.machine.frames;
    let Some(tip) = (if code == 28 { frames.g28 } else { frames.g30 }) else {
        return Err(at(line, format!("G{code}: the setup does not state the G{code} position: give where the tool tip is there, [workpiece] g{code}_mm (G54 part frame)")));
    };
    if other {
        return Err(at(
            line,
            format!("G{code}: only X Y Z (the intermediate point) are read with a move home"),
        ));
    }
    let first = out.points.len();
    let named = target.map(|t| t.is_some());
    let Some(to_program) = s.to_program() else {
        // The tip goes home, but where that is in the program's coordinates depends on the
        // tool's length, not known yet: the axes moved are not known until the program
        // gives them (module docs of `modal`).
        s.pending.get_or_insert(line);
        let moved = named.map(|n| n || !named.iter().any(|n| *n));
        s.leave_unknown(line, moved, HOME_UNPLACED);
        return Ok(());
    };
    let home = to_program * nalgebra::Point3::from(tip);
    if named.iter().any(|n| *n) {
        let (end, known) = end_point(line, &target, (s.position, s.known), s)?;
        // An intermediate point where the tool is (`G28 G91 Z0`) is no move.
        if known != s.known || (end - s.position).norm() > 0.0 {
            rapid(line, (end, known), s, out)?;
        }
    }
    let (mut end, mut known) = (s.position, s.known);
    for k in 0..3 {
        if named[k] || !named.iter().any(|n| *n) {
            (end[k], known[k]) = (home[k], true);
        }
    }
    rapid(line, (end, known), s, out)?;
    out.blocks.push(Block {
        line: span,
        points: first..out.points.len(),
        drop: Vec::new(),
        external_words: Vec::new(),
        arc_word: None,
        spline: false,
        inch: s.inch,
        incremental: s.incremental,
        to_program,
        verbatim: true,
        take_up: 0.0,
        cycle: None,
    });
    Ok(())
}

/// A rapid to `end` in the frame in force: a point when every axis is known, else none yet.
fn rapid(
    line: u64,
    (end, known): (Vector3<f64>, [bool; 3]),
    s: &mut State,
    out: &mut GCode,
) -> Result<()> {
    if known.iter().all(|k| *k) {
        let frame = s.frame.clone();
        let lift = s.lift();
        push_points(line, &[end], Motion::Rapid, (&frame, lift), s, out)?;
    } else {
        s.pending.get_or_insert(line);
    }
    let lift = s.lift();
    (s.position, s.known) = convert((end, known), (&s.frame, lift), (&s.frame, lift));
    Ok(())
}
