//! Arcs (`G2`/`G3`) split into chords within the tolerance, the centre by `I J K` or `R`.

use super::{at, GCode, State, MAX_POINTS};
use nalgebra::Vector3;
use std::ops::Range;
use stiffid_core::Result;

/// One arc block (`G2`/`G3`) of a path: its line and its points.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ArcBlock {
    /// The block's line, 1-based.
    pub line: u64,
    /// Its points in [`GCode::points`]: the arc's start (the point before the block, where the
    /// tool stands), its chord points and its end (the block's last point).
    pub points: Range<usize>,
}

impl GCode {
    /// The arc blocks of the path, in path order, each with its start, chord points and end:
    /// what a robot program may write as circular moves
    /// ([`crate::program::generate::arcs`]).
    pub fn arcs(&self) -> Vec<ArcBlock> {
        (self.blocks.iter())
            .filter(|b| b.arc_word.is_some() && !b.spline && b.cycle.is_none())
            .filter(|b| b.points.start > 0 && !b.points.is_empty())
            .map(|b| ArcBlock {
                line: self.points[b.points.start].line,
                points: b.points.start - 1..b.points.end,
            })
            .collect()
    }
}

/// The plane's axes `(u, v, normal)` as coordinate indices, `u x v = normal`.
pub(super) fn plane_axes(plane: u8) -> (usize, usize, usize) {
    match plane {
        18 => (2, 0, 1),
        19 => (1, 2, 0),
        _ => (0, 1, 2),
    }
}

/// How far an arc's end may lie off the circle through its start, m: grbl's rule
/// (`gcode.c`: refused beyond 0.005 mm when also beyond 0.5 mm or 0.1 % of the radius), which
/// accepts every arc LinuxCNC does (`interp_arc.cc` `arc_data_ijk`: refused beyond
/// `CENTER_ARC_RADIUS_TOLERANCE`, 0.028 mm or 0.0028 inch, or 0.1 % of the radius,
/// `SPIRAL_RELATIVE_TOLERANCE`). As both controllers, the end is reached exactly: the radius
/// changes linearly from the start's to the end's along the arc (LinuxCNC's spiral).
pub(crate) const ARC_END_TOLERANCE_MM: f64 = 0.005;
/// The most an arc's end may lie off the circle in any case, mm (grbl's 0.5 mm).
pub(crate) const ARC_END_MAX_MM: f64 = 0.5;
/// The most an arc's end may lie off the circle beyond [`ARC_END_TOLERANCE_MM`], relative to
/// the radius (grbl's and LinuxCNC's 0.1 %).
pub(crate) const ARC_END_RELATIVE: f64 = 1e-3;

/// Whether an arc of start radius `r0` and end radius `r1` (m) is accepted
/// ([`ARC_END_TOLERANCE_MM`]).
fn on_circle(r0: f64, r1: f64) -> bool {
    let off = (r0 - r1).abs();
    off <= ARC_END_TOLERANCE_MM * 1e-3
        || (off <= ARC_END_MAX_MM * 1e-3 && off <= ARC_END_RELATIVE * r0.max(r1))
}

/// The points of an arc from `s.position` to `end` (the end included), chords within `tolerance`,
/// and its centre in the plane's coordinates.
pub(super) fn arc(
    line: u64,
    s: &State,
    end: Vector3<f64>,
    ijk: [Option<f64>; 3],
    radius: Option<f64>,
    tolerance: f64,
) -> Result<(Vec<Vector3<f64>>, [f64; 2])> {
    let (u, v, n) = plane_axes(s.plane);
    if ijk[n].is_some() {
        let letter = ['I', 'J', 'K'][n];
        return Err(at(line, format!("{letter}: a centre word off the arc's plane G{} (LinuxCNC refuses it; another controller may ignore it or read the arc in another plane): give the plane (G17 XY: I J, G18 ZX: I K, G19 YZ: J K) before the arc", s.plane)));
    }
    let start = s.position;
    let (su, sv, eu, ev) = (start[u], start[v], end[u], end[v]);
    let ccw = s.motion == 3;
    let (cu, cv) = match (radius, ijk.iter().any(Option::is_some)) {
        (Some(_), true) => {
            return Err(at(
                line,
                "give the arc's centre (I J K) or its radius (R), not both".into(),
            ))
        }
        (None, false) => return Err(at(line, "arc without centre (I J K) or radius (R)".into())),
        (None, true) if s.ij_absolute => match (ijk[u], ijk[v]) {
            (Some(cu), Some(cv)) => (cu, cv),
            _ => return Err(at(line, "G90.1 (absolute arc centres): give both of the plane's centre coordinates (I J in G17, K I in G18, J K in G19)".into())),
        },
        (None, true) => (su + ijk[u].unwrap_or(0.0), sv + ijk[v].unwrap_or(0.0)),
        (Some(r), false) => centre_from_radius(line, (su, sv), (eu, ev), r, ccw)?,
    };
    let points = chords(line, (start, end), [cu, cv], ccw, s.plane, tolerance)?;
    Ok((points, [cu, cv]))
}

/// The chord points of an arc in `plane` from `start` to `end` (the end included) around
/// `centre` (the plane's coordinates), counter-clockwise or not, the chords' sagitta within
/// `tolerance`; an end off the circle within [`ARC_END_TOLERANCE_MM`] is reached along a spiral.
pub(super) fn chords(
    line: u64,
    (start, end): (Vector3<f64>, Vector3<f64>),
    [cu, cv]: [f64; 2],
    ccw: bool,
    plane: u8,
    tolerance: f64,
) -> Result<Vec<Vector3<f64>>> {
    let (u, v, n) = plane_axes(plane);
    let (su, sv, eu, ev) = (start[u], start[v], end[u], end[v]);
    let r0 = ((su - cu).powi(2) + (sv - cv).powi(2)).sqrt();
    let r1 = ((eu - cu).powi(2) + (ev - cv).powi(2)).sqrt();
    if r0 < 1e-6 {
        return Err(at(line, "arc radius below 1 um".into()));
    }
    if !on_circle(r0, r1) {
        return Err(at(line, format!("the arc's end is {:.4} mm off its circle (radius {:.4} mm at the start, {:.4} mm at the end; accepted: {ARC_END_TOLERANCE_MM} mm, or {} % of the radius up to {ARC_END_MAX_MM} mm, as grbl and LinuxCNC)", (r0 - r1).abs() * 1e3, r0 * 1e3, r1 * 1e3, ARC_END_RELATIVE * 100.0)));
    }
    let a0 = (sv - cv).atan2(su - cu);
    let a1 = (ev - cv).atan2(eu - cu);
    let two_pi = 2.0 * std::f64::consts::PI;
    let mut sweep = if ccw {
        (a1 - a0).rem_euclid(two_pi)
    } else {
        -(a0 - a1).rem_euclid(two_pi)
    };
    if sweep.abs() < 1e-12 {
        sweep = if ccw { two_pi } else { -two_pi };
    }
    let step = 2.0 * (1.0 - (tolerance / r0).min(1.0)).acos();
    let count = ((sweep.abs() / step).ceil() as usize).max(1);
    if count > MAX_POINTS {
        return Err(at(
            line,
            format!("the arc needs more than {MAX_POINTS} chords at this tolerance"),
        ));
    }
    let points: Vec<Vector3<f64>> = (1..=count)
        .map(|i| {
            if i == count {
                return end;
            }
            let t = i as f64 / count as f64;
            let a = a0 + sweep * t;
            // The spiral of an end off the circle; a circle to rounding stays the circle.
            let r = match (r1 - r0).abs() > 1e-9 {
                true => r0 + (r1 - r0) * t,
                false => r0,
            };
            let mut p = start;
            p[u] = cu + r * a.cos();
            p[v] = cv + r * a.sin();
            p[n] = start[n] + (end[n] - start[n]) * t;
            p
        })
        .collect();
    Ok(points)
}

/// The centre of an `R` arc: on the chord's perpendicular bisector, to the left of the chord for
/// a counter-clockwise arc of at most 180 deg (`r > 0`), to the right for over 180 deg (`r < 0`).
pub(super) fn centre_from_radius(
    line: u64,
    s: (f64, f64),
    e: (f64, f64),
    r: f64,
    ccw: bool,
) -> Result<(f64, f64)> {
    let (du, dv) = (e.0 - s.0, e.1 - s.1);
    let d = (du * du + dv * dv).sqrt();
    if d < 1e-9 {
        return Err(at(
            line,
            "an R arc needs an end point other than its start".into(),
        ));
    }
    let half = d / 2.0;
    // LinuxCNC's RADIUS_TOLERANCE (0.00005 inch, `arc_data_r`): a radius that short of half
    // the chord makes a half circle.
    if r.abs() < half - 1.27e-6 {
        return Err(at(
            line,
            format!(
                "R{:.4} mm is shorter than half the chord ({:.4} mm)",
                r * 1e3,
                half * 1e3
            ),
        ));
    }
    let h = (r * r - half * half).max(0.0).sqrt();
    let left = (-dv / d, du / d);
    let side = if ccw == (r > 0.0) { 1.0 } else { -1.0 };
    Ok((
        s.0 + du / 2.0 + side * h * left.0,
        s.1 + dv / 2.0 + side * h * left.1,
    ))
}
