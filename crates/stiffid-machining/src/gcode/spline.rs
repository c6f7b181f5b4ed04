//! LinuxCNC's quadratic B-spline `G5.1 X Y I J` (the curve from where the tool is, through the
//! control point `I J` from there, to `X Y`), flattened as LinuxCNC's motion planner runs it:
//! `NURBS_FEED` (`src/emc/task/emccanon.cc`, LinuxCNC 2.9 and master) evaluates the curve and its
//! tangent at 12 steps of its parameter (4 per control point) and joins each two by a biarc
//! (`biarc`, `arc`: two circular arcs meeting tangentially, each run as an `ARC_FEED`), whose
//! arcs stiffid splits into chords as any arc ([`super::arc::chords`]). `Z` stays where it is.
//! Refused naming the line as LinuxCNC refuses it (`interp_convert.cc` `convert_spline`: outside
//! `G17`, with `Z`, `A B C` or cutter radius compensation, without both `I` and `J`) and where
//! LinuxCNC's biarc finds no solution (it would leave that step out); on other dialects, and
//! without one, `G5.1` is refused (FANUC's `G5.1` is AI contour control, another thing).

use super::arc::chords;
use super::{at, GcodeDialect, State};
use nalgebra::Vector3;
use stiffid_core::Result;

/// The motion mode `G5.1` (`State::motion`).
pub(super) const SPLINE: u8 = 51;

/// The steps of the curve's parameter (LinuxCNC's `div`: 4 per control point).
const DIVISIONS: u32 = 12;
/// The step of the tangent's difference quotient (LinuxCNC's `nurbs_tangent` `DU`).
const DU: f64 = 1e-5;
/// LinuxCNC's `CART_FUZZ`: a biarc's `beta` above its inverse is run as a line.
const CART_FUZZ: f64 = 1e-8;
/// Below this (program units) an arc of a biarc is run as a line (LinuxCNC's `arc` `small`).
const SMALL: f64 = 1e-6;

/// What a `G5.1` block gives beside its end point.
pub(super) struct Words {
    /// `I`, `J`: the control point from the start, as written (the program's units).
    pub ij: [Option<f64>; 2],
    /// `Z`, `K`, `R`, `P`, rotary or external axis words, `G53`: none belongs to `G5.1`.
    pub other: Option<&'static str>,
}

/// The points of the spline from `s.position` to `end` (m, the frame in force), chords within
/// `tolerance`.
pub(super) fn points(
    line: u64,
    w: &Words,
    end: Vector3<f64>,
    s: &State,
    tolerance: f64,
) -> Result<Vec<Vector3<f64>>> {
    let refuse = |why: &str| Err(at(line, format!("G5.1: {why}")));
    if s.machine.dialect != Some(GcodeDialect::LinuxCnc) {
        return refuse("LinuxCNC's quadratic spline, read only with [controller] dialect = \"linuxcnc\" (FANUC's G5.1 is AI contour control, a mode that moves nothing)");
    }
    if s.plane != 17 {
        return refuse("a spline outside the G17 plane (LinuxCNC refuses it)");
    }
    if let Some(what) = w.other {
        return refuse(&format!("{what} beside a spline (LinuxCNC refuses it)"));
    }
    super::cutter::refuse_while_on(line, "G5.1: a spline", s)?;
    let (Some(i), Some(j)) = (w.ij[0], w.ij[1]) else {
        return refuse("give both I and J, the control point from the start (LinuxCNC refuses the block without them)");
    };
    let scale = if s.inch { 25.4e-3 } else { 1e-3 };
    // LinuxCNC's numbers are the program's units.
    let p0 = [s.position.x / scale, s.position.y / scale];
    if i.abs().max(j.abs()) * scale > 100.0 {
        return refuse("a control point beyond 100 m");
    }
    let control = [p0[0] + i, p0[1] + j];
    let p2 = [end.x / scale, end.y / scale];
    if i == 0.0 && j == 0.0 && p2 == p0 {
        return refuse("a spline of no length");
    }
    let curve = [p0, control, p2];
    let mut out = Vec::new();
    let (mut a, mut ta) = (point(&curve, 0.0), tangent(&curve, 0.0));
    for k in 1..=DIVISIONS {
        let u = f64::from(k) / f64::from(DIVISIONS);
        let (b, tb) = (point(&curve, u), tangent(&curve, u));
        for (to, centre) in biarc(a, ta, b, tb).ok_or_else(|| at(line, "G5.1: LinuxCNC's biarc between two points of the spline has no solution there (LinuxCNC would leave that step out); write the spline as G1 or G2/G3 moves".into()))? {
            let from = out.last().copied().unwrap_or(s.position);
            let to = Vector3::new(to[0] * scale, to[1] * scale, s.position.z);
            match centre {
                Some((c, ccw)) => {
                    let c = [c[0] * scale, c[1] * scale];
                    out.extend(chords(line, (from, to), c, ccw, 17, tolerance)?);
                }
                None => out.push(to),
            }
        }
        (a, ta) = (b, tb);
    }
    // The last biarc ends at the curve's end to rounding: the block's end exactly.
    if let Some(last) = out.last_mut() {
        *last = Vector3::new(end.x, end.y, s.position.z);
    }
    Ok(out)
}

/// The quadratic Bézier (LinuxCNC's `nurbs_point` of three control points, weights 1) at `u`.
fn point(c: &[[f64; 2]; 3], u: f64) -> [f64; 2] {
    let (b0, b1, b2) = ((1.0 - u) * (1.0 - u), 2.0 * u * (1.0 - u), u * u);
    [0, 1].map(|k| c[0][k] * b0 + c[1][k] * b1 + c[2][k] * b2)
}

/// The curve's unit tangent at `u` by LinuxCNC's difference quotient (`nurbs_tangent`).
fn tangent(c: &[[f64; 2]; 3], u: f64) -> [f64; 2] {
    let (lo, hi) = ((u - DU).max(0.0), (u + DU).min(1.0));
    let (p, q) = (point(c, lo), point(c, hi));
    unit([(q[0] - p[0]) / (hi - lo), (q[1] - p[1]) / (hi - lo)])
}

fn unit(v: [f64; 2]) -> [f64; 2] {
    let h = v[0].hypot(v[1]);
    if h == 0.0 {
        v
    } else {
        [v[0] / h, v[1] / h]
    }
}

/// An arc's end, and its centre and direction (`None`: a line), in program units.
type Piece = ([f64; 2], Option<([f64; 2], bool)>);

/// LinuxCNC's `biarc` from `p0` (tangent `ts`) to `p4` (tangent `te`), `r = 1`: its two pieces,
/// a line where the tangents are parallel (LinuxCNC master), or `None` where it has no solution.
fn biarc(p0: [f64; 2], ts: [f64; 2], p4: [f64; 2], te: [f64; 2]) -> Option<Vec<Piece>> {
    let (ts, te) = (unit(ts), unit(te));
    let (vx, vy) = (p0[0] - p4[0], p0[1] - p4[1]);
    let c = vx * vx + vy * vy;
    let b = 2.0 * (vx * (ts[0] + te[0]) + vy * (ts[1] + te[1]));
    let a = 2.0 * (ts[0] * te[0] + ts[1] * te[1] - 1.0);
    let discr = b * b - 4.0 * a * c;
    if discr < 0.0 {
        return None;
    }
    let disq = discr.sqrt();
    let (beta1, beta2) = ((-b - disq) / 2.0 / a, (-b + disq) / 2.0 / a);
    if beta1 > 0.0 && beta2 > 0.0 {
        return None;
    }
    // C++'s std::max: the first unless it is less than the second.
    let beta = if beta1 < beta2 { beta2 } else { beta1 };
    if beta1.is_infinite() || beta2.is_infinite() || beta > 1.0 / CART_FUZZ {
        // Tangents parallel (a straight piece): LinuxCNC master feeds straight to the end.
        return Some(vec![(p4, None)]);
    }
    if beta.is_nan() {
        return None;
    }
    let ab = 2.0 * beta;
    let p1 = [p0[0] + beta * ts[0], p0[1] + beta * ts[1]];
    let p3 = [p4[0] - beta * te[0], p4[1] - beta * te[1]];
    let p2 = [
        (p1[0] * beta + p3[0] * beta) / ab,
        (p1[1] * beta + p3[1] * beta) / ab,
    ];
    let tm = unit([p3[0] - p2[0], p3[1] - p2[1]]);
    Some(vec![arc(p0, p2, ts), arc(p2, p4, tm)])
}

/// LinuxCNC's `arc`: from `p0` along the unit direction `d` to `p1`, the circle tangent to `d` at
/// `p0` through `p1` (counter-clockwise when its signed radius is negative), or a line.
fn arc(p0: [f64; 2], p1: [f64; 2], d: [f64; 2]) -> Piece {
    let (x, y) = (p1[0] - p0[0], p1[1] - p0[1]);
    let den = 2.0 * (y * d[0] - x * d[1]);
    if den.abs() <= SMALL {
        return (p1, None);
    }
    let r = -(x * x + y * y) / den;
    (p1, Some(([p0[0] + d[1] * r, p0[1] - d[0] * r], r < 0.0)))
}
