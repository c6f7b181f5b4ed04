//! Work offsets the program sets: `G10 L2 Pn X Y Z` (offset `n` at machine coordinates
//! `X Y Z`, the axes not given unchanged) and `G10 L20` (LinuxCNC and grbl: offset `n` set so
//! that the tool's current position reads `X Y Z` in it; FANUC and Haas: the additional offset
//! `G54.1 Pn` set as `L2` sets the others). LinuxCNC manual, "G10 L2" and "G10 L20"
//! (`P0` the offset in force, `P1`-`P9` `G54`-`G59.3`, `G91` without effect); FANUC's and Haas's
//! programmable data input (`P1`-`P6` `G54`-`G59`, `P0` the external or common offset, under
//! `G91` the values added to the offset).
//!
//! A robot cell has no machine coordinates of its own: `L2` places an offset through the setup's
//! `G53` frame (`[workpiece.offsets] G53`), or, without it, through the program's own `G54`
//! (`G10 L2 P1 X Y Z` before it: `G54` is the part frame the setup places, so the machine's
//! origin lies at minus those values in it). The part frame is the setup's: an offset set to
//! another frame than the setup gives for the same name (`G54` the part frame itself) is refused
//! naming the line and the setup's entry, as are `G10 L1`/`L10`/`L11` (the tool table: the
//! process's lengths), a rotation `R` other than 0, a `P` the dialect does not name, and values
//! under `G91` where the setup names no dialect reading them.

use super::machine::{convert, Frame};
use super::{at, GcodeDialect, State};
use nalgebra::{Isometry3, Translation3, Vector3};
use stiffid_core::common::words::number;
use stiffid_core::Result;

/// How far an offset the program sets may lie from the setup's of the same name, m.
const AGREE: f64 = 1e-6;

/// The offsets the program set, and the machine's origin it placed.
#[derive(Debug, Clone, Default)]
pub(super) struct Set {
    /// Per name the frame in the `G54` part frame, and the `G10`'s line.
    offsets: Vec<(String, Isometry3<f64>, u64)>,
    /// The machine's frame (`G53`) a `G10 L2 P1` placed, and its line.
    machine: Option<(Isometry3<f64>, u64)>,
}

/// The words of a `G10` block, as written.
pub(super) struct Words {
    pub(super) l: Option<f64>,
    pub(super) p: Option<f64>,
    pub(super) xyz: [Option<f64>; 3],
    pub(super) r: Option<f64>,
}

impl State {
    /// The frame of the work offset `name` (or `G53`): the program's (`G10`), else the setup's.
    pub(super) fn offset(&self, name: &str) -> Option<Isometry3<f64>> {
        if let Some((_, f, _)) = self.set.offsets.iter().find(|(n, _, _)| n == name) {
            return Some(*f);
        }
        match (name, self.set.machine) {
            ("G53", Some((m, _))) if self.machine.frames.offset("G53").is_none() => Some(m),
            _ => self.machine.frames.offset(name),
        }
    }
}

/// A `G10` block (module docs).
pub(super) fn apply(line: u64, w: &Words, s: &mut State) -> Result<()> {
    if s.g92 != Vector3::zeros() {
        return Err(at(line, "G10 while a G92 shift is in force: controllers differ on whether the offset set includes it; cancel it (G92.1) first".into()));
    }
    let refuse = |why: String| Err(at(line, why));
    let l = match w.l {
        Some(l) if l == 2.0 || l == 20.0 => l as u8,
        Some(l) if [1.0, 10.0, 11.0].contains(&l) => {
            return refuse(format!("G10 L{l}: it sets the controller's tool table; stiffid takes the tools' lengths from the process ([tool] length_mm)"));
        }
        Some(l) => {
            return refuse(format!(
                "G10 L{}: expected L2 or L20 (a work offset)",
                number(l)
            ))
        }
        None => return refuse("G10 without L: expected L2 or L20 (a work offset)".into()),
    };
    if w.r.is_some_and(|r| r != 0.0) {
        return refuse("G10: a rotation R of the work offset is not read; give the offset's frame in the setup ([workpiece.offsets])".into());
    }
    let fanuc = matches!(
        s.machine.dialect,
        Some(GcodeDialect::Fanuc | GcodeDialect::Haas)
    );
    if l == 20 && s.machine.dialect.is_none() {
        return refuse("G10 L20: LinuxCNC and grbl set the offset so that the tool's position reads X Y Z, FANUC and Haas set the additional offset G54.1 Pn, and the setup names no controller ([controller] dialect)".into());
    }
    if s.incremental && !matches!(s.machine.dialect, Some(GcodeDialect::LinuxCnc)) && !fanuc {
        return refuse(format!("G10 L{l} under G91: LinuxCNC sets the values, FANUC and Haas add them to the offset, and the setup names neither ([controller] dialect)"));
    }
    let name = name(line, (l, w.p), s)?;
    let scale = if s.inch { 25.4e-3 } else { 1e-3 };
    let v = w.xyz.map(|v| v.map(|v| v * scale));
    let frame = match (l, fanuc) {
        (20, false) => touch_off(line, &name, v, s)?,
        _ => placed(line, &name, (v, fanuc && s.incremental), s)?,
    };
    agree(line, &name, &frame, s)?;
    s.set.offsets.retain(|(n, _, _)| *n != name);
    s.set.offsets.push((name.clone(), frame, line));
    if s.frame.name == name {
        s.set_frame(Frame {
            name,
            part_from: frame,
        });
    }
    Ok(())
}

/// The offset `P` names on the dialect (module docs).
fn name(line: u64, (l, p): (u8, Option<f64>), s: &State) -> Result<String> {
    let Some(p) = p.filter(|p| p.fract() == 0.0 && (0.0..=1e4).contains(p)) else {
        return Err(at(
            line,
            format!("G10 L{l}: expected the offset's number P (a whole number)"),
        ));
    };
    let p = p as u16;
    const NAMES: [&str; 9] = [
        "G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3",
    ];
    let dialect = s.machine.dialect;
    let fanuc = matches!(dialect, Some(GcodeDialect::Fanuc | GcodeDialect::Haas));
    match (l, p) {
        (20, 1..) if fanuc => Ok(format!("G54.1 P{p}")),
        (_, 0) if !fanuc && dialect.is_some() => Ok(s.frame.name.clone()),
        (_, 1..=6) => Ok(NAMES[usize::from(p) - 1].to_string()),
        (_, 7..=9) if dialect == Some(GcodeDialect::LinuxCnc) => Ok(NAMES[usize::from(p) - 1].to_string()),
        _ => Err(at(line, format!("G10 L{l} P{p}: not a work offset stiffid reads on this controller (P1-P6 are G54-G59 everywhere; LinuxCNC's P0 the offset in force and P7-P9 G59.1-G59.3; FANUC's and Haas's P0 the external or common offset, which shifts every other)"))),
    }
}

/// `L2` (and FANUC's and Haas's `L20`): the offset at machine coordinates `v` (added to the
/// offset's under `add`), the axes not given unchanged.
fn placed(
    line: u64,
    name: &str,
    (v, add): ([Option<f64>; 3], bool),
    s: &mut State,
) -> Result<Isometry3<f64>> {
    let machine = match s.offset("G53") {
        Some(m) => m,
        None if name == "G54" && !add && v.iter().all(Option::is_some) => {
            // The part frame is G54: the machine's origin lies at minus the values in it.
            let m = Isometry3::from_parts(Translation3::new(-v[0].unwrap_or(0.0), -v[1].unwrap_or(0.0), -v[2].unwrap_or(0.0)), Default::default());
            s.set.machine = Some((m, line));
            return Ok(Isometry3::identity());
        }
        None => return Err(at(line, format!("G10: sets {name} in machine coordinates, which the setup does not place: give the machine's frame ([workpiece.offsets] G53 = {{ xyz_mm = [..], rpy_deg = [..] }}, in the G54 part frame), or set G54 with all of X Y Z (G10 L2 P1) before"))),
    };
    let old = s.offset(name).map(|f| machine.inverse() * f);
    if old.is_some_and(|o| o.rotation.angle() > 1e-9) {
        return Err(at(line, format!("G10: {name} is turned against the machine's axes in the setup, and a controller's offset is a shift along them")));
    }
    let mut t = Vector3::zeros();
    for k in 0..3 {
        t[k] = match (v[k], old.map(|o| o.translation.vector[k])) {
            (Some(v), Some(o)) if add => o + v,
            (Some(v), _) if !add => v,
            (None, Some(o)) => o,
            _ => return Err(at(line, format!("G10: {} of {name} is not given and has no value before (neither the setup nor the program gives {name})", ["X", "Y", "Z"][k]))),
        };
    }
    Ok(machine * Translation3::from(t))
}

/// LinuxCNC's and grbl's `L20`: the offset moved so that the tool's position reads `v` in it.
fn touch_off(line: u64, name: &str, v: [Option<f64>; 3], s: &State) -> Result<Isometry3<f64>> {
    let Some(old) = s.offset(name) else {
        return Err(at(
            line,
            format!(
                "G10 L20: {name} has no frame before (neither the setup nor the program gives it)"
            ),
        ));
    };
    let lift = s.lift();
    let target = Frame {
        name: name.to_string(),
        part_from: old,
    };
    let (p, known) = convert((s.position, s.known), (&s.frame, lift), (&target, lift));
    let mut shift = Vector3::zeros();
    for k in (0..3).filter(|k| v[*k].is_some()) {
        if !known[k] {
            let mut axes = [true; 3];
            axes[k] = false;
            return Err(at(
                line,
                format!(
                    "G10 L20: the tool's position is not known: {}",
                    s.unknown(axes)
                ),
            ));
        }
        shift[k] = p[k] - v[k].unwrap_or(0.0);
    }
    Ok(old * Translation3::from(shift))
}

/// An error unless `frame` is the setup's frame of `name` (when it gives one).
fn agree(line: u64, name: &str, frame: &Isometry3<f64>, s: &State) -> Result<()> {
    let Some(setup) = s.machine.frames.offset(name) else {
        return Ok(());
    };
    let d = setup.inverse() * frame;
    if d.translation.vector.norm() <= AGREE && d.rotation.angle() <= 1e-9 {
        return Ok(());
    }
    let t = frame.translation.vector * 1e3;
    let what = match name {
        "G54" => "G54 is the part frame the setup places ([workpiece] base_from_part)".to_string(),
        _ => format!(
            "the setup gives {name} another frame ([workpiece.offsets] {name}, {:.3} mm away)",
            d.translation.vector.norm() * 1e3
        ),
    };
    Err(at(line, format!("G10 puts {name} at [{:.3}, {:.3}, {:.3}] mm of the G54 part frame, and {what}: leave {name} out of the setup, or give it there as the program sets it", t.x, t.y, t.z)))
}
