//! The arcs of a G-code path written as the language's circular moves: KUKA KRL
//! `CIRC via, end`, ABB RAPID `MoveC via, end`, FANUC LS `C P[via] : P[end]`, Yaskawa INFORM
//! three `MOVC` (start, via, end).
//!
//! A G-code arc (`G2`/`G3`, [`crate::gcode::GCode::arcs`]) is read as its chord points. After
//! compensation each arc is split into pieces of at most 180 deg (a controller refuses a circle of
//! 360 deg or more, and a piece of at most half a circle keeps its via point far from its start and
//! end), and each piece is written as one circular move from its compensated start through its via
//! point (the compensated chord point nearest its middle) to its compensated end, when the circle
//! through those three stays within the arc tolerance (the chord tolerance) of every compensated
//! chord point of the piece, the points in order along it. Otherwise the arc is written as its
//! chords, as a straight-line path would be, and a warning states the largest distance of its
//! compensated points from that circle; the chords themselves are within the chord tolerance of the
//! programmed arc (their sagitta).
//!
//! An arc is written as chords also when it has fewer than two chords per piece, when the
//! external axes move along it (the controller would move them during the circle), or when the
//! program's targets are joint targets (KRL `PTP`, RAPID `MoveAbsJ`, LS joint positions: the
//! controller interpolates the axes, [`super::Targets::Joint`]), which keep every point.
//!
//! Rules of the controllers (their manuals): KRL `CIRC` takes the auxiliary and end points,
//! the start being where the robot stands, the orientation interpolated from start to end
//! (KUKA System Software 8, "CIRC"); RAPID `MoveC CirPoint, ToPoint` likewise, a full circle in
//! two instructions (ABB RAPID reference, "MoveC"); LS `C P[i] : P[j]` with the via point on the
//! motion line and the end on its continuation line (FANUC R-30iB operator's manual,
//! "circular motion"); INFORM `MOVC` needs three consecutive `MOVC` positions, the arc's
//! start taught as one, and two arcs in a row separated by a linear step at the same point
//! (Yaskawa DX100/YRC1000 operator's manual, "circular interpolation").

use super::{Move, Target};
use crate::gcode::ArcBlock;
use nalgebra::Vector3;
use std::f64::consts::PI;
use std::ops::Range;

/// The most one circular move turns, deg.
pub(crate) const MAX_SWEEP_DEG: f64 = 180.0;

/// How far past [`MAX_SWEEP_DEG`] a compensated piece may turn, deg: a full circle's
/// compensated points are not exactly a circle, and it is two moves, not three.
const SWEEP_SLACK_DEG: f64 = 0.01;

/// How a language writes a circular move.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Form {
    /// The via point and the end (KRL, RAPID, LS): one motion from where the robot stands.
    ViaEnd,
    /// Three positions, the start taught as one (INFORM `MOVC`); arcs in a row separated by a
    /// linear step at the same point.
    StartViaEnd,
}

/// A program's targets with its arcs as circular moves: which target each written one is, how
/// it is moved to, what it stands for, and what the user should know.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Circular {
    /// Per written target, the index of the target (of the path) it is; a target may be
    /// written twice (INFORM: an arc's start taught again as a `MOVC` position).
    pub index: Vec<usize>,
    /// Per written target, how it is moved to.
    pub moves: Vec<Move>,
    /// Per written target, the path's targets it stands for (a via point: the chord points of
    /// its piece before the end).
    pub covers: Vec<Range<usize>>,
    /// The arcs written as chords and why, the circular moves written.
    pub warnings: Vec<String>,
}

impl Circular {
    /// Every target written as itself, with its move.
    fn plain(&mut self, range: Range<usize>, moves: &[Move]) {
        for i in range {
            self.push(i, moves[i], i..i + 1);
        }
    }
    fn push(&mut self, i: usize, m: Move, covers: Range<usize>) {
        self.index.push(i);
        self.moves.push(m);
        self.covers.push(covers);
    }
}

/// Why an arc is written as chords.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Chords {
    /// Its compensated points lie this far (m) off the circle through a piece's start, via and
    /// end (infinite: not in order along it, or the three on a line).
    Off(f64),
    /// Fewer than two chords per piece.
    Short,
    /// The external axes or the feed change along it.
    Moving,
}

/// A circle through three points, the arc from the first through the second to the third.
pub(crate) struct Circle {
    centre: Vector3<f64>,
    /// The unit normal, the arc turning about it right-handed.
    axis: Vector3<f64>,
    radius: f64,
    /// The unit direction from the centre to the arc's start.
    start: Vector3<f64>,
}

impl Circle {
    /// The circle through `a`, `b` and `c`, turning from `a` through `b` to `c`; `None` when
    /// they are on a line (or two are one point).
    pub(crate) fn through(a: &Vector3<f64>, b: &Vector3<f64>, c: &Vector3<f64>) -> Option<Circle> {
        let (x, y) = (a - c, b - c);
        let xy = x.cross(&y);
        let turn = (b - a).cross(&(c - b));
        if xy.norm() <= 1e-9 * x.norm() * y.norm() || turn.norm() == 0.0 {
            return None;
        }
        let centre = c
            + (y * x.norm_squared() - x * y.norm_squared()).cross(&xy) / (2.0 * xy.norm_squared());
        let radius = (a - centre).norm();
        Some(Circle {
            centre,
            axis: turn.normalize(),
            radius,
            start: (a - centre) / radius,
        })
    }

    /// The unit tangent at `p` (a point of the circle), in the direction the arc turns.
    pub(crate) fn tangent(&self, p: &Vector3<f64>) -> Vector3<f64> {
        self.axis.cross(&(p - self.centre)).normalize()
    }

    /// The distance of `p` from the circle, m.
    fn distance(&self, p: &Vector3<f64>) -> f64 {
        let d = p - self.centre;
        let h = d.dot(&self.axis);
        let radial = (d - self.axis * h).norm() - self.radius;
        h.hypot(radial)
    }

    /// The angle of `p` along the arc from its start, rad, in `[0, 2 pi)`.
    fn angle(&self, p: &Vector3<f64>) -> f64 {
        let d = p - self.centre;
        let s = self.start.cross(&d).dot(&self.axis);
        s.atan2(self.start.dot(&d)).rem_euclid(2.0 * PI)
    }

    /// The largest distance of `points` (the first the start, the last the end) from the arc,
    /// m; infinite when they are not in order along it or it turns more than
    /// [`MAX_SWEEP_DEG`].
    fn off(&self, points: &[Vector3<f64>]) -> f64 {
        let mut last = 0.0;
        let mut off: f64 = 0.0;
        for p in &points[1..] {
            let a = self.angle(p);
            if a + 1e-9 < last {
                return f64::INFINITY;
            }
            last = a;
            off = off.max(self.distance(p));
        }
        match last <= (MAX_SWEEP_DEG + SWEEP_SLACK_DEG).to_radians() {
            true => off,
            false => f64::INFINITY,
        }
    }
}

/// How far a polyline turns, rad: the angles between its consecutive segments.
fn turning(p: &[Vector3<f64>]) -> f64 {
    (p.windows(3))
        .map(|w| {
            let (a, b) = (w[1] - w[0], w[2] - w[1]);
            match a.norm() > 0.0 && b.norm() > 0.0 {
                true => a.angle(&b),
                false => 0.0,
            }
        })
        .sum()
}

/// A piece of an arc: its `[start, via, end]` indices and how far its points lie off its circle
/// beyond the tolerance (m; `None`: within it).
type Piece = ([usize; 3], Option<f64>);

/// The pieces of an arc of points `p` (its start first, its end last) as `[start, via, end]`
/// indices into `p`, each with how far its points lie off its circle (m; `None`: within
/// `tolerance`, a circular move), or why the arc is written as chords.
fn pieces(p: &[Vector3<f64>], tolerance: f64) -> Result<Vec<Piece>, Chords> {
    let m = p.len() - 1;
    if m < 2 {
        return Err(Chords::Short);
    }
    // The chords turn by the sweep less one chord's angle.
    let sweep = turning(p) * m as f64 / (m - 1) as f64;
    // The fewest pieces whose longest (a whole number of chords) turns at most the most.
    let most = (MAX_SWEEP_DEG + SWEEP_SLACK_DEG / 2.0).to_radians();
    let step = sweep / m as f64;
    let k = ((sweep / most).ceil() as usize).max(1);
    let Some(k) = (k..=m / 2).find(|k| m.div_ceil(*k) as f64 * step <= most) else {
        return Err(Chords::Short);
    };
    Ok((0..k)
        .map(|j| {
            let (s, e) = ((m * j + k / 2) / k, (m * (j + 1) + k / 2) / k);
            let v = (s + e) / 2;
            let off = match Circle::through(&p[s], &p[v], &p[e]) {
                Some(c) => c.off(&p[s..=e]),
                None => f64::INFINITY,
            };
            ([s, v, e], (off > tolerance).then_some(off))
        })
        .collect())
}

/// Whether the moves and external values of the arc `range` allow a circular move: one feed,
/// the external axes still.
fn still(range: &Range<usize>, targets: &[Target], moves: &[Move]) -> bool {
    let first = &targets[range.start].external;
    let feed = moves[range.start + 1];
    (range.clone().skip(1)).all(|i| moves[i] == feed && matches!(feed, Move::Feed(_)))
        && (range.clone())
            .all(|i| (targets[i].external.iter().zip(first)).all(|(a, b)| (a - b).abs() <= 1e-9))
}

/// The program's targets with the arcs `arcs` written as circular moves of `form` where they
/// stay within `tolerance` (m) of the circle (module docs): `positions` are the targets' TCP
/// positions in the controller's kinematics (any one frame), `moves` how each is moved to.
/// Arcs overlapping one before them, or outside the targets, are written as chords.
pub fn circular(
    arcs: &[ArcBlock],
    (targets, positions, moves): (&[Target], &[Vector3<f64>], &[Move]),
    tolerance: f64,
    form: Form,
) -> Circular {
    let n = targets.len().min(positions.len()).min(moves.len());
    let mut out = Circular::default();
    let mut next = 0;
    let (mut circular, mut chords, mut partly) = (0, Vec::new(), Vec::new());
    for arc in arcs {
        let r = arc.points.clone();
        if r.start + 1 < next || r.end > n || r.len() < 2 {
            continue;
        }
        out.plain(next..r.start + 1, moves);
        let fit = match still(&r, targets, moves) {
            true => pieces(&positions[r.clone()], tolerance),
            false => Err(Chords::Moving),
        };
        let pieces = match fit {
            Ok(p) if p.iter().any(|(_, off)| off.is_none()) => p,
            other => {
                out.plain(r.start + 1..r.end, moves);
                let why = other.map_or_else(|why| why, |p| Chords::Off(largest(&p)));
                chords.push((arc.line, why));
                next = r.end;
                continue;
            }
        };
        let feed = moves[r.end - 1].feed().unwrap_or_default();
        for ([s, v, e], off) in pieces.iter().map(|(p, off)| (p.map(|i| i + r.start), off)) {
            if off.is_some() {
                out.plain(s + 1..e + 1, moves);
                continue;
            }
            if form == Form::StartViaEnd {
                if matches!(out.moves.last(), Some(Move::ArcEnd(_))) {
                    out.push(s, Move::Feed(feed), s..s + 1);
                }
                out.push(s, Move::ArcStart(feed), s..s + 1);
            }
            out.push(v, Move::ArcVia(feed), s + 1..e);
            out.push(e, Move::ArcEnd(feed), e..e + 1);
        }
        if pieces.iter().any(|(_, off)| off.is_some()) {
            partly.push((arc.line, Chords::Off(largest(&pieces))));
        }
        circular += 1;
        next = r.end;
    }
    out.plain(next..n, moves);
    out.warnings = warnings(circular, &chords, tolerance);
    out.warnings.extend(partial(&partly, tolerance));
    out
}

/// The warning of the arcs written as chords (at most one), naming their lines and the largest
/// distance found.
fn warnings(circular: usize, chords: &[(u64, Chords)], tolerance: f64) -> Vec<String> {
    if chords.is_empty() {
        return Vec::new();
    }
    let lines: Vec<String> = (chords.iter().take(8))
        .map(|(l, _)| l.to_string())
        .collect();
    let more = match chords.len() > 8 {
        true => format!(" and {} more", chords.len() - 8),
        false => String::new(),
    };
    let off = (chords.iter())
        .filter_map(|(_, c)| match c {
            Chords::Off(d) if d.is_finite() => Some(*d),
            _ => None,
        })
        .fold(None, |m: Option<f64>, d| Some(m.map_or(d, |m| m.max(d))));
    let why = match off {
        Some(d) => format!("their compensated points lie up to {} mm off the circle through each one's start, middle and end (beyond the arc tolerance, the chord tolerance, {} mm), or the arc has too few chords or moves the external axes", super::number(d * 1e3), super::number(tolerance * 1e3)),
        None => "each has too few chords, its points are not in order along a circle, or the external axes move along it".into(),
    };
    vec![format!(
        "{} of {} arcs written as chords (lines {}{more}): {why}; the chords are within the chord tolerance, {} mm, of the programmed arcs",
        chords.len(),
        chords.len() + circular,
        lines.join(", "),
        super::number(tolerance * 1e3)
    )]
}

/// The largest distance off its circle of the pieces written as chords, m.
fn largest(pieces: &[Piece]) -> f64 {
    (pieces.iter().filter_map(|(_, off)| *off)).fold(0.0, f64::max)
}

/// The warning of the arcs written in part as circular moves, in part as chords (at most one).
fn partial(arcs: &[(u64, Chords)], tolerance: f64) -> Option<String> {
    let off = (arcs.iter())
        .filter_map(|(_, c)| match c {
            Chords::Off(d) if d.is_finite() => Some(*d),
            _ => None,
        })
        .fold(0.0, f64::max);
    let off = match off > 0.0 {
        true => format!("lie up to {} mm off", super::number(off * 1e3)),
        false => "are not in order along".into(),
    };
    let lines: Vec<String> = (arcs.iter().take(8)).map(|(l, _)| l.to_string()).collect();
    let more = match arcs.len() > 8 {
        true => format!(" and {} more", arcs.len() - 8),
        false => String::new(),
    };
    (!arcs.is_empty()).then(|| format!(
        "{} arcs written in part as chords (lines {}{more}): the compensated points of those parts {off} the circle through each part's start, middle and end (beyond the arc tolerance, the chord tolerance, {} mm); the chords are within the chord tolerance of the programmed arcs",
        arcs.len(),
        lines.join(", "),
        super::number(tolerance * 1e3)
    ))
}

/// The warning of a program that keeps its arcs' points (joint targets), `None` without arcs.
pub(crate) fn kept_as_points(arcs: &[ArcBlock], why: &str) -> Option<String> {
    (!arcs.is_empty()).then(|| {
        format!(
            "{} arcs written as their chord points ({why}): no circular move",
            arcs.len()
        )
    })
}

/// The bound of each motion instruction of a program written as `circular` from targets of
/// `bounds`: a written target's the largest of those it stands for, and a via point's joined
/// to its end's where it is no motion of its own ([`Form::ViaEnd`]).
pub fn motion_bounds(circular: &Circular, bounds: &[f64], form: Form) -> Vec<f64> {
    let mut out = Vec::with_capacity(circular.moves.len());
    let mut carried: Option<f64> = None;
    for (m, covers) in circular.moves.iter().zip(&circular.covers) {
        let b = (bounds.get(covers.clone()).unwrap_or(&[]).iter()).fold(0.0_f64, |a, b| a.max(*b));
        match (m, form) {
            (Move::ArcVia(_), Form::ViaEnd) => carried = Some(b),
            _ => out.push(carried.take().map_or(b, |c| c.max(b))),
        }
    }
    out
}

/// Whether the circular moves of `moves` are whole for a language of `form` (`None`: the
/// language or the targets write none): each via point after its start (INFORM) and before its
/// end.
pub fn whole(moves: &[Move], form: Option<Form>) -> bool {
    let arc = |m: &Move| matches!(m, Move::ArcStart(_) | Move::ArcVia(_) | Move::ArcEnd(_));
    let Some(form) = form else {
        return !moves.iter().any(arc);
    };
    (0..moves.len()).all(|i| {
        let before = i.checked_sub(1).map(|j| moves[j]);
        let after = moves.get(i + 1).copied();
        match moves[i] {
            Move::ArcStart(_) => {
                form == Form::StartViaEnd && matches!(after, Some(Move::ArcVia(_)))
            }
            Move::ArcVia(_) => {
                matches!(after, Some(Move::ArcEnd(_)))
                    && (form == Form::ViaEnd || matches!(before, Some(Move::ArcStart(_))))
                    && i > 0
            }
            Move::ArcEnd(_) => matches!(before, Some(Move::ArcVia(_))),
            _ => true,
        }
    })
}

/// The files of a program of `moves`, at most `per_file` each (> 0), none starting inside a
/// circular move (at its end, or at its via point after a taught start).
pub(crate) fn files(moves: &[Move], per_file: usize) -> Vec<Range<usize>> {
    let mut out = Vec::new();
    let mut start = 0;
    while start < moves.len() {
        let mut end = (start + per_file).min(moves.len());
        // The robot stands at a circular move's start when a file begins: its via point and
        // end (and a taught start, INFORM's) go together.
        let inside = |i: usize| match moves[i] {
            Move::ArcEnd(_) => true,
            Move::ArcVia(_) => matches!(moves[i - 1], Move::ArcStart(_)),
            _ => false,
        };
        while end < moves.len() && end > start + 1 && inside(end) {
            end -= 1;
        }
        out.push(start..end);
        start = end;
    }
    out
}
