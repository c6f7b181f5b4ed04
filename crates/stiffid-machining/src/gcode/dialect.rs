//! Where controllers read the same words differently, read as the setup's `[controller]
//! dialect` says, or refused naming the line and the option when it does not say
//! (docs/programs/gcode.md, "Dialects", names each rule's source):
//! - A tool length offset changed (`G43 Hn`, `G44 Hn`, `G49`, Haas's `G28`) in a block
//!   without an absolute `Z`, while `Z` is known. LinuxCNC's interpreter re-expresses where the
//!   tool is in the new offset and does not move ("G43 does not cause any motion"): a `G91`
//!   increment after it counts from the tool's place. FANUC and Haas shift the end point of the
//!   next move that gives `Z` by the offset: a `G91 Z` increment after it carries the change of
//!   the offset as well. Moves without `Z` in between leave `Z` where it is in both readings.
//!   grbl has no tool table (`G43 H` refused).
//! - `G28` with a tool length offset in force: Haas cancels the offset there, LinuxCNC and grbl
//!   keep it; FANUC's rule is a setting of the control, so an absolute `Z` after it is refused
//!   until the program states `G43`/`G44`/`G49` again.
//! - `G53` under `G91`: LinuxCNC and grbl read its words as absolute machine coordinates;
//!   FANUC, Haas and an unstated dialect are refused (module `block`), but for a rapid the
//!   setup gives no `G53` frame for, which leaves the axes it names unknown in every reading.

use super::{at, State, NO_MOTION};
use stiffid_core::setup::GcodeDialect;
use stiffid_core::Result;

/// The words of the option, for messages.
const OPTION: &str = "state which controller runs the program: [controller] dialect = \"linuxcnc\", \"fanuc\", \"haas\" or \"grbl\" in the setup";

impl State {
    /// A tool length offset changed to `h` (m) on `line`: put in force, and the change kept for
    /// the next move that gives `Z` (module docs) while `Z` is known.
    pub(super) fn change_length_offset(&mut self, line: u64, h: f64) {
        let dz = self.length_offset - h;
        self.set_length_offset(h);
        if dz != 0.0 && self.known[2] {
            let (first, before) = self.offset_change.unwrap_or((line, 0.0));
            self.offset_change = Some((first, before + dz));
        }
    }
}

/// Whether a canned cycle is in force: the block drills from where the tool is.
fn in_cycle(s: &State) -> bool {
    s.motion >= 81 && s.motion != NO_MOTION
}

/// What the rules need to know of a block's motion.
pub(super) struct Moves {
    /// Its `X Y Z` words.
    pub(super) target: [Option<f64>; 3],
    /// `G28` or `G30`.
    pub(super) home: bool,
    /// `G53`.
    pub(super) g53: bool,
    /// A rotary or external axis word, or an arc's centre or radius.
    pub(super) other: bool,
}

/// Whether the block moves the tool (an axis word, a home return, an arc's centre, a canned
/// cycle's hole).
fn moves(given: &Moves, s: &State) -> bool {
    given.target.iter().any(Option::is_some) || given.home || given.other || in_cycle(s)
}

/// The block's `Z` given absolutely: its own `Z` in `G90` or under `G53`, or a home return of
/// every axis.
fn absolute_z(given: &Moves, s: &State) -> bool {
    let all_home = given.home && given.target.iter().all(Option::is_none);
    given.target[2].is_some() && (!s.incremental || given.g53) || all_home
}

/// Applies the dialect's reading of a changed tool length offset and of a `G28` with an offset
/// in force to the block on `line` before it moves (module docs), or refuses it.
pub(super) fn before_motion(line: u64, given: &Moves, s: &mut State) -> Result<()> {
    s.take_up = 0.0;
    if !moves(given, s) {
        return Ok(());
    }
    home_cancel(line, given, s)?;
    let Some((changed, dz)) = s.offset_change else {
        return Ok(());
    };
    let cycle = in_cycle(s);
    if !cycle && absolute_z(given, s) {
        s.offset_change = None;
        return Ok(());
    }
    if !cycle && given.target[2].is_none() {
        // Z stays where it is in every reading: the change waits for the next Z.
        return Ok(());
    }
    match s.machine.dialect {
        Some(GcodeDialect::LinuxCnc | GcodeDialect::Grbl) => {}
        Some(d @ (GcodeDialect::Fanuc | GcodeDialect::Haas)) if cycle => {
            // The cycle positions over the hole before its first Z move: whether the change
            // is taken up there or at the rapid to R is not written in the manuals.
            return Err(at(line, format!("a canned cycle after the tool length offset changed on line {changed} without a Z move, on the dialect \"{d}\": the controller takes the change up at the next Z move, and the cycle positions over the hole first; give Z (G0 Z..) after the G43/G44/G49")));
        }
        Some(GcodeDialect::Fanuc | GcodeDialect::Haas) => {
            // The block counts from the programmed point before the change, and the
            // controller moves by the offset's change as well.
            s.position.z -= dz;
            s.take_up = dz;
        }
        // A home return's intermediate point where the tool is (`G28 G91 Z0`): Z goes home
        // from there in every reading.
        None if given.home && given.target[2] == Some(0.0) => {}
        None => {
            let what = if cycle {
                "a canned cycle (it starts from the level where the tool is)"
            } else {
                "Z in G91"
            };
            return Err(at(line, format!("{what} after the tool length offset changed on line {changed} without a Z move: LinuxCNC counts from where the tool is, FANUC and Haas move by the offset's change as well ({:.4} mm apart here); {OPTION}", dz.abs() * 1e3)));
        }
    }
    s.offset_change = None;
    Ok(())
}

/// A `G28` with a tool length offset in force: refused at the next absolute `Z` where the
/// dialect's rule is not known (module docs).
fn home_cancel(line: u64, given: &Moves, s: &mut State) -> Result<()> {
    let Some(home) = s.home_cancel else {
        return Ok(());
    };
    if given.home || !(absolute_z(given, s) || in_cycle(s)) {
        return Ok(());
    }
    let who = match s.machine.dialect {
        Some(GcodeDialect::Fanuc) => {
            "the FANUC dialect: whether G28 cancels it is a setting of the control"
        }
        _ => "Haas cancels it at G28, LinuxCNC keeps it",
    };
    let fix = match s.machine.dialect {
        None => format!("{OPTION}, or "),
        _ => String::new(),
    };
    Err(at(line, format!("Z after the G28 of line {home}, made with a tool length offset in force ({who}): {fix}state G43 H.. or G49 again after the G28")))
}

/// At a `G28` on `line` (`named`: the axes its block names): Haas cancels the tool length
/// offset in force (Z sent home takes it up there); the dialects whose rule is not known here
/// keep the line for [`home_cancel`].
pub(super) fn at_home(line: u64, (code, named): (u8, [bool; 3]), s: &mut State) {
    if code != 28 || s.length_offset == 0.0 {
        return;
    }
    match s.machine.dialect {
        Some(GcodeDialect::LinuxCnc | GcodeDialect::Grbl) => {}
        Some(GcodeDialect::Haas) if named[2] || !named.iter().any(|n| *n) => {
            s.set_length_offset(0.0);
        }
        Some(GcodeDialect::Haas) => s.change_length_offset(line, 0.0),
        Some(GcodeDialect::Fanuc) | None => s.home_cancel = Some(line),
    }
}

/// `G43`/`G44` with `H` on a grbl: refused (grbl 1.1 has no tool table, only `G43.1`).
pub(super) fn length_offset_allowed(line: u64, g: u8, s: &State) -> Result<()> {
    if s.machine.dialect == Some(GcodeDialect::Grbl) {
        return Err(at(line, format!("G{g}: grbl has no tool table (its tool length offset is G43.1, set at run time); the setup says [controller] dialect = \"grbl\"")));
    }
    Ok(())
}

/// Whether `G53` under `G91` may be read as absolute machine coordinates: LinuxCNC and grbl
/// read it so; a rapid the setup gives no `G53` frame for leaves the axes it names unknown in
/// every reading (machine coordinates, or increments as Mitsubishi's M700V reads them: the
/// next point is where the program gives them again); `Err` naming the line otherwise.
pub(super) fn g53_in_g91(line: u64, s: &State) -> Result<()> {
    if s.motion == 0 && s.offset("G53").is_none() {
        return Ok(());
    }
    match s.machine.dialect {
        Some(GcodeDialect::LinuxCnc | GcodeDialect::Grbl) => Ok(()),
        Some(d) => Err(at(line, format!("G53 in G91 on the dialect \"{d}\": stiffid does not know whether this controller reads the words as machine coordinates or increments (LinuxCNC and grbl read them absolute, Mitsubishi's M700V as increments); write G90 before it"))),
        None => Err(at(line, format!("G53 in G91: controllers differ on what its words are (LinuxCNC and grbl read absolute machine coordinates, Mitsubishi's M700V increments); write G90 before it, or {OPTION}"))),
    }
}
