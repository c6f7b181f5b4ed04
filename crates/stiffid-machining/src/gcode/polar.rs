//! LinuxCNC's polar coordinates: `@` the distance and `^` the angle (degrees, counter-clockwise
//! from +X about Z) of a block's X Y end point from the XY origin of the work offset in force, in
//! place of `X` and `Y` (LinuxCNC manual, "Polar Coordinates"; `interp_find.cc` `find_ends` and
//! `interp_cycles.cc` `convert_cycle_xy`). Under `G90` the two give the point, `@` alone keeps
//! the current point's angle and `^` alone its distance; under `G91` `@` adds to the current
//! point's distance from the origin and `^` to its angle (so `G91 @.5 ^90` spirals out, as the
//! manual shows). Refused naming the line: without `[controller] dialect = "linuxcnc"`, beside
//! `X` or `Y`, with `G53`, under cutter radius compensation, `@` alone or `G91` at the origin
//! (LinuxCNC refuses both), and from a current X Y not known.

use super::{at, GcodeDialect, State};
use stiffid_core::Result;

/// The block's `X Y` in `target` (the block's units; increments under `G91`) from its `@` and
/// `^` (`polar`); `g53`: the block has `G53`.
pub(super) fn resolve(
    line: u64,
    polar: [Option<f64>; 2],
    (target, g53): (&mut [Option<f64>; 3], bool),
    s: &State,
) -> Result<()> {
    let [radius, angle] = polar;
    if radius.is_none() && angle.is_none() {
        return Ok(());
    }
    let refuse = |why: &str| Err(at(line, format!("polar coordinates (@ ^): {why}")));
    if s.machine.dialect != Some(GcodeDialect::LinuxCnc) {
        return refuse("LinuxCNC's words, and the setup does not say LinuxCNC runs the program ([controller] dialect = \"linuxcnc\")");
    }
    if target[0].is_some() || target[1].is_some() {
        return refuse("X or Y beside them (LinuxCNC refuses the block)");
    }
    if g53 {
        return refuse("with G53 (LinuxCNC refuses the block)");
    }
    super::cutter::refuse_while_on(line, "polar coordinates (@ ^)", s)?;
    let scale = if s.inch { 25.4e-3 } else { 1e-3 };
    let (cx, cy) = (s.position.x / scale, s.position.y / scale);
    let needs_current = s.incremental || radius.is_none() || angle.is_none();
    if needs_current && !(s.known[0] && s.known[1]) {
        let known = [s.known[0], s.known[1], true];
        return refuse(&format!("from a place not known: {}", s.unknown(known)));
    }
    let at_origin = cx == 0.0 && cy == 0.0;
    let (x, y) = if s.incremental {
        if at_origin {
            return refuse(
                "G91 at the XY origin has no angle to add to (LinuxCNC refuses the block)",
            );
        }
        let r = cx.hypot(cy) + radius.unwrap_or(0.0);
        let t = cy.atan2(cx) + angle.unwrap_or(0.0).to_radians();
        (r * t.cos() - cx, r * t.sin() - cy)
    } else {
        if angle.is_none() && at_origin {
            return refuse("@ alone at the XY origin has no angle (LinuxCNC refuses the block)");
        }
        let r = radius.unwrap_or_else(|| cx.hypot(cy));
        let t = angle.map_or_else(|| cy.atan2(cx), f64::to_radians);
        (r * t.cos(), r * t.sin())
    };
    target[0] = Some(x);
    target[1] = Some(y);
    Ok(())
}
