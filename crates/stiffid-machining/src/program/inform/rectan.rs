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
use stiffid_core::Result;

/// The numbers of a position, in order.
const NAMES: [&str; 6] = ["X", "Y", "Z", "Rx", "Ry", "Rz"];

/// The frames the controller's backup gives by number: its tool files (`TOOL.CND`) and user
/// frames (`UFRAME.CND`).
pub(super) struct Held {
    tools: toolcnd::Tools,
    users: uframe::Frames,
}

impl Held {
    /// The frames of the `context`'s backup.
    ///
    /// # Errors
    /// Those of reading `TOOL.CND` and `UFRAME.CND`.
    pub(super) fn of(context: &Context) -> Result<Self> {
        Ok(Held {
            tools: toolcnd::tools(context)?,
            users: uframe::frames(context)?,
        })
    }
}

/// Frame number `n` selected on `line`: the backup's where it gives it, else one of the
/// setup's `[controller]` tables (checked where the target is resolved).
fn by_number(
    held: &std::collections::BTreeMap<u32, (nalgebra::Isometry3<f64>, String)>,
    (line, n): (u64, u32),
) -> Frame {
    match held.get(&n) {
        Some((f, source)) => Frame::Held(line, n, *f, source.clone()),
        None => Frame::Numbered(line, n),
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
