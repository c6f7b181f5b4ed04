//! The process words of a block, kept in path order for the robot programs written from the
//! path: the spindle (`S`, `M3`, `M4`, `M5`), the coolant (`M7`, `M8`, `M9`), the tool (`T`,
//! `M6`), the end (`M2`, `M30`) and any other `M` word, each as the event it raises
//! ([`ProcessEvent`]) in the order a controller runs one block's words (LinuxCNC's "Order of
//! Execution", RS274/NGC 3.8: speed, tool select, tool change, spindle, coolant, then the
//! motion, then the stop): an `S` in a block with `M3`/`M4`, and a `T` in a block with `M6`, are
//! the value of that event, not events of their own.

use super::words::Word;
use super::State;
use stiffid_core::setup::program_io::ProcessEvent;

/// A process word (or the words of one event) of a G-code program.
#[derive(Debug, Clone, PartialEq)]
pub struct ProcessWord {
    /// The line of its block, 1-based.
    pub line: u64,
    /// The event it raises; `None` for an `M` word stiffid maps to none (written as a comment
    /// with a warning).
    pub event: Option<ProcessEvent>,
    /// Its words as the block gives them, for comments and warnings (`S5000 M3`).
    pub words: String,
    /// The spindle speed in force (the last `S`, rev/min).
    pub rpm: Option<f64>,
    /// The last tool selected (the last `T`, which an `M6` loads): the tool a tool event names.
    pub tool: Option<u32>,
    /// A dwell (`G4 P..`, the G-code reader's `dwell`): its time in seconds as the setup's controller reads
    /// it, or why the controller's reading is not known; `None`: no dwell.
    pub dwell: Option<std::result::Result<f64, String>>,
    /// The path point a dwell follows (a `G82`'s at the hole's bottom, the index into
    /// [`super::GCode::points`]): written after that point's target; `None`: before its block's
    /// motion, as every other word.
    pub point: Option<usize>,
}

/// A comment on a line of its own (no word in its block), kept to be written in the robot
/// program at its place between the motions: the CAM post's operation, tool and header
/// comments (Fusion 360 writes `(2D Contour1)` and `(T1 D=6. CR=0. - ZMIN=-1. - flat end mill)`
/// on lines of their own). A comment after a block's words explains that block and is not
/// kept; stiffid's own directives (`(stiffid: ..)`) are not kept.
#[derive(Debug, Clone, PartialEq)]
pub struct Comment {
    /// Its line, 1-based.
    pub line: u64,
    /// Its text, the parentheses or `;` and the blanks around it taken off; never empty.
    pub text: String,
}

/// The `M` codes that raise an event, with it.
const EVENTS: [(f64, ProcessEvent); 9] = [
    (6.0, ProcessEvent::ToolChange),
    (3.0, ProcessEvent::SpindleCw),
    (4.0, ProcessEvent::SpindleCcw),
    (5.0, ProcessEvent::SpindleOff),
    (7.0, ProcessEvent::CoolantMist),
    (8.0, ProcessEvent::CoolantFlood),
    (9.0, ProcessEvent::CoolantOff),
    (2.0, ProcessEvent::ProgramEnd),
    (30.0, ProcessEvent::ProgramEnd),
];

/// A word as written in comments: `S5000`, `M3`, `T1`.
fn text(w: &Word) -> String {
    format!("{}{}", w.letter, w.value)
}

/// Gathers the process words of one block (`words`, applied: `s` holds the `S` and `T` in
/// force) into `s.process`, in the order of execution (module docs).
pub(super) fn gather(line: u64, words: &[Word], s: &mut State) {
    let m: Vec<&Word> = words.iter().filter(|w| w.letter == 'M').collect();
    let has = |code: f64| m.iter().any(|w| w.value == code);
    let spindle_on = has(3.0) || has(4.0);
    let speed = words.iter().rev().find(|w| w.letter == 'S');
    if let Some(w) = speed {
        s.rpm = Some(w.value);
        if !spindle_on {
            push(s, line, Some(ProcessEvent::SpindleSpeed), text(w));
        }
    }
    let tool = words.iter().find(|w| w.letter == 'T');
    if let (Some(w), false) = (tool, has(6.0)) {
        push(s, line, Some(ProcessEvent::ToolSelect), text(w));
    }
    for (code, event) in EVENTS {
        let Some(w) = m.iter().find(|w| w.value == code) else {
            continue;
        };
        // The value the event takes from its block, before its own word.
        let value = match code {
            6.0 => tool,
            3.0 | 4.0 => speed,
            _ => None,
        };
        let words = match value {
            Some(v) => format!("{} {}", text(v), text(w)),
            None => text(w),
        };
        push(s, line, Some(event), words);
    }
    for w in m
        .iter()
        .filter(|w| !EVENTS.iter().any(|(c, _)| *c == w.value))
    {
        push(s, line, None, text(w));
    }
}

fn push(s: &mut State, line: u64, event: Option<ProcessEvent>, words: String) {
    let (rpm, tool) = (s.rpm, s.selected);
    s.process.push(ProcessWord {
        line,
        event,
        words,
        rpm,
        tool,
        dwell: None,
        point: None,
    });
}
