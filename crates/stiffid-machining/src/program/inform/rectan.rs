//! A job's positions in Cartesian form (module docs of [`super`]): `///POSTYPE BASE`, `ROBOT`
//! or `USER` with `///RECTAN`, `C00000=X,Y,Z,Rx,Ry,Rz` (mm, deg: `Rz Ry Rx`, the coordinate
//! system turned about its Z, then Y, then X: the DX100 job data format, "Configuration of
//! position data"), the manipulator type of the `///RCONF` before it, the user frame of the
//! `///USER n` before it and the tool file of the `///TOOL n` before it (or the motion's
//! `TOOL#(n)`): read as a Cartesian target ([`crate::program::cartesian`]).

use super::inst::Motion;
use super::pos::Position;
use super::{toolcnd, uframe};
use crate::program::cartesian::{within_limits, Cartesian, Flags, Frame};
use crate::program::{at, Context, Dialect};
use stiffid_core::setup::NumberedFrames;
use stiffid_core::Result;

/// The numbers of a position, in order.
const NAMES: [&str; 6] = ["X", "Y", "Z", "Rx", "Ry", "Rz"];

/// The frames the controller's backup gives by number: its tool files (`TOOL.CND`) and user
/// frames (`UFRAME.CND`).
pub(super) struct Held<'a> {
    tools: Numbered<'a>,
    users: Numbered<'a>,
}

/// The frames of one kind by number: the backup's file's (its name when given) and the
/// setup's `[controller]` table's, with their names for messages (`tool file`, `tools`).
struct Numbered<'a> {
    held: std::collections::BTreeMap<u32, (nalgebra::Isometry3<f64>, String)>,
    file: Option<&'a str>,
    table: Option<&'a NumberedFrames>,
    names: (&'static str, &'static str),
}

impl<'a> Held<'a> {
    /// The frames of the `context`'s backup.
    ///
    /// # Errors
    /// Those of reading `TOOL.CND` and `UFRAME.CND`.
    pub(super) fn of(context: &Context<'a>) -> Result<Self> {
        let file = |name: &str| context.backup_file(name).map(|(n, _)| n);
        Ok(Held {
            tools: Numbered {
                held: toolcnd::tools(context)?,
                file: file(toolcnd::FILE),
                table: context.tool.map(|(_, t)| t),
                names: ("tool file", "tools"),
            },
            users: Numbered {
                held: uframe::frames(context)?,
                file: file(uframe::FILE),
                table: context.bases,
                names: ("user frame", "bases"),
            },
        })
    }
}

/// Frame number `n` selected on `line`: the backup's where it gives it, else one of the
/// setup's `[controller]` tables (checked where the target is resolved); refused naming the
/// backup's file where it is given and neither gives it.
fn by_number(frames: &Numbered, (line, n): (u64, u32)) -> Frame {
    match (frames.held.get(&n), frames.file) {
        (Some((f, source)), _) => Frame::Held(line, n, *f, source.clone()),
        (None, Some(file)) if frames.table.and_then(|t| t.get(n)).is_none() => {
            let (what, key) = frames.names;
            let list: Vec<String> = frames.held.keys().map(u32::to_string).collect();
            let gives = match list.is_empty() {
                true => format!("no {what}"),
                false => format!("{what}s {} only", list.join(", ")),
            };
            Frame::Unknown(line, format!("{what} {n}: the backup's {file} gives {gives}, and the setup's [controller] {key} none: give the backup holding the controller's {what} {n}, or the frame in [controller] {key} ({{ number = {n}, xyz_mm = [..], rpy_deg = [..] }})"))
        }
        (None, _) => Frame::Numbered(line, n),
    }
}

/// The Cartesian target of motion `m` to the position `p` in Cartesian form (module docs).
///
/// # Errors
/// [`stiffid_core::Error::Program`] naming the line: a position that is not six numbers or out
/// of limits, in tool coordinates (`TOOL`, `MTOOL`: relative to where the tool is), or in robot
/// coordinates on a base axis (they move with the robot).
pub(super) fn target(m: &Motion, p: &Position, held: &Held) -> Result<Cartesian> {
    let name = format!("C{:05}", m.robot);
    if p.values.len() != 6 {
        let n = p.values.len();
        return Err(at(p.line, format!("{name}: expected 6 values X,Y,Z,Rx,Ry,Rz, found {n} (a seventh, Re, is a seven-axis robot's; stiffid compensates six axes)")));
    }
    within_limits(p.line, &NAMES, &p.values)?;
    let mut c = Cartesian::new(Dialect::Inform, &p.values);
    c.flags = p.rconf.map(|(_, r)| Flags::new(r));
    let postype = p.frame.split_whitespace().next().unwrap_or("");
    let refuse = |why: &str| {
        Err(at(
            m.line,
            format!(
                "{} {name}: ///POSTYPE {postype} (line {}): {why}",
                m.word, p.line
            ),
        ))
    };
    c.frame = match postype {
        "BASE" => Frame::World,
        "ROBOT" if m.base.is_some() => {
            return refuse("robot coordinates, which move with the robot on its base axis (BC); stiffid reads a Cartesian position on a track in base or user coordinates: teach or post it there")
        }
        "ROBOT" => Frame::World,
        "USER" => match p.user {
            Some(user) => by_number(&held.users, user),
            None => Frame::Unknown(m.line, format!("{} {name}: a position in user coordinates with no ///USER n before it (line {}): which user frame is the controller's, which the job does not say", m.word, p.line)),
        },
        _ => {
            return refuse("tool coordinates, relative to where the tool is when the motion starts, which the job does not say; stiffid reads positions in base, robot or user coordinates")
        }
    };
    c.tool = match m.tool.map(|n| (m.line, n)).or(p.tool) {
        Some(tool) => by_number(&held.tools, tool),
        None => Frame::Unknown(m.line, format!("{} {name}: a Cartesian position with no ///TOOL n before it (line {}) and no TOOL#(n) on the motion: its pose is of the controller's tool, which the job does not say", m.word, p.line)),
    };
    Ok(c)
}
