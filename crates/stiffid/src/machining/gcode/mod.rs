//! G-code (ISO 6983 subset): the tool path of a milling or drilling program in the part frame,
//! read with every block's place in the text, and written back with corrected positions.
//!
//! ## What is read
//! - Motion: `G0` (rapid), `G1` (feed), `G2`/`G3` (clockwise / counter-clockwise arcs seen from
//!   the positive end of the plane's normal) with `X Y Z`, the centre by `I J K` (incremental
//!   from the start, in every distance mode) or the radius `R` (negative: the arc over 180 deg);
//!   a helix moves linearly along the normal. `G17`/`G18`/`G19` choose the XY, ZX, YZ plane.
//! - Drilling canned cycles `G81`, `G82`, `G83` with `G98`/`G99`, ended by `G80` or `G0`-`G3`:
//!   each hole read as the moves it makes ([`Cycle`], module `cycles`); after `G80` a motion
//!   needs its `G0`-`G3`.
//! - Modes: `G90`/`G91` absolute / incremental, `G20`/`G21` inch / mm; `G4` dwell, `G40`, `G49`,
//!   `G80`, `G94` are accepted and change nothing here. `F` is the feed rate (modal, per minute:
//!   mm/min under `G21`, inch/min under `G20`), kept with every point for the robot programs
//!   written from the path; a change of units while an `F` is in force needs the `F` again in
//!   its block (controllers differ on whether the feed follows the units). `S`, `M`, `N`, `O`, `P`
//!   words are kept and not interpreted (`P` and `Q` are a cycle's dwell and peck); `T` sets the
//!   tool number (which selects the process operation).
//! - Comments `( ... )` and `; ...`. A comment `(operation: NAME)` selects the process operation
//!   named `NAME` from there on. Header comments state the tool orientation:
//!   `(stiffid: tool_rpy_deg = 180 0 0)`, the tool frame in the part frame as fixed-axis
//!   roll-pitch-yaw (`180 0 0` points the tool z axis down, along the part's -Z); and, to allow
//!   rotary words, `(stiffid: rotary = abc)`: `A B C` (deg, absolute) then turn the tool by
//!   `Rz(C) Ry(B) Rx(A)` in the part frame before the header's orientation.
//! - Arcs are split into chords whose sagitta is at most the chord tolerance.
//!
//! Any other G code or letter is refused naming its line (cutter radius compensation `G41`/`G42`
//! saying it belongs to the CAM post), as are an arc whose end is not on its
//! circle (more than 1 um or 1e-6 of the radius off), an arc of radius below 1 um, a letter given
//! twice in one block (but `G` and `M`), a feed rate `F` outside `(0, MAX_FEED]`, a subprogram
//! call or return (`M97`, `M98`, `M99`), a motion after the program's end (`M2`, `M30`), and more
//! than [`MAX_POINTS`] points.
//!
//! ## What is written
//! [`GCode::write`] keeps every line byte for byte but the motion blocks, where the `X Y Z I J K R`
//! words are replaced by the corrected position of each point (a canned cycle becomes its `G0`,
//! `G1` and `G4` blocks; an arc becomes its chords, `G2`/`G3`
//! becomes `G1`), in the program's own units and distance mode. Only positions are corrected: a
//! 3-axis program has no words for the tool's rotation.

mod cycles;

pub use cycles::{Cycle, PECK_CLEARANCE_MM};

use crate::common::error::JobOption;
use crate::{Error, Result};
use nalgebra::{UnitQuaternion, Vector3};
use std::ops::Range;

/// The most path points (after splitting arcs).
pub const MAX_POINTS: usize = 1_000_000;
/// The most blocks (lines).
pub const MAX_BLOCKS: usize = 1_000_000;
/// The accepted chord tolerance, mm.
pub const CHORD_TOLERANCE_MM: crate::common::limits::Range =
    crate::common::limits::Range::new(1e-6, 10.0, "mm");

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
    /// The tool number in force (`T` word).
    pub tool_number: Option<u32>,
    /// The operation named in force (`(operation: NAME)`), shared by every point it covers (an
    /// arc's thousands of chords hold one copy of the name).
    pub operation: Option<std::sync::Arc<str>>,
    /// The feed rate in force (the last `F` word, per minute in the units of its block), m/s;
    /// `None` before the first `F`.
    pub feed: Option<f64>,
    /// The drilling canned cycle (index into [`GCode::cycles`]) this point is a move of.
    pub cycle: Option<usize>,
}

/// A motion block: where its line is and which points it made.
#[derive(Debug, Clone, PartialEq)]
struct Block {
    line: Range<usize>,
    points: Range<usize>,
    /// Word spans to drop (`X Y Z I J K R`) and the span of a `G2`/`G3` word to write as `G1`.
    drop: Vec<Range<usize>>,
    arc_word: Option<Range<usize>>,
    inch: bool,
    incremental: bool,
    /// A canned cycle's block: its points written as `G0`/`G1` blocks of their own, and the dwell
    /// `G4 P..` after the point of this index (within the block) with the `P` word as written.
    cycle: Option<Option<(usize, String)>>,
}

/// A G-code program and its tool path.
#[derive(Debug, Clone, PartialEq)]
pub struct GCode {
    /// Every point, in path order.
    pub points: Vec<Point>,
    /// The drilling canned cycles, one per hole, in path order.
    pub cycles: Vec<Cycle>,
    blocks: Vec<Block>,
    text: String,
}

struct State {
    position: Vector3<f64>,
    abc: [f64; 3],
    motion: u8,
    plane: u8,
    inch: bool,
    incremental: bool,
    tool_number: Option<u32>,
    operation: Option<std::sync::Arc<str>>,
    tool: Option<UnitQuaternion<f64>>,
    rotary: bool,
    /// The line of the `M2`/`M30` that ended the program.
    ended: Option<u64>,
    feed: Option<f64>,
    /// The line of the `F` word in force.
    feed_line: u64,
    /// `G99`: canned cycles retract to `R` (else, `G98`, to the level they started from).
    retract_to_r: bool,
    /// The canned cycle's words in force.
    cycle: cycles::Modal,
}

fn at(line: u64, message: String) -> Error {
    Error::Program { line, message }
}

/// A word: letter, value and span (bytes of the text).
struct Word {
    letter: char,
    value: f64,
    span: Range<usize>,
}

/// Parses `text` (module docs), arcs split to `chord_tolerance` (m).
///
/// # Errors
/// [`Error::InvalidOption`] for a chord tolerance outside [`CHORD_TOLERANCE_MM`];
/// [`Error::Program`] naming the line for anything outside the subset, a malformed word, an arc
/// off its circle, no tool orientation in the header, rotary words without `rotary = abc`, no
/// motion at all, or more than [`MAX_BLOCKS`] lines or [`MAX_POINTS`] points.
pub fn parse(text: &str, chord_tolerance: f64) -> Result<GCode> {
    crate::common::limits::check(
        "chord_tolerance_mm",
        &[chord_tolerance * 1e3],
        &CHORD_TOLERANCE_MM,
    )
    .map_err(|e| e.for_option(JobOption::ChordToleranceMm))?;
    let mut s = State {
        position: Vector3::zeros(),
        abc: [0.0; 3],
        motion: 0,
        plane: 17,
        inch: false,
        incremental: false,
        tool_number: None,
        operation: None,
        tool: None,
        rotary: false,
        ended: None,
        feed: None,
        feed_line: 0,
        retract_to_r: false,
        cycle: Default::default(),
    };
    let mut out = GCode {
        points: Vec::new(),
        cycles: Vec::new(),
        blocks: Vec::new(),
        text: text.to_string(),
    };
    for (line, start, l) in super::program::lines(text) {
        if line as usize > MAX_BLOCKS {
            return Err(at(line, format!("more than {MAX_BLOCKS} lines")));
        }
        let words = words(line, start, l, &mut s)?;
        block(
            line,
            start..start + l.len(),
            &words,
            &mut s,
            &mut out,
            chord_tolerance,
        )?;
        if out.points.len() > MAX_POINTS {
            return Err(at(
                line,
                format!("more than {MAX_POINTS} path points (after splitting arcs)"),
            ));
        }
    }
    if out.points.is_empty() {
        return Err(at(1, "no motion block (G0, G1, G2, G3) found".into()));
    }
    Ok(out)
}

/// The words of one line; comments are read for the header and operation names.
fn words(line: u64, start: usize, l: &str, s: &mut State) -> Result<Vec<Word>> {
    let bytes = l.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let c = bytes[i] as char;
        if c == '(' {
            let end = l[i..]
                .find(')')
                .map(|e| i + e)
                .ok_or_else(|| at(line, "comment without its closing ')'".into()))?;
            comment(line, &l[i + 1..end], s)?;
            i = end + 1;
            continue;
        }
        if c == ';' {
            comment(line, &l[i + 1..], s)?;
            break;
        }
        if c.is_whitespace() || c == '%' {
            i += 1;
            continue;
        }
        let letter = c.to_ascii_uppercase();
        if !letter.is_ascii_alphabetic() {
            return Err(at(
                line,
                format!("'{c}': expected a word (a letter and a number)"),
            ));
        }
        let (value, span) = super::program::number_at(l, i + 1).ok_or_else(|| {
            at(
                line,
                format!("{letter}: expected a number after the letter"),
            )
        })?;
        out.push(Word {
            letter,
            value,
            span: start + i..start + span.end,
        });
        i = span.end;
    }
    Ok(out)
}

fn comment(line: u64, text: &str, s: &mut State) -> Result<()> {
    let t = text.trim();
    if let Some(name) = t.strip_prefix("operation:") {
        s.operation = Some(name.trim().into());
    }
    let Some(directive) = t.strip_prefix("stiffid:") else {
        return Ok(());
    };
    let (key, value) = directive
        .split_once('=')
        .ok_or_else(|| at(line, "stiffid header: expected 'key = value'".into()))?;
    match key.trim() {
        "tool_rpy_deg" => {
            let v: Vec<f64> = value
                .split_whitespace()
                .map(str::parse)
                .collect::<std::result::Result<_, _>>()
                .map_err(|_| at(line, "tool_rpy_deg: expected three numbers, deg".into()))?;
            if v.len() != 3
                || v.iter()
                    .any(|a| !crate::common::limits::ANGLE_DEG.contains(*a))
            {
                return Err(at(
                    line,
                    format!(
                        "tool_rpy_deg: expected three numbers within {}",
                        crate::common::limits::ANGLE_DEG
                    ),
                ));
            }
            s.tool = Some(UnitQuaternion::from_euler_angles(
                v[0].to_radians(),
                v[1].to_radians(),
                v[2].to_radians(),
            ));
        }
        "rotary" if value.trim().eq_ignore_ascii_case("abc") => s.rotary = true,
        other => {
            return Err(at(
                line,
                format!(
                    "stiffid header: unknown '{}' (expected tool_rpy_deg = R P Y or rotary = abc)",
                    crate::common::limits::short(other)
                ),
            ))
        }
    }
    Ok(())
}

const SUBSET: &str = "G0-G4, G17-G21, G40, G49, G80-G83, G90, G91, G94, G98, G99";

/// `s.motion` after `G80` ended a canned cycle: no motion in force until `G0`-`G3`.
const NO_MOTION: u8 = 80;

fn block(
    line: u64,
    span: Range<usize>,
    words: &[Word],
    s: &mut State,
    out: &mut GCode,
    tolerance: f64,
) -> Result<()> {
    let mut target = [None; 3];
    let mut centre = [None; 3];
    let mut radius = None;
    let mut motion_given = None;
    let mut drop = Vec::new();
    let mut abc_given = false;
    check_words(line, words, s)?;
    let mut feed_given = None;
    let mut cycle_words = cycles::Words::default();
    let inch_before = s.inch;
    for w in words {
        let v = w.value;
        match w.letter {
            'G' => {
                let g = v.round();
                if (v - g).abs() > 1e-9 || !(0.0..100.0).contains(&g) {
                    return Err(at(line, format!("G{v}: not in the supported subset ({SUBSET})")));
                }
                match g as u8 {
                    g @ 0..=3 => motion_given = Some((g, w.span.clone())),
                    g @ 81..=83 => {
                        motion_given = Some((g, w.span.clone()));
                        drop.push(w.span.clone());
                    }
                    g @ (98 | 99) => {
                        s.retract_to_r = g == 99;
                        drop.push(w.span.clone());
                    }
                    80 if s.motion >= 81 => s.motion = NO_MOTION,
                    g @ (41 | 42) => return Err(at(line, format!("G{g}: cutter radius compensation belongs to the CAM post: post the path of the tool centre (compensation in the computer, G40)"))),
                    g @ 17..=19 => s.plane = g,
                    20 => s.inch = true,
                    21 => s.inch = false,
                    90 => s.incremental = false,
                    91 => s.incremental = true,
                    4 | 40 | 49 | 80 | 94 => {}
                    _ => return Err(at(line, format!("G{g}: not in the supported subset ({SUBSET})"))),
                }
            }
            'X' | 'Y' | 'Z' => {
                target[(w.letter as u8 - b'X') as usize] = Some(v);
                drop.push(w.span.clone());
            }
            'I' | 'J' | 'K' => {
                centre[(w.letter as u8 - b'I') as usize] = Some(v);
                drop.push(w.span.clone());
            }
            'R' => {
                radius = Some(v);
                drop.push(w.span.clone());
            }
            'A' | 'B' | 'C' => {
                if !s.rotary {
                    return Err(at(line, format!("{}: rotary words need the header comment (stiffid: rotary = abc)", w.letter)));
                }
                s.abc[(w.letter as u8 - b'A') as usize] = v;
                abc_given = true;
            }
            'T' => {
                if v < 0.0 || v.fract() != 0.0 || v > 1e6 {
                    return Err(at(line, format!("T{v}: expected a tool number 0..1000000")));
                }
                s.tool_number = Some(v as u32);
            }
            'F' => feed_given = Some(v),
            'Q' => {
                cycle_words.peck = Some(v);
                drop.push(w.span.clone());
            }
            'P' => cycle_words.dwell = Some((v, w.span.clone())),
            'S' | 'M' | 'N' | 'O' | 'H' | 'D' => {}
            other => return Err(at(line, format!("'{other}': not a word of the supported subset (G M T F S N O P Q X Y Z I J K R, A B C with rotary = abc)"))),
        }
    }
    if let Some((g, _)) = &motion_given {
        if *g >= 81 && s.motion < 81 {
            s.cycle = cycles::Modal::starting_at(s.position.z);
        }
        s.motion = *g;
    }
    if let Some(f) = feed_given {
        s.feed = Some(f * if s.inch { 25.4e-3 } else { 1e-3 } / 60.0);
        s.feed_line = line;
    } else if s.inch != inch_before && s.feed.is_some() {
        return Err(at(line, format!("G{}: the units change while the feed rate F of line {} is in force, and controllers differ on whether it follows them: give F again in this block", if s.inch { 20 } else { 21 }, s.feed_line)));
    }
    if s.motion >= 81 && s.motion != NO_MOTION {
        cycle_words.xyz = target;
        cycle_words.retract = radius;
        cycle_words.given = motion_given.is_some();
        let centre_given = centre.iter().any(Option::is_some);
        return cycles::block(
            line,
            span,
            cycle_words,
            centre_given || abc_given,
            drop,
            s,
            out,
        );
    }
    if cycle_words.peck.is_some() {
        return Err(at(line, "Q: a peck depth outside a G83 cycle".into()));
    }
    let arc_only = s.motion >= 2 && (centre.iter().any(Option::is_some) || radius.is_some());
    let moves = target.iter().any(Option::is_some) || abc_given || arc_only;
    if !moves {
        if centre.iter().any(Option::is_some) || radius.is_some() {
            return Err(at(line, "I, J, K or R without an end point".into()));
        }
        return Ok(());
    }
    if s.motion == NO_MOTION {
        return Err(at(line, "a motion after G80 without G0, G1, G2 or G3: controllers differ on the motion in force after a canned cycle; give it".into()));
    }
    let tool = may_move(line, s)?;
    let scale = if s.inch { 25.4e-3 } else { 1e-3 };
    let mut end = s.position;
    for k in 0..3 {
        if let Some(v) = target[k] {
            end[k] = if s.incremental {
                end[k] + v * scale
            } else {
                v * scale
            };
        }
    }
    if !end.iter().all(|v| v.abs() <= 100.0) {
        return Err(at(line, "position beyond 100 m".into()));
    }
    let [a, b, c] = s.abc.map(f64::to_radians);
    let orientation = UnitQuaternion::from_euler_angles(a, b, c) * tool;
    let first = out.points.len();
    let positions = match s.motion {
        2 | 3 => arc(
            line,
            s,
            end,
            centre.map(|c| c.map(|v| v * scale)),
            radius.map(|r| r * scale),
            tolerance,
        )?,
        _ => vec![end],
    };
    for p in positions {
        out.points.push(Point {
            line,
            position: p,
            orientation,
            motion: if s.motion == 0 {
                Motion::Rapid
            } else {
                Motion::Feed
            },
            tool_number: s.tool_number,
            operation: s.operation.clone(),
            feed: s.feed,
            cycle: None,
        });
    }
    s.position = end;
    let arc_word = motion_given.filter(|(g, _)| *g >= 2).map(|(_, span)| span);
    out.blocks.push(Block {
        line: span,
        points: first..out.points.len(),
        drop,
        arc_word,
        inch: s.inch,
        incremental: s.incremental,
        cycle: None,
    });
    Ok(())
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
    s.tool.ok_or_else(|| at(line, "no tool orientation: state it in a header comment before the first motion, e.g. (stiffid: tool_rpy_deg = 180 0 0)".into()))
}

/// The largest feed rate `F` accepted (mm/min, or inch/min after `G20`).
pub const MAX_FEED: f64 = 1e6;

/// What the subset refuses in the words of one block, before any is applied: a letter given twice
/// (`G` and `M` aside: several modal groups may share a block), a feed rate outside
/// `(0, MAX_FEED]`, a subprogram call or return (`M97`, `M98`, `M99`: the path would go where
/// this file does not say). `M2`/`M30` end the program: a motion after them is refused.
fn check_words(line: u64, words: &[Word], s: &mut State) -> Result<()> {
    for (i, w) in words.iter().enumerate() {
        let again = words[..i].iter().any(|o| o.letter == w.letter);
        if again && !matches!(w.letter, 'G' | 'M') {
            return Err(at(line, format!("{} given twice in one block", w.letter)));
        }
        match w.letter {
            'F' if !(w.value > 0.0 && w.value <= MAX_FEED) => {
                return Err(at(
                    line,
                    format!(
                        "F{}: expected a feed rate in (0, {MAX_FEED}] (mm/min, inch/min after G20)",
                        w.value
                    ),
                ));
            }
            'M' if [97.0, 98.0, 99.0].contains(&w.value) => {
                return Err(at(
                    line,
                    format!("M{}: subprogram calls and returns are not followed; expand the program into one file first", w.value),
                ));
            }
            'M' if w.value == 2.0 || w.value == 30.0 => s.ended = Some(line),
            _ => {}
        }
    }
    Ok(())
}

/// The plane's axes `(u, v, normal)` as coordinate indices, `u x v = normal`.
fn plane_axes(plane: u8) -> (usize, usize, usize) {
    match plane {
        18 => (2, 0, 1),
        19 => (1, 2, 0),
        _ => (0, 1, 2),
    }
}

/// The points of an arc from `s.position` to `end` (the end included), chords within `tolerance`.
fn arc(
    line: u64,
    s: &State,
    end: Vector3<f64>,
    ijk: [Option<f64>; 3],
    radius: Option<f64>,
    tolerance: f64,
) -> Result<Vec<Vector3<f64>>> {
    let (u, v, n) = plane_axes(s.plane);
    let start = s.position;
    let (su, sv, eu, ev) = (start[u], start[v], end[u], end[v]);
    let ccw = s.motion == 3;
    let (cu, cv) = match (radius, ijk.iter().any(Option::is_some)) {
        (Some(_), true) => {
            return Err(at(
                line,
                "give the arc's centre (I J K) or its radius (R), not both".into(),
            ))
        }
        (None, false) => return Err(at(line, "arc without centre (I J K) or radius (R)".into())),
        (None, true) => (su + ijk[u].unwrap_or(0.0), sv + ijk[v].unwrap_or(0.0)),
        (Some(r), false) => centre_from_radius(line, (su, sv), (eu, ev), r, ccw)?,
    };
    let r0 = ((su - cu).powi(2) + (sv - cv).powi(2)).sqrt();
    let r1 = ((eu - cu).powi(2) + (ev - cv).powi(2)).sqrt();
    if r0 < 1e-6 {
        return Err(at(line, "arc radius below 1 um".into()));
    }
    if (r0 - r1).abs() > 1e-6_f64.max(1e-6 * r0) {
        return Err(at(line, format!("the arc's end is {:.4} mm off its circle (radius {:.4} mm at the start, {:.4} mm at the end)", (r0 - r1).abs() * 1e3, r0 * 1e3, r1 * 1e3)));
    }
    let a0 = (sv - cv).atan2(su - cu);
    let a1 = (ev - cv).atan2(eu - cu);
    let two_pi = 2.0 * std::f64::consts::PI;
    let mut sweep = if ccw {
        (a1 - a0).rem_euclid(two_pi)
    } else {
        -(a0 - a1).rem_euclid(two_pi)
    };
    if sweep.abs() < 1e-12 {
        sweep = if ccw { two_pi } else { -two_pi };
    }
    let step = 2.0 * (1.0 - (tolerance / r0).min(1.0)).acos();
    let count = ((sweep.abs() / step).ceil() as usize).max(1);
    if count > MAX_POINTS {
        return Err(at(
            line,
            format!("the arc needs more than {MAX_POINTS} chords at this tolerance"),
        ));
    }
    Ok((1..=count)
        .map(|i| {
            if i == count {
                return end;
            }
            let t = i as f64 / count as f64;
            let a = a0 + sweep * t;
            let mut p = start;
            p[u] = cu + r0 * a.cos();
            p[v] = cv + r0 * a.sin();
            p[n] = start[n] + (end[n] - start[n]) * t;
            p
        })
        .collect())
}

/// The centre of an `R` arc: on the chord's perpendicular bisector, to the left of the chord for
/// a counter-clockwise arc of at most 180 deg (`r > 0`), to the right for over 180 deg (`r < 0`).
fn centre_from_radius(
    line: u64,
    s: (f64, f64),
    e: (f64, f64),
    r: f64,
    ccw: bool,
) -> Result<(f64, f64)> {
    let (du, dv) = (e.0 - s.0, e.1 - s.1);
    let d = (du * du + dv * dv).sqrt();
    if d < 1e-9 {
        return Err(at(
            line,
            "an R arc needs an end point other than its start".into(),
        ));
    }
    let half = d / 2.0;
    if r.abs() < half - 1e-9 {
        return Err(at(
            line,
            format!(
                "R{:.4} mm is shorter than half the chord ({half:.4} mm)",
                r * 1e3
            ),
        ));
    }
    let h = (r * r - half * half).max(0.0).sqrt();
    let left = (-dv / d, du / d);
    let side = if ccw == (r > 0.0) { 1.0 } else { -1.0 };
    Ok((
        s.0 + du / 2.0 + side * h * left.0,
        s.1 + dv / 2.0 + side * h * left.1,
    ))
}

impl GCode {
    /// The program with each point at `positions[i]` (part frame, m) (module docs).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`positions`) for another number of positions than points or a
    /// position that is not finite.
    pub fn write(&self, positions: &[Vector3<f64>]) -> Result<String> {
        if positions.len() != self.points.len()
            || positions.iter().any(|p| !p.iter().all(|v| v.is_finite()))
        {
            return Err(Error::InvalidField {
                field: "positions".into(),
                message: format!(
                    "expected {} finite positions, one per point",
                    self.points.len()
                ),
            });
        }
        let mut out = String::with_capacity(self.text.len() * 2);
        let mut at = 0;
        // The position the controller is at, as written (for incremental blocks).
        let mut written = Vector3::zeros();
        for b in &self.blocks {
            out.push_str(&self.text[at..b.line.start]);
            let scale = if b.inch { 25.4e-3 } else { 1e-3 };
            let mut words = |p: &Vector3<f64>| {
                let v = if b.incremental {
                    (p - written) / scale
                } else {
                    p / scale
                };
                written = *p;
                format!("X{:.6} Y{:.6} Z{:.6}", v.x, v.y, v.z)
            };
            let ending = match self.text[b.line.end..].starts_with("\r\n") {
                true => "\r\n",
                false => "\n",
            };
            if let Some(dwell) = &b.cycle {
                let mut drop = b.drop.clone();
                drop.sort_by_key(|r| r.start);
                let mut from = b.line.start;
                for r in &drop {
                    out.push_str(&self.text[from..r.start]);
                    from = r.end;
                }
                out.push_str(&self.text[from..b.line.end]);
                for (j, (p, point)) in positions[b.points.clone()]
                    .iter()
                    .zip(&self.points[b.points.clone()])
                    .enumerate()
                {
                    out.push_str(ending);
                    out.push_str(match point.motion {
                        Motion::Rapid => "G0 ",
                        Motion::Feed => "G1 ",
                    });
                    out.push_str(&words(p));
                    if let Some((_, p_word)) = dwell.as_ref().filter(|(after, _)| *after == j) {
                        out.push_str(ending);
                        out.push_str("G4 ");
                        out.push_str(p_word);
                    }
                }
                at = b.line.end;
                continue;
            }
            let first = words(&positions[b.points.start]);
            let mut line = String::new();
            let mut from = b.line.start;
            let mut edits: Vec<(Range<usize>, &str)> =
                b.drop.iter().map(|r| (r.clone(), "")).collect();
            if let Some(g) = &b.arc_word {
                edits.push((g.clone(), "G1"));
            }
            edits.sort_by_key(|(r, _)| r.start);
            let insert = edits
                .iter()
                .find(|(_, t)| t.is_empty())
                .map_or(b.line.end, |(r, _)| r.start);
            for (r, t) in &edits {
                line.push_str(&self.text[from..r.start]);
                if r.start == insert {
                    line.push_str(&first);
                }
                line.push_str(t);
                from = r.end;
            }
            line.push_str(&self.text[from..b.line.end]);
            if insert == b.line.end {
                line.push(' ');
                line.push_str(&first);
            }
            out.push_str(&line);
            for p in &positions[b.points.start + 1..b.points.end] {
                out.push_str(ending);
                out.push_str(&words(p));
            }
            at = b.line.end;
        }
        out.push_str(&self.text[at..]);
        Ok(out)
    }
}
