//! The `/MN` instructions around an LS program's motions: which stiffid passes over (they cannot
//! change the path or the frames), which it follows (the frame numbers selected), and which it
//! refuses naming the line (FANUC R-30iA/R-30iB HandlingTool operator's manual, "Program
//! instructions").
//!
//! - Passed over: remarks `!`, lines commented out `//`, labels `LBL[i]`, `WAIT` (a time or a
//!   condition, without `TIMEOUT,LBL`), I/O (`DO[i]=`, `RO[i]=`, `GO[i]=`, `AO[i]=`, `F[i]=`),
//!   registers (`R[i]=`, `PR[i]=`, `SR[i]=`: a position register matters only to a motion to it
//!   or offset by it, which is refused), `TIMER[i]`, `PAYLOAD[i]`, `OVERRIDE`, `UALM`, `MESSAGE`,
//!   `PAUSE`, the offset conditions (`OFFSET CONDITION PR[i]`: only a motion's `Offset` uses it,
//!   and that is refused), `RUN` (a task started alongside: the controller refuses a second
//!   program holding a motion group the first holds, so it cannot move this program's groups),
//!   a `CALL` before the first motion or after the last, and every other instruction that neither
//!   moves nor selects a frame (nor names a position `P[i]` but in an assignment's value: a
//!   motion whose keyword is lost, `X P[8] ..`, is refused).
//! - Followed: `UFRAME_NUM=n` and `UTOOL_NUM=n` (also `UFRAME_NUM[GP1]=n`, naming the robot's
//!   motion group), the user and tool frame numbers in force for the motions after them
//!   ([`Selected`]); another group's (`UTOOL_NUM[GP2]=n`) is refused naming the line.
//! - Jumps, branches and loops are the order of run's ([`super::flow`]); where an instruction
//!   sits among the motions is on that order ([`Place`]).
//! - Refused naming the line, in a program with motions: a `CALL` (also a branch's, `IF
//!   ..,CALL`) between two
//!   motions (the called program may move the robot between them), and so a macro instruction
//!   there (a program run by its name alone, `GO_HOME`, or with arguments, `OPEN_GRIP(1)`),
//!   but one of a program the controller's backup holds that moves nothing ([`super::calls`]);
//!   `Weave ..` and `Track ..` (ArcTool: weaving and seam tracking move the tool off
//!   the programmed path) before a motion; `Touch Offset PR[i]` (ArcTool touch sensing: the
//!   motions up to `Touch Offset End` are shifted by the offset it finds at run time, held in
//!   the register on the controller) before a motion; a frame's value set by the program
//!   (`UFRAME[i]=`, `UTOOL[i]=`, a system variable of the frames, `$MNUFRAME`, `$MNUTOOL`,
//!   `$UFRAME`, `$UTOOL`) before a motion; a frame number in a register (`UFRAME_NUM=R[i]`).
//!
//! A program a controller set to German writes is read as its English twin: `WENN` (`IF`),
//! `SPRUNG` (`JMP`), `SONST` (`ELSE`), `LABEL[i]` (`LBL[i]`), `AUFRUF` (`CALL`), `ENDE`
//! (`END`), `BENUTZER_NUM` (`UFRAME_NUM`), `WKZ_NUM` (`UTOOL_NUM`) ([`GERMAN`]).

use super::cartesian::MAX_FRAME;
use crate::program::at;
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// A frame number selected by `UFRAME_NUM=` or `UTOOL_NUM=`: the number and the line, or the
/// line and text of a selection stiffid cannot read (a register).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) enum Number {
    /// The number selected on the line.
    Literal(u64, u32),
    /// A number held on the controller: the line and the instruction.
    Unread(u64, String),
    /// A number the paths that reach the motion leave differently: why, naming their lines
    /// ([`Selected::join`]).
    Paths(String),
}

/// The user and tool frame numbers in force (`None`: none selected yet in the program).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub(super) struct Selected {
    /// `UFRAME_NUM`.
    pub user: Option<Number>,
    /// `UTOOL_NUM`.
    pub tool: Option<Number>,
}

impl Number {
    /// Whether `self` and `other` select one frame (the lines aside).
    fn same(&self, other: &Number) -> bool {
        match (self, other) {
            (Number::Literal(_, m), Number::Literal(_, n)) => m == n,
            (a, b) => a == b,
        }
    }

    /// The selection in words, for the instruction `word` (`UFRAME_NUM`).
    fn describe(&self, word: &str) -> String {
        match self {
            Number::Literal(l, n) => format!("{word}={n} (line {l})"),
            Number::Unread(l, t) => format!("{t} (line {l})"),
            Number::Paths(why) => why.clone(),
        }
    }
}

/// `a` joined with `b` where two paths meet on `line`, for the instruction `word`; whether `a`
/// changed.
fn join_number(a: &mut Option<Number>, b: &Option<Number>, word: &str, line: u64) -> bool {
    let describe = |n: &Option<Number>| match n {
        Some(n) => n.describe(word),
        None => format!("none (the controller's {word})"),
    };
    match (&*a, b) {
        (None, None) | (Some(Number::Paths(_)), _) => false,
        (Some(x), Some(y)) if x.same(y) => false,
        (_, Some(Number::Paths(_))) => {
            *a = b.clone();
            true
        }
        _ => {
            let why = format!("the {word} in force here depends on the path taken to line {line}: one path leaves {}, another {}; select it alike on every path", describe(a), describe(b));
            *a = Some(Number::Paths(why));
            true
        }
    }
}

impl Selected {
    /// `self` joined with `other` where two paths meet on `line`: a number both select alike
    /// stays, one they select differently becomes [`Number::Paths`] naming both; whether
    /// `self` changed.
    pub(super) fn join(&mut self, other: &Selected, line: u64) -> bool {
        let user = join_number(&mut self.user, &other.user, "UFRAME_NUM", line);
        let tool = join_number(&mut self.tool, &other.tool, "UTOOL_NUM", line);
        user || tool
    }
}

/// Where an instruction sits among the program's motions.
#[derive(Debug, Clone, Copy)]
pub(super) struct Place {
    /// A motion comes before it.
    pub after_first: bool,
    /// A motion comes after it.
    pub before_last: bool,
}

/// The instruction `t` on `line` (module docs): the frame numbers it selects into `selected`.
///
/// # Errors
/// Naming the line, an instruction refused at its `place` (module docs).
pub(super) fn instruction(line: u64, t: &str, place: Place, selected: &mut Selected) -> Result<()> {
    let upper = english(&t.trim().to_ascii_uppercase());
    let first = upper
        .split(|c: char| c.is_whitespace() || c == '[' || c == '(' || c == '=')
        .next()
        .unwrap_or("");
    let refuse = |why: &str| Err(at(line, format!("{}: {why}", short(t.trim()))));
    if names_a_position(&upper) {
        return refuse("names a position P[i] but is no motion stiffid reads (J, L or C P[i] ..); passed over, its target would be lost");
    }
    if let Some(n) = upper.strip_prefix("UFRAME_NUM") {
        selected.user = Some(number(line, t, n)?);
        return Ok(());
    }
    if let Some(n) = upper.strip_prefix("UTOOL_NUM") {
        selected.tool = Some(number(line, t, n)?);
        return Ok(());
    }
    if conditional_call(&upper).is_some() && place.after_first && place.before_last {
        return refuse("a call between two motions; the called program may move the robot between them, off the path the file gives: call it before the first motion or after the last, or give the controller's backup holding the program called (its .LS) if it moves nothing");
    }
    if macro_call(&upper) && place.after_first && place.before_last {
        return refuse("a macro (a program the controller runs by its name) between two motions; it may move the robot between them, off the path the file gives: run it before the first motion or after the last, or give the controller's backup holding it (its .LS) if it moves nothing");
    }
    let process_path = matches!(first, "WEAVE" | "TRACK") && !upper.ends_with("END");
    if process_path && place.before_last {
        return refuse("the motions after it weave across the path or follow a sensor (ArcTool), so the path the controller runs is not the file's: remove it or compensate the program without it");
    }
    if touch_offset(&upper) && place.before_last {
        return refuse("touch sensing (ArcTool) shifts every motion after it, up to Touch Offset End, by the offset the sensing finds at run time, held in a position register on the controller, not in this program; apply the offset to the positions and remove the Touch Offset lines");
    }
    if sets_frame(&upper) && place.before_last {
        return refuse("the program sets a frame's value, which stiffid reads from the setup's [controller] tools and bases (as the controller holds them before the program runs): set the frame on the controller and give it in the setup");
    }
    Ok(())
}

/// The program an instruction (upper case, English) calls: `CALL NAME ..`, or a branch's
/// action `IF R[1]=1,CALL NAME`, `SELECT R[1]=1,CALL NAME`, `=2,CALL NAME`, `ELSE,CALL NAME`;
/// the text after `CALL `.
pub(super) fn conditional_call(upper: &str) -> Option<&str> {
    let t = upper.trim();
    if let Some(rest) = t.strip_prefix("CALL ") {
        return Some(rest.trim_start());
    }
    let branch = ["IF ", "IF(", "SELECT ", "=", "ELSE"]
        .iter()
        .any(|w| t.starts_with(w));
    let (_, action) = t.rsplit_once(',').filter(|_| branch)?;
    action
        .trim_start()
        .strip_prefix("CALL ")
        .map(str::trim_start)
}

/// The instructions of one word alone (no macro, though written as one).
const ONE_WORD: &[&str] = &[
    "END",
    "PAUSE",
    "ABORT",
    "ELSE",
    "ENDIF",
    "ENDFOR",
    "ENDSELECT",
];

/// Whether `upper` is a macro instruction: a program's name alone (letters, digits and `_`,
/// a letter first), or with its arguments in parentheses (`OPEN_GRIPPER(1)`), not one of the
/// instructions of one word ([`ONE_WORD`]).
pub(super) fn macro_call(upper: &str) -> bool {
    let t = upper.trim();
    let name = t
        .split_once('(')
        .map_or(t, |(name, rest)| match rest.ends_with(')') {
            true => name,
            false => "",
        });
    name.starts_with(|c: char| c.is_ascii_alphabetic())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        && !ONE_WORD.contains(&name)
}

/// The keywords a FANUC controller set to German writes in its programs (as seen in real
/// controller backups), and the English ones they stand for.
const GERMAN: &[(&str, &str)] = &[
    ("WENN", "IF"),
    ("SPRUNG", "JMP"),
    ("SONST", "ELSE"),
    ("LABEL", "LBL"),
    ("AUFRUF", "CALL"),
    ("ENDE", "END"),
    ("BENUTZER_NUM", "UFRAME_NUM"),
    ("WKZ_NUM", "UTOOL_NUM"),
];

/// The instruction `upper` (upper case) with its German keywords ([`GERMAN`]) in English, word
/// by word, so that a German program is read as its English twin.
pub(super) fn english(upper: &str) -> String {
    let mut out = String::with_capacity(upper.len());
    let mut word = String::new();
    let flush = |word: &mut String, out: &mut String| {
        let g = GERMAN.iter().find(|(g, _)| *g == word.as_str());
        out.push_str(g.map_or(word.as_str(), |(_, e)| e));
        word.clear();
    };
    for c in upper.chars() {
        if c.is_ascii_alphanumeric() || c == '_' {
            word.push(c);
        } else {
            flush(&mut word, &mut out);
            out.push(c);
        }
    }
    flush(&mut word, &mut out);
    out
}

/// Whether the instruction (upper case) opens a touch offset (`TOUCH OFFSET PR[i]`, ArcTool's
/// touch sensing; its closing `TOUCH OFFSET END` does not).
fn touch_offset(upper: &str) -> bool {
    let mut words = upper.split_whitespace();
    words.next() == Some("TOUCH")
        && words.next().is_some_and(|w| w.starts_with("OFFSET"))
        && !upper.ends_with("END")
}

/// Whether the instruction (upper case, not a motion) names a position `P[i]` outside an
/// assignment's value (`PR[1]=P[3]` copies one): a motion its keyword lost (`X P[8] ..`,
/// `L] P[8] ..`), which the controller refuses to load.
fn names_a_position(upper: &str) -> bool {
    let before_value = upper.split('=').next().unwrap_or(upper);
    before_value.match_indices("P[").any(|(i, _)| {
        let previous = before_value[..i].chars().next_back();
        !previous.is_some_and(|c| c.is_ascii_alphanumeric() || c == '_' || c == '$')
    })
}

/// The number after `UFRAME_NUM`/`UTOOL_NUM` (`rest`, upper case) of instruction `t` on
/// `line`, also in the form naming the motion group, `UTOOL_NUM[GP1]=4` (as ROBOGUIDE writes
/// it), where the group is the robot's, group 1.
///
/// # Errors
/// Naming the line, a selection for another motion group (`UTOOL_NUM[GP2]=1`), or of a value
/// that is neither a frame number (0 to 999, as a position's `UF : n`) nor a register's
/// (`R[i]`, `AR[i]`, an expression in parentheses): `UFRAME_NUM=-1`, `UFRAME_NUM=1000`,
/// `UFRAME_NUM=`, which the controller does not load.
fn number(line: u64, t: &str, rest: &str) -> Result<Number> {
    let mut rest = rest.trim_start();
    if let Some(inner) = rest.strip_prefix('[') {
        let (group, after) = inner.split_once(']').unwrap_or((inner, ""));
        let group = group.trim();
        let number = group.strip_prefix("GP").map(|g| g.trim().parse::<u32>());
        if !matches!(number, Some(Ok(1))) {
            return Err(at(line, format!("{}: selects the frame of motion group {}; stiffid reads motion group 1 as the robot and follows only its frames (UFRAME_NUM=n, UTOOL_NUM=n, or with [GP1]): compensate a program of group 1", short(t.trim()), short(group))));
        }
        rest = after.trim_start();
    }
    let n = rest.strip_prefix('=').map(str::trim).unwrap_or("");
    match n.parse::<u32>() {
        Ok(n) if n <= MAX_FRAME => Ok(Number::Literal(line, n)),
        _ if n.starts_with(|c: char| c.is_ascii_alphabetic() || c == '(' || c == '$') => {
            Ok(Number::Unread(line, short(t.trim()).to_string()))
        }
        _ => Err(at(line, format!("{}: expected = and a frame number, 0 to {MAX_FRAME} (as a position's UF : n), or a register (R[i])", short(t.trim())))),
    }
}

/// Whether the instruction (upper case) assigns a frame's value: `UFRAME[i]=`, `UTOOL[i]=`, or
/// a system variable of the frames (`$MNUFRAME[..]=`, `$GROUP[..].$UTOOL=`).
pub(super) fn sets_frame(upper: &str) -> bool {
    let Some((lhs, _)) = upper.split_once('=') else {
        return false;
    };
    let lhs = lhs.trim();
    lhs.starts_with("UFRAME[")
        || lhs.starts_with("UTOOL[")
        || (lhs.starts_with('$') && (lhs.contains("FRAME") || lhs.contains("TOOL")))
}
