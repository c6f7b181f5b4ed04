//! The offset path of one compensated move (a line, or an arc concentric with the programmed
//! one), the corners between two (LinuxCNC's `convert_straight_comp2`/`convert_arc_comp2`: an
//! arc of the tool's radius outside, the offset paths' meeting point inside) and an earlier move
//! ended there.

use super::super::{at, GCode, State};
use super::{unit, Tool};
use nalgebra::Vector3;
use std::f64::consts::TAU;
use stiffid_core::Result;

/// A move's offset path as far as the next corner needs it.
#[derive(Debug, Clone)]
pub(in crate::gcode) enum Shape {
    /// A straight move (from the tool's `from` to its `xy`).
    Line,
    /// An arc about `centre` from the angle `start` through `sweep` (signed: positive
    /// counter-clockwise), its radius from `r0` to `r1`, its height from `z0`, its points from
    /// index `first` to the tool's `point`.
    Arc {
        centre: [f64; 2],
        start: f64,
        sweep: f64,
        r0: f64,
        r1: f64,
        z0: f64,
        first: usize,
    },
}

impl Shape {
    /// The shape with its first point's index.
    pub(super) fn with_first(self, index: usize) -> Self {
        match self {
            Shape::Arc {
                centre,
                start,
                sweep,
                r0,
                r1,
                z0,
                ..
            } => Shape::Arc {
                centre,
                start,
                sweep,
                r0,
                r1,
                z0,
                first: index,
            },
            line => line,
        }
    }
}

/// This move's offset path.
pub(super) enum Piece {
    Line {
        s0: [f64; 2],
        q1: [f64; 2],
        u: [f64; 2],
    },
    Arc {
        c: [f64; 2],
        ccw: bool,
        a0: f64,
        sweep: f64,
        r0: f64,
        r1: f64,
        s0: [f64; 2],
        q1: [f64; 2],
    },
}

fn angle(c: [f64; 2], p: [f64; 2]) -> f64 {
    (p[1] - c[1]).atan2(p[0] - c[0])
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// The angle from `a0` to `a` turning the arc's way (`ccw`), in `[0, 2 pi)`.
fn along(a0: f64, a: f64, ccw: bool) -> f64 {
    let d = if ccw { a - a0 } else { a0 - a };
    let d = d.rem_euclid(TAU);
    if TAU - d < 1e-12 {
        0.0
    } else {
        d
    }
}

impl Piece {
    /// The straight move from `p` to `q` offset by `r` to its `side`.
    pub(super) fn line(p: [f64; 2], q: [f64; 2], (side, r): (f64, f64)) -> Self {
        let u = unit([q[0] - p[0], q[1] - p[1]]).unwrap_or([1.0, 0.0]);
        let n = [-u[1] * side * r, u[0] * side * r];
        Piece::Line {
            s0: [p[0] + n[0], p[1] + n[1]],
            q1: [q[0] + n[0], q[1] + n[1]],
            u,
        }
    }

    /// The arc from `p` to `q` about `c` (counter-clockwise: `ccw`) offset by `r` to its `side`:
    /// concentric, its radius less `r` where the tool is on the centre's side.
    pub(super) fn arc(
        line: u64,
        (p, q, c): ([f64; 2], [f64; 2], [f64; 2]),
        ccw: bool,
        (side, r): (f64, f64),
    ) -> Result<Self> {
        let (big0, big1) = (dist(p, c), dist(q, c));
        let k = if ccw { side } else { -side };
        let (r0, r1) = (big0 - k * r, big1 - k * r);
        if r0.min(r1) <= 1e-9 {
            return Err(at(line, format!("the tool's radius ({:.4} mm) is not less than the arc's ({:.4} mm) on the side it cuts: LinuxCNC refuses it (the tool does not fit)", r * 1e3, big0.min(big1) * 1e3)));
        }
        let a0 = angle(c, p);
        let mut sweep = along(a0, angle(c, q), ccw);
        if sweep < 1e-12 {
            sweep = TAU;
        }
        let sweep = if ccw { sweep } else { -sweep };
        let at_r = |x: [f64; 2], big: f64, small: f64| {
            [
                c[0] + (x[0] - c[0]) * small / big,
                c[1] + (x[1] - c[1]) * small / big,
            ]
        };
        Ok(Piece::Arc {
            c,
            ccw,
            a0,
            sweep,
            r0,
            r1,
            s0: at_r(p, big0, r0),
            q1: at_r(q, big1, r1),
        })
    }

    /// LinuxCNC's arc entering the compensation (`convert_arc_comp1`): from where the tool is,
    /// `p`, to the programmed end `q` moved by `r` along its radius (toward the centre `c` where
    /// the tool is inside the arc, `G41` with `G3`, `G42` with `G2`), about the centre on that
    /// radius that is as far from both ends (a circle, its radius changed).
    pub(super) fn entry(
        line: u64,
        (p, q, c): ([f64; 2], [f64; 2], [f64; 2]),
        ccw: bool,
        (side, r): (f64, f64),
    ) -> Result<Self> {
        if dist(p, q) <= r {
            return Err(at(line, format!("the arc entering cutter radius compensation ({:.4} mm from its start to its end) is not longer than the tool radius ({:.4} mm): LinuxCNC refuses it", dist(p, q) * 1e3, r * 1e3)));
        }
        let inside = (side > 0.0) == ccw;
        if inside && dist(p, c) <= r {
            return Err(at(line, format!("the tool's radius ({:.4} mm) is not less than the entry arc's ({:.4} mm) on the side it cuts: LinuxCNC refuses it", r * 1e3, dist(p, c) * 1e3)));
        }
        let gamma = if inside { angle(q, c) } else { angle(c, q) };
        let e = [q[0] + r * gamma.cos(), q[1] + r * gamma.sin()];
        let (ab, a) = (angle(e, c), angle(e, p) - angle(e, c));
        if a.cos().abs() < 1e-12 {
            return Err(at(line, "the arc entering cutter radius compensation has no circle from where the tool is to its compensated end: LinuxCNC refuses it (tool radius not less than the arc radius)".into()));
        }
        let len = dist(p, e) / 2.0 / a.cos();
        let n = [e[0] + len * ab.cos(), e[1] + len * ab.sin()];
        let a0 = angle(n, p);
        let mut sweep = along(a0, angle(n, e), ccw);
        if sweep < 1e-12 {
            sweep = TAU;
        }
        let rr = dist(n, e);
        Ok(Piece::Arc {
            c: n,
            ccw,
            a0,
            sweep: if ccw { sweep } else { -sweep },
            r0: dist(n, p),
            r1: rr,
            s0: p,
            q1: e,
        })
    }

    pub(super) fn start_point(&self) -> [f64; 2] {
        match self {
            Piece::Line { s0, .. } | Piece::Arc { s0, .. } => *s0,
        }
    }

    pub(super) fn end_point(&self) -> [f64; 2] {
        match self {
            Piece::Line { q1, .. } | Piece::Arc { q1, .. } => *q1,
        }
    }

    pub(super) fn start_tangent(&self) -> [f64; 2] {
        match self {
            Piece::Line { u, .. } => *u,
            Piece::Arc { a0, ccw, .. } => tangent(*a0, *ccw),
        }
    }

    pub(super) fn end_tangent(&self) -> [f64; 2] {
        match self {
            Piece::Line { u, .. } => *u,
            Piece::Arc { a0, sweep, ccw, .. } => tangent(a0 + sweep, *ccw),
        }
    }

    /// The piece's points from `from` (its start, or an inside corner's meeting point on it),
    /// its height from `z0` to `z1`, chords within `tolerance`: pushed to `out`; its shape.
    pub(super) fn points(
        &self,
        from: [f64; 2],
        (z0, z1): (f64, f64),
        tolerance: f64,
        out: &mut Vec<Vector3<f64>>,
    ) -> Shape {
        let (c, ccw, sweep, r1, q1) = match self {
            Piece::Line { q1, .. } => {
                out.push(Vector3::new(q1[0], q1[1], z1));
                return Shape::Line;
            }
            Piece::Arc {
                c,
                ccw,
                sweep,
                r1,
                q1,
                a0,
                ..
            } => {
                let done = along(*a0, angle(*c, from), *ccw);
                let left = sweep.abs() - done;
                (*c, *ccw, if *ccw { left } else { -left }, *r1, *q1)
            }
        };
        let (start, rf) = (angle(c, from), dist(from, c));
        let step = 2.0 * (1.0 - (tolerance / rf.max(r1)).min(1.0)).acos();
        let count = ((sweep.abs() / step.max(1e-6)).ceil() as usize).clamp(1, 100_000);
        for i in 1..=count {
            let f = i as f64 / count as f64;
            let (a, r) = (start + sweep * f, rf + (r1 - rf) * f);
            let xy = if i == count {
                q1
            } else {
                [c[0] + r * a.cos(), c[1] + r * a.sin()]
            };
            out.push(Vector3::new(xy[0], xy[1], z0 + (z1 - z0) * f));
        }
        let _ = ccw;
        Shape::Arc {
            centre: c,
            start,
            sweep,
            r0: rf,
            r1,
            z0,
            first: 0,
        }
    }
}

/// The unit tangent of an arc at the angle `a`, turning counter-clockwise (`ccw`) or not.
fn tangent(a: f64, ccw: bool) -> [f64; 2] {
    let t = [-a.sin(), a.cos()];
    if ccw {
        t
    } else {
        [-t[0], -t[1]]
    }
}

/// The arc of radius `r` around `p` from `a` to `b` (the tool outside the corner: clockwise on
/// the left side), chords within `tolerance`, at height `z`; `b` included.
pub(super) fn corner(
    p: [f64; 2],
    (a, b): ([f64; 2], [f64; 2]),
    (side, r): (f64, f64),
    tolerance: f64,
    z: f64,
    out: &mut Vec<Vector3<f64>>,
) {
    let a0 = angle(p, a);
    let sweep = if side > 0.0 {
        -along(a0, angle(p, b), false)
    } else {
        along(a0, angle(p, b), true)
    };
    let step = 2.0 * (1.0 - (tolerance / r).min(1.0)).acos();
    let count = ((sweep.abs() / step.max(1e-6)).ceil() as usize).clamp(1, 100_000);
    for k in 1..=count {
        let a = a0 + sweep * k as f64 / count as f64;
        let at = if k == count {
            b
        } else {
            [p[0] + r * a.cos(), p[1] + r * a.sin()]
        };
        out.push(Vector3::new(at[0], at[1], z));
    }
}

/// The points where the line through `o` along the unit `d` meets the circle about `c` of
/// radius `r`: their distances along `d` (a tangent line's, to rounding, as one point).
fn line_circle(o: [f64; 2], d: [f64; 2], c: [f64; 2], r: f64) -> Option<[f64; 2]> {
    let w = [o[0] - c[0], o[1] - c[1]];
    let b = w[0] * d[0] + w[1] * d[1];
    let disc = b * b - (w[0] * w[0] + w[1] * w[1] - r * r);
    let disc = if disc < 0.0 && disc > -1e-9 * r * r {
        0.0
    } else {
        disc
    };
    (disc >= 0.0).then(|| [-b - disc.sqrt(), -b + disc.sqrt()])
}

/// Where the circles about `c1` (radius `r1`) and `c2` (`r2`) meet.
fn circle_circle(c1: [f64; 2], r1: f64, c2: [f64; 2], r2: f64) -> Option<[[f64; 2]; 2]> {
    let d = dist(c1, c2);
    if d < 1e-12 {
        return None;
    }
    let a = (r1 * r1 - r2 * r2 + d * d) / (2.0 * d);
    let h2 = r1 * r1 - a * a;
    let h = if h2 < 0.0 && h2 > -1e-9 * r1 * r1 {
        0.0
    } else {
        h2.sqrt()
    };
    if !h.is_finite() {
        return None;
    }
    let e = [(c2[0] - c1[0]) / d, (c2[1] - c1[1]) / d];
    let m = [c1[0] + a * e[0], c1[1] + a * e[1]];
    Some([
        [m[0] - h * e[1], m[1] + h * e[0]],
        [m[0] + h * e[1], m[1] - h * e[0]],
    ])
}

/// Whether `x` (on the tool's last offset path) lies on it, back from its end.
fn on_last(t: &Tool, x: [f64; 2]) -> bool {
    match &t.shape {
        Shape::Line => {
            let back = dist(t.xy, t.from);
            let a = (x[0] - t.xy[0]) * t.dir[0] + (x[1] - t.xy[1]) * t.dir[1];
            a <= 1e-12 && a >= -back - 1e-12
        }
        Shape::Arc {
            centre,
            start,
            sweep,
            ..
        } => along(*start, angle(*centre, x), *sweep > 0.0) <= sweep.abs() + 1e-12,
    }
}

/// Whether `x` lies on `piece`, from its start.
fn on_piece(piece: &Piece, x: [f64; 2]) -> bool {
    match piece {
        Piece::Line { s0, q1, u } => {
            let b = (x[0] - s0[0]) * u[0] + (x[1] - s0[1]) * u[1];
            b >= -1e-12 && b <= dist(*s0, *q1) + 1e-12
        }
        Piece::Arc {
            c, ccw, a0, sweep, ..
        } => along(*a0, angle(*c, x), *ccw) <= sweep.abs() + 1e-12,
    }
}

/// Where the last offset path `t` and `piece` meet at the inside corner `p` (the meeting point
/// nearest the corner); refused where they do not meet on both (LinuxCNC's gouging error).
pub(super) fn meet(line: u64, t: &Tool, piece: &Piece, p: [f64; 2]) -> Result<[f64; 2]> {
    let along_line = |o: [f64; 2], d: [f64; 2], roots: [f64; 2]| {
        roots.map(|k| [o[0] + k * d[0], o[1] + k * d[1]])
    };
    let candidates: Vec<[f64; 2]> = match (&t.shape, piece) {
        (Shape::Line, Piece::Line { s0, u, .. }) => {
            let (d, w) = (t.dir, [s0[0] - t.xy[0], s0[1] - t.xy[1]]);
            let det = -d[0] * u[1] + d[1] * u[0];
            let a = (-w[0] * u[1] + w[1] * u[0]) / det;
            vec![[t.xy[0] + a * t.dir[0], t.xy[1] + a * t.dir[1]]]
        }
        (Shape::Line, Piece::Arc { c, r0, .. }) => line_circle(t.xy, t.dir, *c, *r0)
            .map_or(vec![], |r| along_line(t.xy, t.dir, r).to_vec()),
        (Shape::Arc { centre, r1, .. }, Piece::Line { s0, u, .. }) => {
            line_circle(*s0, *u, *centre, *r1).map_or(vec![], |r| along_line(*s0, *u, r).to_vec())
        }
        (Shape::Arc { centre, r1, .. }, Piece::Arc { c, r0, .. }) => {
            circle_circle(*centre, *r1, *c, *r0).map_or(vec![], |x| x.to_vec())
        }
    };
    let nearest = candidates
        .into_iter()
        .filter(|x| x.iter().all(|v| v.is_finite()))
        .min_by(|a, b| dist(*a, p).total_cmp(&dist(*b, p)));
    match nearest {
        Some(x) if on_last(t, x) && on_piece(piece, x) => Ok(x),
        _ => Err(at(line, "the tool does not fit this inside corner under cutter radius compensation (the offset moves meet outside them: LinuxCNC's gouging error)".into())),
    }
}

/// The last move `t` ended at `x` (an inside corner): its end point moved there, an arc's
/// points spread along its shorter sweep.
pub(super) fn move_end(line: u64, t: &Tool, x: [f64; 2], s: &State, out: &mut GCode) -> Result<()> {
    let frame = (&s.frame, s.lift());
    let Shape::Arc {
        centre,
        start,
        sweep,
        r0,
        z0,
        first,
        ..
    } = &t.shape
    else {
        let moved = super::from_plane(s.plane, &Vector3::new(x[0], x[1], t.z));
        out.points[t.point].position = s.tip(line, &moved, frame)?;
        return Ok(());
    };
    let ccw = *sweep > 0.0;
    let done = along(*start, angle(*centre, x), ccw);
    let shorter = if ccw { done } else { -done };
    let (n, rx) = (t.point + 1 - first, dist(x, *centre));
    for i in 1..=n {
        let f = i as f64 / n as f64;
        let (a, r) = (start + shorter * f, r0 + (rx - r0) * f);
        let xy = if i == n {
            x
        } else {
            [centre[0] + r * a.cos(), centre[1] + r * a.sin()]
        };
        let moved = super::from_plane(s.plane, &Vector3::new(xy[0], xy[1], z0 + (t.z - z0) * f));
        out.points[first + i - 1].position = s.tip(line, &moved, frame)?;
    }
    Ok(())
}
