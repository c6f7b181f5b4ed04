//! FANUC LS frames held on the controller by number (`UF : n`, `UT : n`), which an LS program
//! cannot state: which of them stiffid takes, and which it refuses (module docs of [`crate::program::cartesian`]).
//!
//! - `UF : 0` is the controller's world.
//! - `UF : n`, n >= 1, is the part frame (the setup's `[workpiece]`) only when the program
//!   says so in a remark, `! stiffid: user_frame = n ;`; a position in any other user frame is
//!   refused naming its line (that frame's value is on the controller only).
//! - `UT : n`: one tool frame holds every position, the one that holds the setup's tool: the
//!   frame the remark `! stiffid: tool_frame = n ;` names, else the first position's; a
//!   position for another is refused naming its line.

use crate::program::cartesian::Frame;
use crate::program::{at, lines, JointTarget};
use stiffid_core::Result;

/// The remark naming the user frame that holds the part frame.
const USER_FRAME: &str = "stiffid: user_frame";
/// The remark naming the tool frame that holds the setup's tool.
const TOOL_FRAME: &str = "stiffid: tool_frame";

/// The rule (module docs) applied to the Cartesian `targets` of the LS program `text`: a frame
/// it refuses becomes [`Frame::Unknown`] saying why, which resolving the target reports on its
/// position's line.
///
/// # Errors
/// [`stiffid_core::Error::Program`] naming the line of a remark without a frame number, or of a
/// second remark naming another frame.
pub(crate) fn apply(text: &str, targets: &mut [JointTarget]) -> Result<()> {
    let user = declared(text, USER_FRAME)?;
    let first_tool =
        (targets.iter().filter_map(|t| t.cartesian.as_deref())).find_map(|c| match c.tool {
            Frame::Numbered(l, n) => Some((l, n)),
            _ => None,
        });
    let tool = declared(text, TOOL_FRAME)?.or(first_tool);
    for c in targets
        .iter_mut()
        .filter_map(|t| t.cartesian.as_deref_mut())
    {
        if let Frame::Numbered(l, n) = c.frame {
            c.frame = match user {
                Some((_, u)) if u == n => Frame::Declared(l),
                Some((d, u)) => Frame::Unknown(l, format!("UF : {n}: the program names user frame {u} the part frame (line {d}); user frame {n} is held on the controller, which the program does not state: give the position in UF : {u} or in the world, UF : 0")),
                None => Frame::Unknown(l, format!("UF : {n}: a user frame held on the controller, which the program does not state: say that it holds the part frame (the setup's [workpiece]) with the remark `! {USER_FRAME} = {n} ;`, or give the positions in the world, UF : 0")),
            };
        }
        if let (Frame::Numbered(l, n), Some((d, t))) = (c.tool.clone(), tool) {
            c.tool = match n == t {
                true => Frame::Declared(l),
                false => Frame::Unknown(l, format!("UT : {n}: the program's positions are for tool frame {t} (line {d}), the one that must hold the setup's tool; give every position in UT : {t}")),
            };
        }
    }
    Ok(())
}

/// The frame number the remark `key = n` declares and its line; `None` without one.
fn declared(text: &str, key: &str) -> Result<Option<(u64, u32)>> {
    let mut found: Option<(u64, u32)> = None;
    for (line, _, l) in lines(text) {
        let Some(start) = l.find(key) else { continue };
        let n = (l[start + key.len()..].trim_start().strip_prefix('='))
            .and_then(|r| r.trim_start().split(|c: char| !c.is_ascii_digit()).next())
            .and_then(|d| d.parse::<u32>().ok());
        let Some(n) = n else {
            return Err(at(
                line,
                format!("{key}: expected = and a frame number, `! {key} = 1 ;`"),
            ));
        };
        match found {
            Some((first, m)) if m != n => {
                return Err(at(
                    line,
                    format!(
                    "{key} = {n}: the remark on line {first} names {m}; one frame is the program's"
                ),
                ))
            }
            Some(_) => {}
            None => found = Some((line, n)),
        }
    }
    Ok(found)
}
