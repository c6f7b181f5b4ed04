//! FANUC LS frames held on the controller by number (`UF : n`, `UT : n`, `UFRAME_NUM=n`,
//! `UTOOL_NUM=n`), which an LS program cannot state: how stiffid takes them (module docs of
//! [`crate::program::cartesian`]).
//!
//! - `UF : 0` is the controller's world; `UT : 0` its flange (the tool frame of no tool).
//! - `UF : F`, `UT : F` is the frame in force where the motion runs: the number the last
//!   `UFRAME_NUM=`/`UTOOL_NUM=` before it selects (as a FANUC position register follows the
//!   frames selected when it is used), refused naming the line where the program selects none.
//! - `UF : n` (n >= 1) is the setup's `[controller] bases` frame `n`, `UT : n` its `tools` frame
//!   `n` ([`Frame::Numbered`]), refused naming the line where the setup does not give it;
//!   unless a remark declares the number the setup's own frame: `! stiffid: user_frame = n ;`
//!   the part frame (the setup's `[workpiece]`), `! stiffid: tool_frame = n ;` the setup's
//!   `[tool]` ([`Frame::Declared`]); a program stiffid wrote declares its tool frame with the
//!   remark its writer puts first, `! set UTOOL[1] to the tool: ;`.
//! - The frame numbers in force: a position's `UF` and `UT` are the frames the controller moves
//!   it in only when they are the ones selected by `UFRAME_NUM=` and `UTOOL_NUM=` (the last
//!   before the motion; none in the program: the controller's, which must be the position's).
//!   A position whose numbers differ stops the program with the controller's frame-number
//!   mismatch alarm (the INTP alarms "Uframe number mismatch", "Utool number mismatch"), or,
//!   where the integrator switched that check off, moves in the selected frame instead: which of
//!   the two the controller does is not in the program, so stiffid refuses the motion naming its
//!   line. A number selected from a register
//!   (`UFRAME_NUM=R[i]`) is refused naming that line for every Cartesian position after it.

use super::cartesian::IN_FORCE;
use super::statements::{Number, Selected};
use crate::program::cartesian::Frame;
use crate::program::{at, lines, JointTarget};
use stiffid_core::Result;

/// The remark naming the user frame that holds the part frame.
const USER_FRAME: &str = "stiffid: user_frame";
/// The remark naming the tool frame that holds the setup's tool.
const TOOL_FRAME: &str = "stiffid: tool_frame";

/// The frame numbers a program's remarks declare the setup's own (module docs): the user frame
/// holding the part frame and the tool frame holding the setup's tool, each with its remark's
/// line. They are facts of the controller, so a program called from the backup takes its
/// caller's ([`Declared::within`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(super) struct Declared {
    /// `! stiffid: user_frame = n ;`.
    pub user: Option<(u64, u32)>,
    /// `! stiffid: tool_frame = n ;`, or the writer's `! set UTOOL[n] to the tool: ;`.
    pub tool: Option<(u64, u32)>,
}

impl Declared {
    /// The declarations of the LS program `text`.
    ///
    /// # Errors
    /// [`stiffid_core::Error::Program`] naming the line of a remark without a frame number, or
    /// of a second remark naming another frame.
    pub(super) fn of(text: &str) -> Result<Self> {
        Ok(Declared {
            user: declared(text, USER_FRAME)?,
            tool: declared(text, TOOL_FRAME)?.or_else(|| written_tool(text)),
        })
    }

    /// The declarations in force in the program `text` called on `line` by a program declaring
    /// `self`: its own, else the caller's.
    ///
    /// # Errors
    /// [`stiffid_core::Error::Program`] naming the call's line, a called program whose remark
    /// declares another frame number than its caller's.
    pub(super) fn within(self, text: &str, line: u64) -> Result<Self> {
        let own = Declared::of(text)?;
        let pick = |mine: Option<(u64, u32)>, theirs: Option<(u64, u32)>, key: &str| {
            match (mine, theirs) {
            (Some((l, m)), Some((_, n))) if m != n => Err(at(line, format!("{key} = {m} (the called program's line {l}): the caller declares {n}; one frame is the program's"))),
            (Some(m), _) => Ok(Some(m)),
            (None, t) => Ok(t),
        }
        };
        Ok(Declared {
            user: pick(own.user, self.user, USER_FRAME)?,
            tool: pick(own.tool, self.tool, TOOL_FRAME)?,
        })
    }
}

/// The rule (module docs) applied to the Cartesian `targets` of an LS program declaring
/// `declared`, each moved to with the frame numbers `selected` in force: a frame it refuses
/// becomes [`Frame::Unknown`] saying why, which resolving the target reports on its line.
pub(super) fn apply(declared: Declared, targets: &mut [JointTarget], selected: &[Selected]) {
    let Declared { user, tool } = declared;
    for (t, s) in targets.iter_mut().zip(selected) {
        let line = t.line;
        let Some(c) = t.cartesian.as_deref_mut() else {
            continue;
        };
        c.frame = frame(&c.frame, user, s.user.as_ref(), (line, Kind::User));
        c.tool = frame(&c.tool, tool, s.tool.as_ref(), (line, Kind::Tool));
    }
}

/// A user or a tool frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    User,
    Tool,
}

impl Kind {
    /// The position's word (`UF`) and the instruction selecting it (`UFRAME_NUM`).
    fn words(self) -> (&'static str, &'static str) {
        match self {
            Kind::User => ("UF", "UFRAME_NUM"),
            Kind::Tool => ("UT", "UTOOL_NUM"),
        }
    }
}

/// The frame a position gives (`given`) as stiffid takes it on the motion on `line`: checked
/// against the number `selected` in force, the number a remark `declared` the setup's own.
fn frame(
    given: &Frame,
    declared: Option<(u64, u32)>,
    selected: Option<&Number>,
    (line, kind): (u64, Kind),
) -> Frame {
    let (word, instruction) = kind.words();
    let (l, mut n) = match given {
        Frame::Numbered(l, n) => (*l, *n),
        Frame::World => (line, 0),
        other => return other.clone(),
    };
    if let Some(Number::Paths(why)) = selected {
        return Frame::Unknown(line, format!("{word} : {}: {why}", shown(n)));
    }
    if n == IN_FORCE {
        match selected {
            Some(Number::Literal(_, m)) => n = *m,
            Some(Number::Unread(..) | Number::Paths(_)) => {}
            None => return Frame::Unknown(line, format!("{word} : F: the position is in the frame in force where it runs, and no {instruction}=n before this motion selects one: the controller's, which the program does not say; select it by number ({instruction}=n) before the motion")),
        }
    }
    match selected {
        Some(Number::Literal(s, m)) if *m != n => {
            return Frame::Unknown(line, format!("{word} : {n}: the position is in frame {n}, and {instruction}={m} on line {s} is in force: the controller stops such a motion with a frame-number mismatch alarm, or, with the check switched off, moves in frame {m}; select {instruction}={n} before the motion or give the position in frame {m}"));
        }
        Some(Number::Unread(s, text)) => {
            return Frame::Unknown(*s, format!("{text}: the frame number is held in a register on the controller, which the program does not state; select the frame by number ({instruction}=n)"));
        }
        _ => {}
    }
    match (n, declared) {
        (0, _) => Frame::World,
        (n, Some((remark, d))) if d == n => Frame::Declared(remark, n),
        (n, _) => Frame::Numbered(l, n),
    }
}

/// A position's frame number as written (`F`: the one in force).
fn shown(n: u32) -> String {
    match n {
        IN_FORCE => "F".into(),
        n => n.to_string(),
    }
}

/// The tool frame number of the remark stiffid's LS writer puts first in a program it writes
/// ([`super::generate::header`]), `! set UTOOL[n] to the tool: ;`, and its line: the writer's
/// declaration that tool frame `n` holds the setup's tool.
fn written_tool(text: &str) -> Option<(u64, u32)> {
    const OPEN: &str = "! set UTOOL[";
    lines(text).find_map(|(line, _, l)| {
        let rest = &l[l.find(OPEN)? + OPEN.len()..];
        let (n, tail) = rest.split_once(']')?;
        tail.starts_with(" to the tool:")
            .then(|| n.parse().ok().map(|n| (line, n)))
            .flatten()
    })
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
