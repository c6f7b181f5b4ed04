//! Cutter radius compensation `G41` (the tool left of the programmed path) and `G42` (right),
//! ended by `G40`, as LinuxCNC's interpreter runs it (LinuxCNC manual, "Cutter Compensation"
//! and G40-G42; `interp_convert.cc`, `convert_straight_comp1`/`comp2`, `convert_arc_comp2`), in
//! the `G17` plane and in `G18` (its `Z X` coordinates as LinuxCNC's `comp_get_current`): the radius is the process's tool radius (`[tool] diameter_mm` / 2) of the
//! tool `D` names (LinuxCNC's `D` is a tool number), else of the tool in use, plus the wear the
//! setup's `[controller] radius_wear_mm` gives for that number (a controller's wear offset).
//! - The entry, the first move in X or Y after `G41`/`G42`: a straight one ends where it is
//!   tangent to the circle of the radius around its programmed end (it must be longer than the
//!   radius); an arc (`convert_arc_comp1`) goes from where the tool is to its programmed end
//!   moved by the radius along the arc's radius (toward the centre where the tool is inside the
//!   arc), on the circle through both about a centre on that radius.
//! - Each following straight move is its programmed line offset by the radius to its side; an
//!   arc is its programmed arc offset by the radius (concentric: its radius less the tool's where
//!   the tool is on the centre's side, `G41` with `G3`, `G42` with `G2`, else more; refused where
//!   the tool's radius is not less than the arc's). At an outside corner the tool goes around the
//!   programmed corner on an arc of the radius; at an inside corner the previous move ends, and
//!   this one starts, where the two offset paths meet (line and line, line and circle, circle and
//!   circle; refused where they meet outside either move: the tool does not fit, LinuxCNC's
//!   gouging error). A previous arc ended early keeps its number of points along its shorter
//!   sweep (module `piece`).
//! - A move along `Z` alone keeps the tool where it is in X and Y.
//! - The move after `G40` goes from where the tool is to its programmed end (a straight move).
//!
//! Refused naming the line: `G41`/`G42` on a dialect other than LinuxCNC or without one (FANUC
//! and Haas start and turn corners their own ways, by settings), in `G19`, an arc right
//! after `G40`, a work offset, tool length offset or plane changed, a canned
//! cycle, `G28`/`G30` or `G53` while it is on, `G41`/`G42` while it is on, a tool without a
//! radius in the process.

mod piece;

use super::{at, GCode, State};
use nalgebra::Vector3;
use piece::{Piece, Shape};
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
    /// The direction of the last move in X Y at its end (unit).
    dir: [f64; 2],
    /// Where that move started.
    from: [f64; 2],
    /// The index of its end point in the path, and whether a move along Z alone followed it.
    point: usize,
    z_since: bool,
    /// The last move's offset path (a line, or an arc and its points).
    shape: Shape,
}

/// The radius of tool `d` (else the tool in use) with its wear, m (module docs).
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
    let r = found.map(|(_, r)| *r).ok_or_else(|| at(line, format!("cutter radius compensation needs the radius of tool {}: give the process an operation with its tool_number and [tool] diameter_mm", n.map_or("in use".to_string(), |n| n.to_string()))))?;
    let wear = n.and_then(|n| s.machine.radius_wear.iter().find(|(t, _)| *t == n));
    let r = r + wear.map_or(0.0, |(_, w)| *w);
    if r <= 0.0 {
        return Err(at(
            line,
            format!(
                "the tool's radius with its wear is {:.4} mm: not a radius to offset by",
                r * 1e3
            ),
        ));
    }
    Ok(r)
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
    if s.plane == 19 {
        return Err(at(line, format!("G{code} in G19: LinuxCNC reads cutter radius compensation in the XY (G17) and ZX (G18) planes only, and refuses it in G19")));
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

pub(super) fn unit(a: [f64; 2]) -> Option<[f64; 2]> {
    let n = a[0].hypot(a[1]);
    (n > 1e-12).then(|| [a[0] / n, a[1] / n])
}

/// The move from `start` to `positions` (its programmed end, program coordinates, m; an arc
/// about `centre`, program coordinates of the plane) as the compensated tool makes it (module
/// docs): the positions to push, an earlier move's end moved for an inside corner.
pub(super) fn apply(
    line: u64,
    start: Vector3<f64>,
    (positions, centre): (Vec<Vector3<f64>>, Option<[f64; 2]>),
    tolerance: f64,
    s: &mut State,
    out: &mut GCode,
) -> Result<Vec<Vector3<f64>>> {
    if matches!(s.comp, Comp::Off) {
        return Ok(positions);
    }
    // In the plane's coordinates (G18: Z X, then Y), as LinuxCNC's comp_get_current.
    let (u, v, n) = super::arc::plane_axes(s.plane);
    let to = |p: &Vector3<f64>| Vector3::new(p[u], p[v], p[n]);
    let positions = positions.iter().map(to).collect();
    let pts = in_plane(line, to(&start), (positions, centre), tolerance, s, out)?;
    Ok(pts.iter().map(|p| from_plane(s.plane, p)).collect())
}

/// A point of the plane's coordinates (`apply`) in the program's `X Y Z`.
pub(super) fn from_plane(plane: u8, p: &Vector3<f64>) -> Vector3<f64> {
    let (u, v, n) = super::arc::plane_axes(plane);
    let mut q = Vector3::zeros();
    (q[u], q[v], q[n]) = (p.x, p.y, p.z);
    q
}

/// [`apply`] in the plane's coordinates.
fn in_plane(
    line: u64,
    start: Vector3<f64>,
    (positions, centre): (Vec<Vector3<f64>>, Option<[f64; 2]>),
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
    let end = positions[positions.len() - 1];
    let (p, q) = ([start.x, start.y], [end.x, end.y]);
    let next = out.points.len();
    if centre.is_none() && unit([q[0] - p[0], q[1] - p[1]]).is_none() {
        // Along Z alone: the tool stays where it is in X and Y.
        let Some(mut t) = tool else {
            return Ok(positions);
        };
        t.z_since = true;
        let xy = t.xy;
        set_tool(s, t);
        return Ok(vec![Vector3::new(xy[0], xy[1], end.z)]);
    }
    let Some(t) = tool else {
        if let Some(c) = centre {
            return arc_entry(
                line,
                (p, q, c),
                (start.z, end.z),
                (side, r, tolerance),
                s,
                next,
            );
        }
        let e = entry(line, p, q, side, r)?;
        let dir = unit([e[0] - p[0], e[1] - p[1]]).unwrap_or([1.0, 0.0]);
        let shape = Shape::Line;
        set_tool(
            s,
            Tool {
                xy: e,
                z: end.z,
                dir,
                from: p,
                point: next,
                z_since: false,
                shape,
            },
        );
        return Ok(vec![Vector3::new(e[0], e[1], end.z)]);
    };
    let piece = match centre {
        Some(c) => Piece::arc(line, (p, q, c), s.motion == 3, (side, r))?,
        None => Piece::line(p, q, (side, r)),
    };
    let mut pts = Vec::new();
    let from = turn(
        line,
        &t,
        &piece,
        (p, start.z),
        (side, r, tolerance),
        s,
        out,
        &mut pts,
    )?;
    let first = next + pts.len();
    let shape = piece.points(from, (start.z, end.z), tolerance, &mut pts);
    let shape = shape.with_first(first);
    let point = next + pts.len() - 1;
    let (xy, dir) = (piece.end_point(), piece.end_tangent());
    set_tool(
        s,
        Tool {
            xy,
            z: end.z,
            dir,
            from,
            point,
            z_since: false,
            shape,
        },
    );
    Ok(pts)
}

/// The corner from the last move `t` into `piece` at the programmed corner `p` (its `z`): an
/// outside corner's arc pushed to `pts`, an inside corner's earlier end moved; where the piece
/// starts.
#[allow(clippy::too_many_arguments)]
fn turn(
    line: u64,
    t: &Tool,
    piece: &Piece,
    (p, z): ([f64; 2], f64),
    (side, r, tolerance): (f64, f64, f64),
    s: &mut State,
    out: &mut GCode,
    pts: &mut Vec<Vector3<f64>>,
) -> Result<[f64; 2]> {
    let (u, s0) = (piece.start_tangent(), piece.start_point());
    let cross = t.dir[0] * u[1] - t.dir[1] * u[0];
    let dot = t.dir[0] * u[0] + t.dir[1] * u[1];
    if cross.abs() < 1e-9 && dot > 0.0 {
        // Straight on (a tangent junction).
        return Ok(s0);
    }
    if side * cross < 0.0 || cross.abs() < 1e-9 {
        // Outside: around the programmed corner on an arc of the radius.
        piece::corner(p, (t.xy, s0), (side, r), tolerance, z, pts);
        return Ok(s0);
    }
    if t.z_since {
        return Err(at(line, "an inside corner after a move along Z alone under cutter radius compensation: not read; give the corner's moves in X Y together".into()));
    }
    let x = piece::meet(line, t, piece, p)?;
    piece::move_end(line, t, x, s, out)?;
    Ok(x)
}

/// LinuxCNC's arc entry (`Piece::entry`) from `p` to the programmed end `q` about `c`, its
/// height from `z0` to `z1`: its points, the first of index `next` in the path.
fn arc_entry(
    line: u64,
    (p, q, c): ([f64; 2], [f64; 2], [f64; 2]),
    (z0, z1): (f64, f64),
    (side, r, tolerance): (f64, f64, f64),
    s: &mut State,
    next: usize,
) -> Result<Vec<Vector3<f64>>> {
    let piece = Piece::entry(line, (p, q, c), s.motion == 3, (side, r))?;
    let mut pts = Vec::new();
    let shape = piece
        .points(p, (z0, z1), tolerance, &mut pts)
        .with_first(next);
    let tool = Tool {
        xy: piece.end_point(),
        z: z1,
        dir: piece.end_tangent(),
        from: p,
        point: next + pts.len() - 1,
        z_since: false,
        shape,
    };
    set_tool(s, tool);
    Ok(pts)
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
