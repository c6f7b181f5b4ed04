//! G-code (ISO 6983 subset): the tool path of a milling or drilling program in the part frame,
//! read with every block's place in the text, and written back with corrected positions.
//!
//! ## What is read
//! - Motion: `G0` (rapid), `G1` (feed), `G2`/`G3` (clockwise / counter-clockwise arcs seen from
//!   the positive end of the plane's normal) with `X Y Z`, the centre by `I J K` (incremental
//!   from the start, in every distance mode) or the radius `R` (negative: the arc over 180 deg);
//!   a helix moves linearly along the normal. `G17`/`G18`/`G19` choose the XY, ZX, YZ plane.
//! - Drilling canned cycles `G81`, `G82`, `G83` with `G98`/`G99`, under `G90` or `G91`, repeated
//!   by `L` (FANUC's `K`), ended by `G80` or `G0`-`G3`:
//!   each hole read as the moves it makes (`Cycle`, module `cycles`); after `G80` a motion
//!   needs its `G0`-`G3`.
//! - As the controller runs it ([`parse_on`] with a [`Machine`]: the setup's `[workpiece]` and the
//!   process's tool lengths; `docs/programs/gcode.md` names each rule's source): an axis is
//!   unknown until a block gives it or the setup states the start (rapids before make no point;
//!   a feed, arc or cycle from there is refused, module `modal`); work offsets `G54`-`G59`,
//!   `G59.1`-`G59.3`, `G54.1 Pn` (or as the program sets them, `G10 L2`/`L20`, module `g10`)
//!   and machine coordinates `G53` (of the spindle, the tool
//!   length offset not applied; `G0`/`G1` only) in the setup's frames (without the setup's
//!   `G53` frame a `G53` rapid makes no point and the axes it names unknown, a feed is refused); `G28`/`G30`
//!   to the setup's positions (module `home`); tool length offsets `G43 Hn`/`G44`/`G49` with the
//!   tools' lengths (module `machine`); arc centres `G90.1`/`G91.1`; an arc's end off its circle
//!   within grbl's and LinuxCNC's tolerance (0.005 mm), reached along a spiral.
//!   Every point is the tool tip in the `G54` part frame.
//! - Modes: `G90`/`G91` absolute / incremental, `G20`/`G21` inch / mm; `G4` dwell, `G40`, `G61`,
//!   `G61.1`, `G64` (its `P Q`), `G80`, `G94` are accepted and change nothing here; a line opening
//!   with `%` is no block. `F` is the feed rate (modal, per minute:
//!   mm/min under `G21`, inch/min under `G20`), kept with every point for the robot programs
//!   written from the path; a change of units while an `F` is in force needs the `F` again in
//!   its block (controllers differ on whether the feed follows the units). `S`, `M`, `N`, `O`, `P`
//!   words are kept and not interpreted (`P` and `Q` are a cycle's dwell and peck); `T` selects
//!   a tool and `M6` loads it: the tool in the spindle (which selects the process operation and
//!   the tool length) is the one the last `M6` loaded (a `T` alone after an `M6` pre-selects the
//!   next tool), or, before the program's first `M6`, the last `T`.
//! - Comments `( ... )` and `; ...`; those on lines of their own are kept in path order
//!   ([`Comment`], written in a robot program at their place). A comment `(operation: NAME)`
//!   selects the process operation named `NAME` from there on. Header comments state the tool orientation:
//!   `(stiffid: tool_rpy_deg = 180 0 0)` (else the setup's `[workpiece] tool_rpy_deg`), the tool frame in the part frame as fixed-axis
//!   roll-pitch-yaw (`180 0 0` points the tool z axis down, along the part's -Z); and, to allow
//!   rotary words, `(stiffid: rotary = abc)`: `A B C` (deg, absolute, -360 to 360) then turn the tool by
//!   `Rz(C) Ry(B) Rx(A)` in the part frame before the header's orientation. A canned cycle
//!   drills into the part's surface at `Z = 0` of the part frame, or at the level
//!   `(stiffid: surface_mm = Z)` states (mm whatever the program's units, from there on).
//! - Arcs are split into chords whose sagitta is at most the chord tolerance; which points came
//!   from one arc block is kept ([`GCode::arcs`]), so that a robot program written from the
//!   path may write the arc as a circular move ([`crate::program::generate::arcs`]).
//!
//! Cutter radius compensation `G41`/`G42` is read as LinuxCNC runs it on the LinuxCNC dialect
//! (module `cutter`); where controllers differ the setup's `[controller] dialect` says how
//! (module `dialect`), else the block is refused naming the line.
//!
//! Subprograms of the same file, parameters, expressions and control flow (LinuxCNC's O-words,
//! FANUC's and Haas's `M98`/`M97`/`G65` and macro B) are expanded first into the blocks the
//! controller runs (module `expand`; [`GCode::expanded`]): the points name the program's lines.
//!
//! Any other G code or letter is refused naming its line (`G92`, `G93`, `G95`, `G28.1` saying
//! why), as are block delete `/`, polar words `@ ^` but on LinuxCNC (module `polar`),
//! an arc whose end is off its circle beyond 0.005 mm, an arc of radius below 1 um, a letter given
//! twice in one block (but `G` and `M`), two codes of one modal group in one block (`G0 G1`, `G90
//! G91`, `M3 M4`), an arc with a number of turns `P` or a centre or radius beyond 100 m, a feed
//! rate `F` outside `(0, MAX_FEED]`, a spindle speed `S` outside `[0, 100000]` rev/min, an `M` code
//! not a whole number from 0 to 999, a motion after the program's end (`M2`, `M30`), a work
//! offset, home position or tool length the [`Machine`] does not give, and more than 1 000 000
//! points.
//!
//! ## What is written
//! [`GCode::write`] keeps every line byte for byte but the motion blocks, where the `X Y Z I J K R`
//! words are replaced by the corrected position of each point (a word dropped takes the blanks
//! before it along, so a program written back twice reads as once; a canned cycle becomes its `G0`,
//! `G1` and `G4` blocks; an arc becomes its chords, `G2`/`G3`
//! becomes `G1`), in the program's own units and distance mode, each block's words in its own
//! work offset's frame and tool length offset; rapids before the first point and `G28`/`G30`
//! blocks as found (the controller goes where its own positions are). Only positions are corrected: a
//! 3-axis program has no words for the tool's rotation. `GCode::write_with_external` also writes
//! the mapped external axes' values of every point (a station chosen by the compensation): the
//! block's own external words are dropped and every written point carries all of them, in the
//! header's order, in the program's units and distance mode.

mod arc;
mod block;
mod cutter;
mod cycles;
mod dialect;
mod dwell;
mod expand;
mod g10;
mod g53;
mod g92;
mod groups;
mod home;
mod machine;
mod modal;
mod polar;
mod process;
mod rotation;
mod spline;
mod subset;
mod words;
mod write;

pub use arc::ArcBlock;
pub(crate) use cycles::Cycle;
pub use machine::{GcodeDialect, Machine, ProgramFrames};
pub use process::{Comment, ProcessWord};

use block::block;
use nalgebra::{UnitQuaternion, Vector3};
use std::ops::Range;
use stiffid_core::common::error::JobOption;
use stiffid_core::{Error, Result};
use words::words;

/// `State::motion` after `G80` ended a canned cycle: no motion in force until `G0`-`G3`.
pub(super) const NO_MOTION: u8 = 80;

/// The most path points (after splitting arcs).
pub(crate) const MAX_POINTS: usize = 1_000_000;
/// The most blocks (lines).
pub(crate) const MAX_BLOCKS: usize = 1_000_000;
/// The accepted chord tolerance, mm.
pub(crate) const CHORD_TOLERANCE_MM: stiffid_core::common::limits::Range =
    stiffid_core::common::limits::Range::new(1e-6, 10.0, "mm");

/// Rapid or cutting motion.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Motion {
    /// `G0`: no cutting.
    Rapid,
    /// `G1`, `G2`, `G3`: cutting.
    Feed,
}

/// One point of the tool path, part frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    /// The line of its block, 1-based.
    pub line: u64,
    /// The tool point, part frame, m.
    pub position: Vector3<f64>,
    /// The tool frame in the part frame.
    pub orientation: UnitQuaternion<f64>,
    /// Rapid or cutting.
    pub motion: Motion,
    /// The tool in the spindle: the tool number the last `M6` loaded (`Tn M6`, or `M6` alone
    /// loading the last `T` selected before it); before the program's first `M6`, the last `T`
    /// (a program for a machine without a tool changer).
    pub tool_number: Option<u32>,
    /// The operation named in force (`(operation: NAME)`), shared by every point it covers (an
    /// arc's thousands of chords hold one copy of the name).
    pub operation: Option<std::sync::Arc<str>>,
    /// The feed rate in force (the last `F` word, per minute in the units of its block), m/s;
    /// `None` before the first `F`.
    pub feed: Option<f64>,
    /// The drilling canned cycle (index into [`GCode::cycles`]) this point is a move of.
    pub cycle: Option<usize>,
    /// The cell's external axes at this point, in the order of [`GCode::external`] (the
    /// cell's): mm for a linear axis (`U V W`), deg for a rotary one (`A B C`); empty when the
    /// program maps none.
    pub external: Vec<f64>,
}

/// A motion block: where its line is and which points it made.
#[derive(Debug, Clone, PartialEq)]
struct Block {
    line: Range<usize>,
    points: Range<usize>,
    /// Word spans to drop (`X Y Z I J K R`) and the span of a `G2`/`G3` word to write as `G1`.
    drop: Vec<Range<usize>>,
    /// The spans of the words of the mapped external axes, dropped where the external values
    /// are written anew ([`GCode::write_with_external`]).
    external_words: Vec<Range<usize>>,
    arc_word: Option<Range<usize>>,
    /// A `G5.1` spline's block (its `arc_word` the `G5.1`): its points are no circle's.
    spline: bool,
    inch: bool,
    incremental: bool,
    /// The programmed coordinates of a tip (`G54` part frame) in the block's frame and tool
    /// length offset.
    to_program: nalgebra::Isometry3<f64>,
    /// Written as found (`G28`, `G30`): the controller goes where its stored position is.
    verbatim: bool,
    /// The change of the tool length offset the controller moves by in this block, along the
    /// frame's `Z`, m (FANUC and Haas: an incremental `Z` after `G43` without a move; module
    /// `dialect`): an incremental block's `Z` is written less it.
    take_up: f64,
    /// A canned cycle's block: its points written as `G0`/`G1` blocks of their own, and the dwell
    /// `G4 P..` after the points of these indices (within the block: each hole's bottom) with the
    /// `P` word as written.
    cycle: Option<Option<(Vec<usize>, String)>>,
}

/// A G-code program and its tool path.
#[derive(Debug, Clone, PartialEq)]
pub struct GCode {
    /// Every point, in path order.
    pub points: Vec<Point>,
    /// The drilling canned cycles, one per hole, in path order.
    pub cycles: Vec<Cycle>,
    /// The letters the header maps to the cell's external axes, in the cell's order
    /// (`(stiffid: external = U C)`), and the header's line; empty (line 0) when it maps none.
    pub external: (Vec<char>, u64),
    /// The process words (spindle, coolant, tool, end), in path order
    /// ([`ProcessWord`]).
    pub process: Vec<ProcessWord>,
    /// The comments on lines of their own, in path order ([`Comment`]).
    pub comments: Vec<Comment>,
    /// The line of the first motion when no `G20` or `G21` comes before it: the program does
    /// not state its units and is read in mm, the units a controller is in at its start being
    /// its own setting (LinuxCNC's ini, Haas setting 9, a FANUC parameter).
    pub unstated_units: Option<u64>,
    /// The lines of the `G53` rapids read without the setup's `G53` frame: each made no point
    /// and left the axes it names unknown until the program gives them again, so the robot goes
    /// from the point before it to the next one in one move.
    pub unplaced_g53: Vec<u64>,
    /// The first motion made while the tool in use has a length and no tool length offset
    /// (`G43`) is in force, and that length (m): the program's coordinates are read as the
    /// spindle's gauge line's, the tip that length below them.
    pub no_length_offset: Option<(u64, f64)>,
    /// The line of the first rotary word (`A0`, `B0`, `C0`) of a program that neither turns the
    /// tool (`rotary = abc`) nor maps the letter to an external axis: every such word is 0 (any
    /// other value is refused), the axis never leaves its zero, and the words are read as no
    /// motion (written back as found).
    pub zero_rotary: Option<u64>,
    /// The program has subprograms, parameters or control flow: it was read as the blocks its
    /// controller runs, in their order, each point naming the program's line; it is written
    /// back so, expanded (module `expand`).
    pub expanded: bool,
    blocks: Vec<Block>,
    /// Words dropped when written (`G41`, `G42` and their `D`: the path is the tool centre's).
    dropped: Vec<Range<usize>>,
    text: String,
    /// The tip at the start (the setup's), `G54` part frame, m: where an incremental first
    /// block is written from.
    start: Option<Vector3<f64>>,
}

struct State {
    position: Vector3<f64>,
    abc: [f64; 3],
    motion: u8,
    plane: u8,
    inch: bool,
    /// Whether a `G20` or `G21` has been read.
    units_stated: bool,
    incremental: bool,
    /// The tool in the spindle: the one the last `M6` loaded (its block's `T`, else the last
    /// `T` selected before it); before the program's first `M6`, the last `T`.
    tool_number: Option<u32>,
    /// The last tool selected (`T`), which an `M6` loads.
    selected: Option<u32>,
    /// An `M6` has been read: from there on a `T` alone only selects the next tool.
    changed: bool,
    operation: Option<std::sync::Arc<str>>,
    tool: Option<UnitQuaternion<f64>>,
    rotary: bool,
    /// The line of the first `A0`/`B0`/`C0` word read without `rotary = abc` or a mapping.
    zero_rotary: Option<u64>,
    /// The letters mapped to the cell's external axes and the header's line.
    external: (Vec<char>, u64),
    /// Each mapped axis's value in force, mm or deg.
    e: Vec<Option<f64>>,
    /// The line of the `M2`/`M30` that ended the program.
    ended: Option<u64>,
    /// The spindle speed in force (the last `S`, rev/min).
    rpm: Option<f64>,
    /// The process words so far.
    process: Vec<ProcessWord>,
    /// The comments of the line being read (stiffid's directives left out).
    line_comments: Vec<String>,
    /// The comments on lines of their own so far.
    comments: Vec<Comment>,
    feed: Option<f64>,
    /// The line of the `F` word in force.
    feed_line: u64,
    /// Which axes of `position` the program has given (or the setup's start).
    known: [bool; 3],
    /// The line of the first motion with an axis unknown, before any point.
    pending: Option<u64>,
    /// Per axis, the block that last left it unknown once known (a `G53` rapid the setup does
    /// not place, a `G28`/`G30` before the tool's length is known): its line and why.
    left_unknown: [Option<(u64, &'static str)>; 3],
    /// The line of the first rapid that made no point because no tool was named yet (its tip
    /// depends on the length of the tool the machine holds).
    untooled: Option<u64>,
    /// The work offset in force.
    frame: machine::Frame,
    /// The tool length offset in force (`G43`: +length, `G44`: -length, `G49`: 0), m.
    length_offset: f64,
    /// `G90.1`: arc centres `I J K` absolute (else, `G91.1`, from the arc's start).
    ij_absolute: bool,
    /// The controller's knowledge beyond the text.
    machine: Machine,
    /// `G99`: canned cycles retract to `R` (else, `G98`, to the level they started from).
    retract_to_r: bool,
    /// The canned cycle's words in force.
    cycle: cycles::Modal,
    /// The tool length offset change (the line of the first, and the sum of the changes of the
    /// programmed `Z` where the tool is, m) a move that gives `Z` has not yet taken up (module
    /// `dialect`).
    offset_change: Option<(u64, f64)>,
    /// The change this block's controller moves by (FANUC, Haas), m (module `dialect`).
    take_up: f64,
    /// The line of a `G28` made with a tool length offset in force, on a dialect whose rule is
    /// not known (module `dialect`).
    home_cancel: Option<u64>,
    /// Cutter radius compensation (module `cutter`).
    comp: cutter::Comp,
    /// The spans of words dropped when the program is written (`G41`, `G42` and their `D`).
    dropped: Vec<Range<usize>>,
    /// The part's surface a canned cycle drills into, part frame `Z`, m (`(stiffid: surface_mm
    /// = Z)`, default 0).
    surface: f64,
    /// The work offsets the program set (`G10`, module `g10`).
    set: g10::Set,
    /// The `G92` shift in force, along the frame's axes, m (module `g92`).
    g92: Vector3<f64>,
    /// The coordinate rotation `G68` in force (module `rotation`).
    rotation: Option<rotation::Rotation>,
    /// The line of a `G68`/`G69` whose first motion after it has not come yet.
    rotated: Option<u64>,
}

impl State {
    /// The state at the program's start on `machine`, nothing read yet.
    fn new(machine: &Machine) -> Self {
        State {
            position: Vector3::zeros(),
            abc: [0.0; 3],
            motion: 0,
            plane: 17,
            inch: false,
            units_stated: false,
            incremental: false,
            tool_number: None,
            selected: None,
            changed: false,
            operation: None,
            tool: machine.frames.tool,
            rotary: false,
            zero_rotary: None,
            external: (Vec::new(), 0),
            e: Vec::new(),
            ended: None,
            rpm: None,
            process: Vec::new(),
            line_comments: Vec::new(),
            comments: Vec::new(),
            feed: None,
            feed_line: 0,
            retract_to_r: false,
            cycle: Default::default(),
            surface: 0.0,
            set: Default::default(),
            g92: Vector3::zeros(),
            rotation: None,
            rotated: None,
            known: [false; 3],
            pending: None,
            left_unknown: [None; 3],
            untooled: None,
            frame: machine::Frame::default(),
            length_offset: 0.0,
            ij_absolute: false,
            offset_change: None,
            take_up: 0.0,
            home_cancel: None,
            comp: Default::default(),
            dropped: Vec::new(),
            machine: machine.clone(),
        }
    }
}

fn at(line: u64, message: String) -> Error {
    Error::Program { line, message }
}

/// Parses `text` (module docs), arcs split to `chord_tolerance` (m), on a controller that knows
/// nothing beyond the text ([`Machine::default`]: `G54` only, the start unknown, no tool
/// lengths).
///
/// # Errors
/// Those of [`parse_on`].
pub fn parse(text: &str, chord_tolerance: f64) -> Result<GCode> {
    parse_on(text, chord_tolerance, &Machine::default())
}

/// Parses `text` (module docs), arcs split to `chord_tolerance` (m), on a controller that knows
/// `machine`: its work offsets, start and home positions and tool lengths.
///
/// # Errors
/// [`Error::InvalidOption`] for a chord tolerance outside [1e-6, 10] mm; [`Error::Program`] naming
/// the line for anything outside the subset, a malformed word, an arc off its circle, no tool
/// orientation in the header or the setup, rotary words without `rotary = abc`, a work offset, home
/// position or tool length `machine` lacks, a feed motion before every axis is known, no motion at
/// all, or more than 1 000 000 lines or `MAX_POINTS` points.
pub fn parse_on(text: &str, chord_tolerance: f64, machine: &Machine) -> Result<GCode> {
    stiffid_core::common::limits::check(
        "chord_tolerance_mm",
        &[chord_tolerance * 1e3],
        &CHORD_TOLERANCE_MM,
    )
    .map_err(|e| e.for_option(JobOption::ChordToleranceMm))?;
    let expanded = expand::expand(text, machine.dialect)?;
    let (text, map) = match &expanded {
        Some(e) => (e.text.as_str(), Some(e.lines.as_slice())),
        None => (text, None),
    };
    let mut s = State::new(machine);
    s.start();
    let mut out = GCode {
        points: Vec::new(),
        cycles: Vec::new(),
        external: (Vec::new(), 0),
        process: Vec::new(),
        comments: Vec::new(),
        unstated_units: None,
        unplaced_g53: Vec::new(),
        no_length_offset: None,
        zero_rotary: None,
        expanded: expanded.is_some(),
        blocks: Vec::new(),
        dropped: Vec::new(),
        text: text.to_string(),
        start: machine.frames.start,
    };
    for (n, start, l) in super::text::lines(text) {
        if n as usize > MAX_BLOCKS {
            return Err(at(n, format!("more than {MAX_BLOCKS} lines")));
        }
        // The program's own line of an expanded block.
        let line = map.map_or(n, |m| m.get(n as usize - 1).copied().unwrap_or(n));
        if l.contains('\r') {
            return Err(at(line, "a carriage return inside the line: the file ends its lines with a carriage return alone (an old Mac's) or mixes line ends, and a controller ends a block at a line feed, so what follows it would be read as part of this block (inside a comment, dropped); convert the line ends to LF or CR LF".into()));
        }
        let words = words(line, start, l, &mut s)?;
        let (words, x_dwell) = dwell::time_in_x(line, words, text, s.machine.dialect)?;
        let comments = std::mem::take(&mut s.line_comments);
        if words.is_empty() {
            let kept = comments.into_iter().map(|text| Comment { line, text });
            s.comments.extend(kept);
        }
        let first = out.points.is_empty();
        block(
            line,
            start..start + l.len(),
            &words,
            &mut s,
            &mut out,
            chord_tolerance,
        )?;
        dwell::gather(line, (&words, text), x_dwell, &mut s);
        if first && !out.points.is_empty() && !s.units_stated {
            out.unstated_units = Some(line);
        }
        if out.points.len() > MAX_POINTS {
            return Err(at(
                line,
                format!("more than {MAX_POINTS} path points (after splitting arcs)"),
            ));
        }
    }
    if out.points.is_empty() {
        if let Some(line) = s.untooled {
            return Err(s.no_length(line));
        }
        if let Some(line) = s.pending {
            return Err(at(line, format!("no motion reaches a point whose X, Y and Z are all known (from line {line} on; {})", modal::UNKNOWN_HELP)));
        }
        return Err(at(1, "no motion block (G0, G1, G2, G3) found".into()));
    }
    out.external = s.external;
    out.zero_rotary = s.zero_rotary;
    out.process = s.process;
    out.comments = s.comments;
    out.dropped = s.dropped;
    Ok(out)
}

/// The mapped external axes' values in force for a motion on `line`: every one must have been
/// given.
fn external_values(line: u64, s: &State) -> Result<Vec<f64>> {
    s.e.iter()
        .zip(&s.external.0)
        .map(|(v, letter)| {
            v.ok_or_else(|| at(line, format!("{letter}: a motion before the external axis it drives has a value (the header maps it on line {}): give {letter} in this block or before", s.external.1)))
        })
        .collect()
}

/// The tool orientation for a motion on `line`: refused after the program's end or before the
/// header states it.
fn may_move(line: u64, s: &State) -> Result<UnitQuaternion<f64>> {
    if let Some(end) = s.ended {
        return Err(at(
            line,
            format!("a motion after the end of the program (M2/M30 on line {end})"),
        ));
    }
    s.tool.ok_or_else(|| at(line, "no tool orientation: state it in the setup, [workpiece] tool_rpy_deg = [180, 0, 0] (the tool frame in the part frame), or in a header comment before the first motion, (stiffid: tool_rpy_deg = 180 0 0)".into()))
}

#[cfg(test)]
mod cycles_tests;
#[cfg(test)]
mod g10_tests;
