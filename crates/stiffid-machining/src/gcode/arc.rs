//! Arcs (`G2`/`G3`) split into chords within the tolerance, the centre by `I J K` or `R`.

use super::{at, State, MAX_POINTS};
use nalgebra::Vector3;
use stiffid_core::Result;

/// The plane's axes `(u, v, normal)` as coordinate indices, `u x v = normal`.
pub(super) fn plane_axes(plane: u8) -> (usize, usize, usize) {
    match plane {
        18 => (2, 0, 1),
        19 => (1, 2, 0),
        _ => (0, 1, 2),
    }
}

/// The points of an arc from `s.position` to `end` (the end included), chords within `tolerance`.
pub(super) fn arc(
    line: u64,
    s: &State,
    end: Vector3<f64>,
    ijk: [Option<f64>; 3],
    radius: Option<f64>,
    tolerance: f64,
) -> Result<Vec<Vector3<f64>>> {
    let (u, v, n) = plane_axes(s.plane);
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
        (None, true) => (su + ijk[u].unwrap_or(0.0), sv + ijk[v].unwrap_or(0.0)),
        (Some(r), false) => centre_from_radius(line, (su, sv), (eu, ev), r, ccw)?,
    };
    let r0 = ((su - cu).powi(2) + (sv - cv).powi(2)).sqrt();
    let r1 = ((eu - cu).powi(2) + (ev - cv).powi(2)).sqrt();
    if r0 < 1e-6 {
        return Err(at(line, "arc radius below 1 um".into()));
    }
    if (r0 - r1).abs() > 1e-6_f64.max(1e-6 * r0) {
        return Err(at(line, format!("the arc's end is {:.4} mm off its circle (radius {:.4} mm at the start, {:.4} mm at the end)", (r0 - r1).abs() * 1e3, r0 * 1e3, r1 * 1e3)));
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
    Ok((1..=count)
        .map(|i| {
            if i == count {
                return end;
            }
            let t = i as f64 / count as f64;
            let a = a0 + sweep * t;
            let mut p = start;
            p[u] = cu + r0 * a.cos();
            p[v] = cv + r0 * a.sin();
            p[n] = start[n] + (end[n] - start[n]) * t;
            p
        })
        .collect())
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
    if r.abs() < half - 1e-9 {
        return Err(at(
            line,
            format!(
                "R{:.4} mm is shorter than half the chord ({half:.4} mm)",
                r * 1e3
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
