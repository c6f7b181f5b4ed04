//! Cutter radius compensation `G41` (the tool left of the programmed path) and `G42` (right),
//! ended by `G40`, as LinuxCNC's interpreter runs it (LinuxCNC manual, "Cutter Compensation"
//! and G40-G42; `interp_convert.cc`, `convert_straight_comp1`/`comp2`), in the `G17` plane with
//! straight moves (`G0`, `G1`): the radius is the process's tool radius (`[tool] diameter_mm` /
//! 2) of the tool `D` names (LinuxCNC's `D` is a tool number), else of the tool in use.
//! - The entry, the first move in X or Y after `G41`/`G42`, ends where it is tangent to the
//!   circle of the radius around its programmed end (it must be longer than the radius).
//! - Each following move is its programmed line offset by the radius to its side. At an outside
//!   corner the tool goes around the programmed corner on an arc of the radius; at an inside
//!   corner the previous move ends, and this one starts, where the two offset lines meet (refused
//!   where they meet outside either move: the tool does not fit, LinuxCNC's gouging error).
//! - A move along `Z` alone keeps the tool where it is in X and Y.
//! - The move after `G40` goes from where the tool is to its programmed end (a straight move).
//!
//! Refused naming the line: `G41`/`G42` on a dialect other than LinuxCNC or without one (FANUC
//! and Haas start and turn corners their own ways, by settings), outside `G17`, an arc, a work
//! offset, tool length offset or plane changed, a canned cycle, `G28`/`G30` or `G53` while it is
//! on, `G41`/`G42` while it is on, a tool without a radius in the process.

use super::{at, GCode, State};
use nalgebra::Vector3;
use stiffid_core::setup::GcodeDialect;
use stiffid_core::Result;

/// The compensation in force.
#[derive(Debug, Clone, Default)]
pub(super) enum Comp {
    /// None (`G40`, the start).
    #[default]
    Off,
    /// `G41`/`G42` on: the side (+1 left, -1 right), the radius (m), its line, and the tool
    /// once the entry moved it.
    On {
        side: f64,
        radius: f64,
        line: u64,
        tool: Option<Tool>,
    },
    /// `G40` after the tool was offset: the next move goes to its programmed end.
    Exiting,
}

/// Where the compensated tool is, program coordinates of the plane, m.
#[derive(Debug, Clone)]
pub(super) struct Tool {
    xy: [f64; 2],
    z: f64,
    /// The direction of the last move in X Y (unit).
    dir: [f64; 2],
    /// Where that move started.
    from: [f64; 2],
    /// The index of its end point in the path, and whether a move along Z alone followed it.
    point: usize,
    z_since: bool,
}

/// The tool radius of tool `d` (else the tool in use), m.
fn radius(line: u64, d: Option<f64>, s: &State) -> Result<f64> {
    let n = match d {
        Some(d) if d.fract() == 0.0 && (0.0..=1e6).contains(&d) => Some(d as u32),
        Some(d) => {
            return Err(at(
                line,
                format!("D{d}: expected a tool number (LinuxCNC's D)"),
            ))
        }
        None => s.tool_number,
    };
    let radii = &s.machine.tool_radii;
    let exact = n.and_then(|n| radii.iter().find(|(t, _)| *t == Some(n)));
    let found = exact.or_else(|| radii.iter().find(|(t, _)| t.is_none()));
    found.map(|(_, r)| *r).ok_or_else(|| at(line, format!("cutter radius compensation needs the radius of tool {}: give the process an operation with its tool_number and [tool] diameter_mm", n.map_or("in use".to_string(), |n| n.to_string()))))
}

/// A `G40`, `G41` or `G42` (`code`) with its `D` on `line`.
pub(super) fn set(line: u64, code: u8, d: Option<f64>, s: &mut State) -> Result<()> {
    if code == 40 {
        s.comp = match s.comp {
            Comp::On { tool: Some(_), .. } => Comp::Exiting,
            _ => Comp::Off,
        };
        return Ok(());
    }
    match s.machine.dialect {
        Some(GcodeDialect::LinuxCnc) => {}
        Some(d) => return Err(at(line, format!("G{code} on the dialect \"{d}\": its entry move and corners are the controller's own (by its settings), which stiffid does not read; post the path of the tool centre (G40)"))),
        None => return Err(at(line, format!("G{code}: controllers enter cutter radius compensation and turn its corners differently; stiffid reads LinuxCNC's: state [controller] dialect = \"linuxcnc\" in the setup, or post the path of the tool centre (G40)"))),
    }
    if let Comp::On { line: on, .. } = s.comp {
        return Err(at(line, format!("G{code}: cutter radius compensation is on already (line {on}); LinuxCNC refuses it: G40 first")));
    }
    if s.plane != 17 {
        return Err(at(line, format!("G{code} in G{}: stiffid reads cutter radius compensation in the XY plane (G17) only", s.plane)));
    }
    let side = if code == 41 { 1.0 } else { -1.0 };
    let radius = radius(line, d, s)?;
    s.comp = Comp::On {
        side,
        radius,
        line,
        tool: None,
    };
    Ok(())
}

/// Refuses `what` (a frame, an offset, a cycle, ..) while the compensation is on.
pub(super) fn refuse_while_on(line: u64, what: &str, s: &State) -> Result<()> {
    match s.comp {
        Comp::On { line: on, .. } => Err(at(line, format!("{what} while cutter radius compensation is on (G41/G42 of line {on}): not read there; G40 first"))),
        _ => Ok(()),
    }
}

fn unit(a: [f64; 2]) -> Option<[f64; 2]> {
    let n = a[0].hypot(a[1]);
    (n > 1e-12).then(|| [a[0] / n, a[1] / n])
}

/// The move from `start` to `positions` (its programmed end, program coordinates, m) as the
/// compensated tool makes it (module docs): the positions to push, an earlier point moved for an
/// inside corner.
pub(super) fn apply(
    line: u64,
    start: Vector3<f64>,
    positions: Vec<Vector3<f64>>,
    tolerance: f64,
    s: &mut State,
    out: &mut GCode,
) -> Result<Vec<Vector3<f64>>> {
    let (side, r, tool) = match &s.comp {
        Comp::Off => return Ok(positions),
        Comp::Exiting => {
            if s.motion >= 2 {
                return Err(at(line, "an arc right after G40: LinuxCNC refuses it (the move that leaves cutter radius compensation is straight)".into()));
            }
            s.comp = Comp::Off;
            return Ok(positions);
        }
        Comp::On {
            side, radius, tool, ..
        } => (*side, *radius, tool.clone()),
    };
    if s.motion >= 2 {
        return Err(at(line, "an arc under cutter radius compensation (G41/G42): not read yet; post the path of the tool centre (G40)".into()));
    }
    let end = positions[positions.len() - 1];
    let (p, q) = ([start.x, start.y], [end.x, end.y]);
    let next = out.points.len();
    let Some(u) = unit([q[0] - p[0], q[1] - p[1]]) else {
        // Along Z alone: the tool stays where it is in X and Y.
        let Some(mut t) = tool else {
            return Ok(positions);
        };
        t.z_since = true;
        let xy = t.xy;
        set_tool(s, t);
        return Ok(vec![Vector3::new(xy[0], xy[1], end.z)]);
    };
    let Some(t) = tool else {
        let e = entry(line, p, q, side, r)?;
        let dir = unit([e[0] - p[0], e[1] - p[1]]).unwrap_or(u);
        set_tool(
            s,
            Tool {
                xy: e,
                z: end.z,
                dir,
                from: p,
                point: next,
                z_since: false,
            },
        );
        return Ok(vec![Vector3::new(e[0], e[1], end.z)]);
    };
    let t = &t;
    let n = [-u[1] * side * r, u[0] * side * r];
    let s0 = [p[0] + n[0], p[1] + n[1]];
    let q1 = [q[0] + n[0], q[1] + n[1]];
    let cross = t.dir[0] * u[1] - t.dir[1] * u[0];
    let dot = t.dir[0] * u[0] + t.dir[1] * u[1];
    let mut out_positions = Vec::new();
    let mut from = s0;
    if cross.abs() < 1e-9 && dot > 0.0 {
        // Straight on.
    } else if side * cross < 0.0 || cross.abs() < 1e-9 {
        // Outside: around the programmed corner on an arc of the radius.
        corner(
            p,
            (t.xy, s0),
            (side, r),
            tolerance,
            start.z,
            &mut out_positions,
        );
    } else {
        let x = inside(line, t, (s0, u), q1)?;
        if t.z_since {
            return Err(at(line, "an inside corner after a move along Z alone under cutter radius compensation: not read; give the corner's moves in X Y together".into()));
        }
        let moved = Vector3::new(x[0], x[1], t.z);
        out.points[t.point].position = s.tip(line, &moved, (&s.frame, s.lift()))?;
        from = x;
    }
    out_positions.push(Vector3::new(q1[0], q1[1], end.z));
    let point = next + out_positions.len() - 1;
    set_tool(
        s,
        Tool {
            xy: q1,
            z: end.z,
            dir: u,
            from,
            point,
            z_since: false,
        },
    );
    Ok(out_positions)
}

/// Where the compensated tool is now.
fn set_tool(s: &mut State, now: Tool) {
    if let Comp::On { tool, .. } = &mut s.comp {
        *tool = Some(now);
    }
}

/// LinuxCNC's entry: the point where the line from `c` is tangent to the circle of radius `r`
/// around the programmed end `p`, on the compensation's side.
fn entry(line: u64, c: [f64; 2], p: [f64; 2], side: f64, r: f64) -> Result<[f64; 2]> {
    let d = (p[0] - c[0]).hypot(p[1] - c[1]);
    if d <= r {
        return Err(at(line, format!("the move entering cutter radius compensation ({:.4} mm) is not longer than the tool radius ({:.4} mm): LinuxCNC refuses it", d * 1e3, r * 1e3)));
    }
    let theta = (r / d).acos();
    let alpha = (c[1] - p[1]).atan2(c[0] - p[0]) - side * theta;
    Ok([p[0] + r * alpha.cos(), p[1] + r * alpha.sin()])
}

/// The arc of radius `r` around `p` from `a` to `b` (the tool outside the corner: clockwise on
/// the left side), chords within `tolerance`, at height `z`; `b` included.
fn corner(
    p: [f64; 2],
    (a, b): ([f64; 2], [f64; 2]),
    (side, r): (f64, f64),
    tolerance: f64,
    z: f64,
    out: &mut Vec<Vector3<f64>>,
) {
    let two_pi = 2.0 * std::f64::consts::PI;
    let a0 = (a[1] - p[1]).atan2(a[0] - p[0]);
    let a1 = (b[1] - p[1]).atan2(b[0] - p[0]);
    let sweep = if side > 0.0 {
        -(a0 - a1).rem_euclid(two_pi)
    } else {
        (a1 - a0).rem_euclid(two_pi)
    };
    let step = 2.0 * (1.0 - (tolerance / r).min(1.0)).acos();
    let count = ((sweep.abs() / step.max(1e-6)).ceil() as usize).clamp(1, 100_000);
    for k in 1..=count {
        let angle = a0 + sweep * k as f64 / count as f64;
        let at = match k == count {
            true => b,
            false => [p[0] + r * angle.cos(), p[1] + r * angle.sin()],
        };
        out.push(Vector3::new(at[0], at[1], z));
    }
}

/// Where the previous offset line (through `t`, along its direction) meets this one (through
/// `s0` along `u`, to `q1`): refused outside either move.
fn inside(line: u64, t: &Tool, (s0, u): ([f64; 2], [f64; 2]), q1: [f64; 2]) -> Result<[f64; 2]> {
    let d = t.dir;
    let det = d[0] * (-u[1]) - d[1] * (-u[0]);
    let w = [s0[0] - t.xy[0], s0[1] - t.xy[1]];
    let a = (w[0] * (-u[1]) - w[1] * (-u[0])) / det;
    let b = (d[0] * w[1] - d[1] * w[0]) / det;
    let back = (t.xy[0] - t.from[0]).hypot(t.xy[1] - t.from[1]);
    let ahead = (q1[0] - s0[0]).hypot(q1[1] - s0[1]);
    if !(a.is_finite() && b.is_finite()) || a < -back - 1e-12 || b > ahead + 1e-12 {
        return Err(at(line, "the tool does not fit this inside corner under cutter radius compensation (the offset moves meet outside them: LinuxCNC's gouging error)".into()));
    }
    Ok([t.xy[0] + a * d[0], t.xy[1] + a * d[1]])
}
