//! Machine coordinates `G53` in a motion block: the setup's (or the program's, module `g10`)
//! frame of them, or, for a rapid without one, the axes it names left unknown.

use super::{at, GCode, State};
use stiffid_core::Result;

/// `G53`'s frame: machine coordinates with `G0` or `G1` (LinuxCNC refuses it with an arc), its
/// words absolute (in `G91` as the dialect says: module `dialect`). `None` for a rapid when the
/// setup gives no `G53` frame ([`unplaced_machine_move`]).
pub(super) fn machine_frame(line: u64, s: &State) -> Result<Option<super::machine::Frame>> {
    if s.motion >= 2 {
        return Err(at(line, "G53: machine coordinates move with G0 or G1 only, not with an arc (LinuxCNC refuses it)".into()));
    }
    match s.offset("G53") {
        Some(part_from) => Ok(Some(super::machine::Frame { name: "G53".into(), part_from })),
        None if s.motion == 0 => Ok(None),
        None => Err(at(line, "G53: the setup gives no frame for machine coordinates, which a feed (G1) to them needs: give it under [workpiece.offsets] (G53 = { xyz_mm = [..], rpy_deg = [..] }, its frame in the G54 part frame); a rapid (G0 or the G0 in force) to machine coordinates without it makes the axes it names unknown".into())),
    }
}

/// A `G53` rapid the setup gives no frame for: the machine goes where the setup does not say
/// (a retract to machine Z0, a park), so the axes it names are unknown until the program gives
/// them again, as at the program's start (module docs of `modal`), and it makes no point. The
/// line is kept ([`GCode::unplaced_g53`]): the robot goes from the point before it to the next
/// one in one move.
pub(super) fn unplaced_machine_move(
    line: u64,
    named: [bool; 3],
    s: &mut State,
    out: &mut GCode,
) -> Result<()> {
    s.leave_unknown(line, named, UNPLACED_G53);
    s.pending.get_or_insert(line);
    out.unplaced_g53.push(line);
    Ok(())
}

/// The error for `G53` in a block `G0`/`G1` does not move: a canned cycle in force, `G28`,
/// `G30` (LinuxCNC refuses `G53` unless `G0` or `G1` is in force).
pub(super) fn g53_outside_g0_g1(line: u64, home: Option<u8>, s: &State) -> stiffid_core::Error {
    let (what, fix) = match home {
        Some(g) => (
            format!("with G{g} in its block"),
            format!("write the G{g} and the G53 move in blocks of their own"),
        ),
        None => (
            format!("while the canned cycle G{} is in force", s.motion),
            "end the cycle with G80 and write G53 G0 (or G53 G1) in a block of its own".to_string(),
        ),
    };
    at(line, format!("G53 {what}: machine coordinates move with G0 or G1 only (LinuxCNC refuses G53 unless G0 or G1 is in force); {fix}"))
}

/// Why a `G53` rapid the setup does not place leaves the axes it names unknown.
const UNPLACED_G53: &str = "a G53 rapid there went to machine coordinates, which the setup does not place: no [workpiece.offsets] G53";
