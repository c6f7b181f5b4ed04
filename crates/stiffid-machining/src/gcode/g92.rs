//! `G92 X Y Z` on LinuxCNC and grbl: the coordinate system shifted so that the tool's position
//! reads the block's values on the axes it names (absolute, whatever the distance mode), every
//! work offset shifted alike, until `G92.1` or `G92.2` (LinuxCNC manual, G92; grbl `gcode.c`).
//! A robot cell knows where the tool is wherever the program has given it: the shift is that
//! position less the values, carried into every frame the program selects (module `modal`,
//! [`super::modal::frame`]). No shift is in force at the start (the setup's frames are read as
//! given: LinuxCNC keeps a `G92` shift across runs in its parameters, which programs clear with
//! `G92.1` first). Refused naming the line: `G92` on another dialect or none (FANUC's and Haas's
//! `G92` sets the work coordinate system by their own rules, on a FANUC lathe it is a spindle
//! speed limit), beside other words, without an axis word, on an axis whose position is not
//! known, under cutter radius compensation, and a `G10` while a shift is in force.

use super::machine::Frame;
use super::{at, GcodeDialect, State};
use nalgebra::{Translation3, Vector3};
use stiffid_core::Result;

/// A `G92` block of `target` (its `X Y Z` as written), `other`: other words beside it.
pub(super) fn set(
    line: u64,
    (target, other): ([Option<f64>; 3], bool),
    s: &mut State,
) -> Result<()> {
    let refuse = |why: &str| Err(at(line, format!("G92: {why}")));
    if !matches!(
        s.machine.dialect,
        Some(GcodeDialect::LinuxCnc | GcodeDialect::Grbl)
    ) {
        return refuse("read with [controller] dialect = \"linuxcnc\" or \"grbl\" (the coordinate system shifted so that the tool's position reads X Y Z); FANUC and Haas set their work coordinate system by their own rules");
    }
    if other {
        return refuse("write it in a block of its own (X Y Z only)");
    }
    if target.iter().all(Option::is_none) {
        return refuse("no axis word (LinuxCNC refuses it)");
    }
    super::cutter::refuse_while_on(line, "G92", s)?;
    let scale = if s.inch { 25.4e-3 } else { 1e-3 };
    let mut shift = s.g92;
    for (k, v) in target.iter().enumerate() {
        let Some(v) = v else { continue };
        if !s.known[k] {
            let mut known = [true; 3];
            known[k] = false;
            return refuse(&format!(
                "the tool's position is not known: {}",
                s.unknown(known)
            ));
        }
        if (v * scale).abs() > 100.0 {
            return refuse("a value beyond 100 m");
        }
        shift[k] += s.position[k] - v * scale;
    }
    shift_to(shift, s);
    Ok(())
}

/// `G92.1`, `G92.2`: no shift in force.
pub(super) fn cancel(s: &mut State) {
    shift_to(Vector3::zeros(), s);
}

/// The frame in force with the shift `shift` instead of the one before, the tool's position
/// carried (it does not move).
fn shift_to(shift: Vector3<f64>, s: &mut State) {
    let base = s.frame.part_from * Translation3::from(-s.g92);
    let frame = Frame {
        name: s.frame.name.clone(),
        part_from: base * Translation3::from(shift),
    };
    s.g92 = shift;
    s.set_frame(frame);
}
