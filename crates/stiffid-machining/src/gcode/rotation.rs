//! FANUC's and Haas's coordinate rotation `G68` .. `G69` in the `G17` plane: the program's
//! coordinates turned by `R` degrees (counter-clockwise seen from `+Z`) about a centre, until
//! `G69`. FANUC: `G68 X Y R` (FANUC Series 0i-MF operator's manual, "Coordinate system rotation
//! (G68, G69)"); Haas: `G68 A B R`, `A B` the centre's coordinates in the plane (Haas mill
//! operator's manual, G68 Rotation); without a centre, where the tool is. The rotation turns the
//! work offset's frame about that centre (module `machine`): arcs, canned cycles and the
//! written program follow it; the tool does not turn (its orientation stays the work offset's).
//! Refused naming the line: on LinuxCNC and grbl (no such code) and without a dialect, outside
//! `G17`, under `G91` (whether `R` adds to the rotation in force is a setting of the control),
//! without `R`, beside other words, and, while a rotation is in force, a work offset, plane,
//! `G10`, `G28`/`G30`, `G53` or `G92`; after `G68` and after `G69`, a motion before one that
//! gives both `X` and `Y` absolutely (the controls differ on where an axis not given is).

use super::machine::Frame;
use super::words::Word;
use super::{at, GcodeDialect, State};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use stiffid_core::Result;

/// A rotation in force: the frame it turned, its angle (rad) and the `G68`'s line.
#[derive(Debug, Clone)]
pub(super) struct Rotation {
    base: Frame,
    angle: f64,
    line: u64,
}

/// The words of a `G68`/`G69` block, as written.
struct Words {
    /// `X Y` (FANUC) and `A B` (Haas) beside it.
    xy: [Option<f64>; 2],
    ab: [Option<f64>; 2],
    r: Option<f64>,
    /// Any other word beside it (but `N`, and `G17`/`G90` already in force).
    other: bool,
}

/// A block of `words` read here: `Ok(true)` for a `G68` block (applied), an error for a block
/// refused under a rotation or right after one (module docs), `Ok(false)` for the others (a
/// `G69` cancels the rotation in force, if any, and its block is read on).
pub(super) fn block(line: u64, words: &[Word], s: &mut State) -> Result<bool> {
    let g = |w: &Word, v: f64| w.letter == 'G' && (w.value - v).abs() < 1e-9;
    if words.iter().any(|w| g(w, 68.0)) {
        let mut w = Words {
            xy: [None; 2],
            ab: [None; 2],
            r: None,
            other: false,
        };
        for word in words {
            match word.letter {
                'X' | 'Y' => w.xy[usize::from(word.letter == 'Y')] = Some(word.value),
                'A' | 'B' => w.ab[usize::from(word.letter == 'B')] = Some(word.value),
                'R' => w.r = Some(word.value),
                'N' => {}
                'G' if g(word, 68.0) => {}
                'G' if g(word, 17.0) && s.plane == 17 || g(word, 90.0) && !s.incremental => {}
                _ => w.other = true,
            }
        }
        set(line, &w, s)?;
        return Ok(true);
    }
    if words.iter().any(|w| g(w, 69.0))
        && let Some(rot) = s.rotation.take()
    {
        s.set_frame(rot.base);
        s.rotated = Some(line);
    }
    if let Some(rot) = &s.rotation {
        let codes = [
            (10.0, "G10"),
            (28.0, "G28"),
            (30.0, "G30"),
            (53.0, "G53"),
            (92.0, "G92"),
            (17.0, "a plane"),
            (18.0, "a plane"),
            (19.0, "a plane"),
            (54.0, "a work offset"),
            (55.0, "a work offset"),
            (56.0, "a work offset"),
            (57.0, "a work offset"),
            (58.0, "a work offset"),
            (59.0, "a work offset"),
            (54.1, "a work offset"),
            (59.1, "a work offset"),
            (59.2, "a work offset"),
            (59.3, "a work offset"),
        ];
        let same_plane = |v: f64| v == 17.0 && s.plane == 17;
        let given = |v: f64| !same_plane(v) && words.iter().any(|w| g(w, v));
        if let Some((_, what)) = codes.iter().find(|(v, _)| given(*v)) {
            return Err(at(line, format!("{what} while the coordinate rotation G68 of line {} is in force: cancel it (G69) first", rot.line)));
        }
    }
    if let Some(at_line) = s.rotated {
        let has = |l: char| words.iter().any(|w| w.letter == l);
        let home = words.iter().any(|w| g(w, 28.0) || g(w, 30.0) || g(w, 53.0));
        if home || !['X', 'Y', 'Z'].iter().any(|l| has(*l)) {
            return Ok(false);
        }
        let absolute =
            words.iter().any(|w| g(w, 90.0)) || !s.incremental && !words.iter().any(|w| g(w, 91.0));
        if !(has('X') && has('Y') && absolute) {
            return Err(at(line, format!("the first motion after the G68/G69 of line {at_line} gives both X and Y absolutely, as FANUC and Haas ask (the controls differ on where an axis not given, or an increment, puts the tool): give both under G90")));
        }
        s.rotated = None;
    }
    Ok(false)
}

/// The rotation of a frame's coordinates that turns the tool as well: the frame's own, without a
/// `G68`'s (the tool does not turn with the coordinates).
pub(super) fn tool_turn(frame: &Frame, s: &State) -> UnitQuaternion<f64> {
    match &s.rotation {
        Some(rot) => {
            frame.part_from.rotation * UnitQuaternion::from_euler_angles(0.0, 0.0, -rot.angle)
        }
        None => frame.part_from.rotation,
    }
}

/// A `G68` block.
fn set(line: u64, w: &Words, s: &mut State) -> Result<()> {
    let refuse = |why: &str| Err(at(line, format!("G68: {why}")));
    let haas = match s.machine.dialect {
        Some(GcodeDialect::Fanuc) => false,
        Some(GcodeDialect::Haas) => true,
        _ => return refuse("a coordinate rotation, read with [controller] dialect = \"fanuc\" or \"haas\" (LinuxCNC and grbl have none)"),
    };
    if w.other {
        return refuse("write it in a block of its own (the centre and R only)");
    }
    if s.plane != 17 {
        return refuse("a rotation outside the G17 plane");
    }
    if s.incremental {
        return refuse("under G91 (whether R adds to the rotation in force is a setting of the control): write G90 before it");
    }
    if s.rotation.is_some() {
        return refuse("a rotation while one is in force: cancel it (G69) first");
    }
    let (centre, other) = if haas { (w.ab, w.xy) } else { (w.xy, w.ab) };
    if other.iter().any(Option::is_some) {
        let letters = if haas { "X Y" } else { "A B" };
        return refuse(&format!(
            "{letters} beside it: the centre is {} on this dialect",
            if haas { "A B" } else { "X Y" }
        ));
    }
    let Some(r) = w.r else {
        return refuse("without R (the angle then is a parameter of the control): give R");
    };
    if !(-360.0..=360.0).contains(&r) {
        return refuse("R: expected an angle from -360 to 360 deg");
    }
    let scale = if s.inch { 25.4e-3 } else { 1e-3 };
    let mut c = [0.0; 2];
    for k in 0..2 {
        c[k] = match centre[k] {
            Some(v) if (v * scale).abs() <= 100.0 => v * scale,
            Some(_) => return refuse("a centre beyond 100 m"),
            None if s.known[k] => s.position[k],
            None => {
                let mut known = [true; 3];
                known[k] = false;
                return refuse(&format!(
                    "the centre is where the tool is, and that is not known: {}",
                    s.unknown(known)
                ));
            }
        };
    }
    let angle = r.to_radians();
    let about = Vector3::new(c[0], c[1], 0.0);
    let turn = Translation3::from(about)
        * Isometry3::from_parts(
            Translation3::identity(),
            UnitQuaternion::from_euler_angles(0.0, 0.0, angle),
        )
        * Translation3::from(-about);
    let base = s.frame.clone();
    s.set_frame(Frame {
        name: base.name.clone(),
        part_from: base.part_from * turn,
    });
    s.rotation = Some(Rotation { base, angle, line });
    s.rotated = Some(line);
    Ok(())
}
