//! The frame and the tool length offset in force, and which axes are known: a controller
//! starts where the machine is, which the program does not say. As LinuxCNC's interpreter does
//! (`G0 X1 Y2` moves X and Y only, from wherever the machine is), an axis is known once a
//! block gives it absolutely (or a `G28`/`G30` sends it home), or from the start when the setup
//! states the start (`[workpiece] start_mm`). Rapids before every axis is known make no point:
//! the first point is the first place they reach with `X Y Z` all known, reached by the robot
//! in one move from wherever it is (a rapid in the air, as the first move of every robot
//! program). A feed, an arc or a canned cycle from a place not known is refused naming the
//! line.

use super::machine::{self, Frame, Lift};
use super::{at, external_values, may_move, GCode, Motion, Point, State};
use nalgebra::{Point3, UnitQuaternion, Vector3};
use stiffid_core::Result;

/// What to do about an axis not known (module docs).
pub(super) const UNKNOWN_HELP: &str = "the controller starts where the machine is, which the program does not say: give X Y Z in a rapid (G0) first, or state where the tool tip is when the program starts in the setup ([workpiece] start_mm, G54 part frame)";

impl State {
    /// The start: the setup's, or nothing known.
    pub(super) fn start(&mut self) {
        let Some(tip) = self.machine.frames.start else {
            return;
        };
        let lift = self.lift();
        let p = tip - Vector3::z() * lift.unwrap_or(0.0);
        self.position = p;
        self.known = [true, true, lift.is_some()];
    }

    /// The tool in use named by a `T` before the program's first tool change: the spindle has
    /// held it since the start, so the start's `Z`, unknown for want of its length, is known
    /// now (while no block has moved or left `Z` and the part frame `G54` is in force).
    pub(super) fn first_tool_named(&mut self) {
        let Some(tip) = self.machine.frames.start else {
            return;
        };
        if self.known[2] || self.left_unknown[2].is_some() || self.frame.name != "G54" {
            return;
        }
        if let Some(lift) = self.lift() {
            (self.position.z, self.known[2]) = (tip.z - lift, true);
        }
    }

    /// The tip's lift from the programmed point in force (module docs of [`machine`]).
    pub(super) fn lift(&self) -> Lift {
        if self.machine.tool_lengths.is_empty() {
            return Some(0.0);
        }
        let length = self.machine.tool_length(self.tool_number)?;
        Some(self.length_offset - length)
    }

    /// The tip's lift from the spindle's gauge line, the tool length offset not applied: the
    /// point `G53`'s coordinates place (LinuxCNC, FANUC), under `G43` and `G49` alike.
    pub(super) fn spindle_lift(&self) -> Lift {
        if self.machine.tool_lengths.is_empty() {
            return Some(0.0);
        }
        Some(-self.machine.tool_length(self.tool_number)?)
    }

    /// Puts `frame` in force, the position carried into it.
    pub(super) fn set_frame(&mut self, frame: Frame) {
        let lift = self.lift();
        let (p, k) = machine::convert(
            (self.position, self.known),
            (&self.frame, lift),
            (&frame, lift),
        );
        (self.position, self.known, self.frame) = (p, k, frame);
    }

    /// Puts the tool length offset `h` (m) in force: the machine does not move, so the
    /// programmed coordinates of where it is change by the offset's change (LinuxCNC, G43).
    pub(super) fn set_length_offset(&mut self, h: f64) {
        self.position.z += self.length_offset - h;
        self.length_offset = h;
    }

    /// The tip at the programmed point `p` of `frame` with `lift` (`None`: the tool in use has
    /// no length), `G54` part frame, m.
    pub(super) fn tip(
        &self,
        line: u64,
        p: &Vector3<f64>,
        (frame, lift): (&Frame, Lift),
    ) -> Result<Vector3<f64>> {
        let lift = lift.ok_or_else(|| self.no_length(line))?;
        if frame.part_from == nalgebra::Isometry3::identity() && lift == 0.0 {
            // The part frame itself: the programmed point, to the last bit.
            return Ok(*p);
        }
        Ok((frame.part_from * Point3::from(p + Vector3::z() * lift)).coords)
    }

    /// The error for a point while the tool in use has no length in the table.
    pub(super) fn no_length(&self, line: u64) -> stiffid_core::Error {
        match self.tool_number {
            Some(t) => at(line, format!("the tool in use (T{t}) has no length in the process's tool table ([tool] length_mm of the operation with its tool_number), and the tool length offset G43/G44/G49 in force needs it to place the tip")),
            None => at(line, "no tool named yet (no T word before this line): the spindle holds whatever tool the machine holds, whose length the program does not say, and the tip depends on it; name the tool (T1 M6) before this motion, or give one length for every tool (a process of one operation without tool_number)".into()),
        }
    }

    /// An error unless every axis is known (module docs), naming what moves from there.
    pub(super) fn known(&self, line: u64, what: &str) -> Result<()> {
        match self.known.iter().position(|k| !k) {
            None => Ok(()),
            Some(i) => {
                let mut known = [true; 3];
                known[i] = false;
                Err(at(
                    line,
                    format!("{what} from a place not known: {}", self.unknown(known)),
                ))
            }
        }
    }

    /// The axes `known` says are not, and why: the block that left one unknown
    /// ([`State::left_unknown`]), else the program's start ([`UNKNOWN_HELP`]).
    pub(super) fn unknown(&self, known: [bool; 3]) -> String {
        let missing = (0..3).filter(|k| !known[*k]);
        let names: Vec<&str> = missing.clone().map(|k| ["X", "Y", "Z"][k]).collect();
        let names = names.join(" ");
        match missing.filter_map(|k| self.left_unknown[k]).max() {
            Some((line, why)) => format!("{names} has no value since line {line} ({why}): give it again in a rapid (G0) before this move"),
            None => format!("{names} has no value yet ({UNKNOWN_HELP})"),
        }
    }

    /// Leaves the axes `named` unknown from the block on `line`, saying `why`.
    pub(super) fn leave_unknown(&mut self, line: u64, named: [bool; 3], why: &'static str) {
        for k in (0..3).filter(|k| named[*k]) {
            (self.known[k], self.left_unknown[k]) = (false, Some((line, why)));
        }
    }

    /// The programmed coordinates of a tip in the frame and tool length offset in force;
    /// `None` while the tool in use has no length.
    pub(super) fn to_program(&self) -> Option<nalgebra::Isometry3<f64>> {
        Some(machine::to_program(&self.frame, self.lift()?))
    }

    /// The shift from a programmed `Z` to the part frame's `Z` in the work offset and tool
    /// length offset in force, m (a canned cycle drills along the part's `Z`), or the error
    /// naming the line: the tool in use without a length, or a work offset that turns the
    /// part's `Z` axis.
    pub(super) fn part_z_shift(&self, line: u64, what: &str) -> Result<f64> {
        let lift = self.lift().ok_or_else(|| self.no_length(line))?;
        let part_from = &self.frame.part_from;
        if (part_from.rotation * Vector3::z() - Vector3::z()).norm() > 1e-12 {
            return Err(at(line, format!("{what} in the work offset {}, whose Z axis is not the part's: stiffid drills along the part's Z", self.frame.name)));
        }
        Ok(part_from.translation.vector.z + lift)
    }
}

/// The frame of the work offset `name` the setup gives, or the error naming the line.
pub(super) fn frame(line: u64, name: String, s: &State) -> Result<Frame> {
    match s.offset(&name) {
        // A G92 shift in force shifts every work offset alike (module `g92`).
        Some(part_from) => Ok(Frame {
            name,
            part_from: part_from * nalgebra::Translation3::from(s.g92),
        }),
        None => Err(at(line, format!("{name}: the setup gives no frame for this work offset: give it under [workpiece.offsets] ({} = {{ xyz_mm = [..], rpy_deg = [..] }}, its frame in the G54 part frame)", toml_key(&name)))),
    }
}

/// `name` as a TOML key (quoted when it has a dot or a blank).
fn toml_key(name: &str) -> String {
    match name.contains(['.', ' ']) {
        true => format!("\"{name}\""),
        false => name.to_string(),
    }
}

/// The move's end point in m from the block's `X Y Z` (absolute or incremental, mm or inch),
/// from `from` (with the axes known), and the axes known there.
pub(super) fn end_point(
    line: u64,
    target: &[Option<f64>; 3],
    from: (Vector3<f64>, [bool; 3]),
    s: &State,
) -> Result<(Vector3<f64>, [bool; 3])> {
    let scale = if s.inch { 25.4e-3 } else { 1e-3 };
    let (mut end, mut known) = from;
    for k in 0..3 {
        if let Some(v) = target[k] {
            end[k] = if s.incremental {
                end[k] + v * scale
            } else {
                v * scale
            };
            known[k] |= !s.incremental;
        }
    }
    if !end.iter().all(|v| v.abs() <= 100.0) {
        return Err(at(line, "position beyond 100 m".into()));
    }
    Ok((end, known))
}

/// The points at `positions` (programmed, in `frame` with `lift`) added to `out` as tips in the
/// `G54` part frame.
pub(super) fn push_points(
    line: u64,
    positions: &[Vector3<f64>],
    motion: Motion,
    (frame, lift): (&Frame, Lift),
    s: &mut State,
    out: &mut GCode,
) -> Result<()> {
    let tool = may_move(line, s)?;
    let external = external_values(line, s)?;
    let [a, b, c] = s.abc.map(f64::to_radians);
    let mut orientation = UnitQuaternion::from_euler_angles(a, b, c) * tool;
    let turn = super::rotation::tool_turn(frame, s);
    if turn != UnitQuaternion::identity() {
        orientation = turn * orientation;
    }
    for p in positions {
        out.points.push(Point {
            line,
            position: s.tip(line, p, (frame, lift))?,
            orientation,
            motion,
            tool_number: s.tool_number,
            operation: s.operation.clone(),
            feed: s.feed,
            cycle: None,
            external: external.clone(),
        });
    }
    Ok(())
}

/// The error for a motion that needs every axis known and lacks one.
pub(super) fn refuse_unknown(
    line: u64,
    what: &str,
    known: [bool; 3],
    s: &State,
) -> stiffid_core::Error {
    at(
        line,
        format!("{what} from or to a place not known: {}", s.unknown(known)),
    )
}
