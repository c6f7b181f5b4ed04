//! One block applied to the state: modes, motions, canned cycles, the points it makes.

use super::arc::arc;
use super::words::{check_words, Word};
use super::{at, cycles, external_values, may_move, Block, GCode, Motion, Point, State};
use nalgebra::{UnitQuaternion, Vector3};
use std::ops::Range;
use stiffid_core::Result;

pub(super) const SUBSET: &str = "G0-G4, G17-G21, G40, G49, G80-G83, G90, G91, G94, G98, G99";

/// `s.motion` after `G80` ended a canned cycle: no motion in force until `G0`-`G3`.
pub(super) const NO_MOTION: u8 = 80;

/// The words of one block, gathered before it moves anything (the block's units).
#[derive(Default)]
struct Given {
    target: [Option<f64>; 3],
    centre: [Option<f64>; 3],
    radius: Option<f64>,
    motion: Option<(u8, Range<usize>)>,
    /// Spans the compensated block writes again (targets, centres, cycle words).
    drop: Vec<Range<usize>>,
    abc: bool,
    external: bool,
    external_words: Vec<Range<usize>>,
    feed: Option<f64>,
    cycle: cycles::Words,
}

pub(super) fn block(
    line: u64,
    span: Range<usize>,
    words: &[Word],
    s: &mut State,
    out: &mut GCode,
    tolerance: f64,
) -> Result<()> {
    check_words(line, words, s)?;
    let inch_before = s.inch;
    let mut given = Given::default();
    for w in words {
        given.word(line, w, s)?;
    }
    motion_and_feed(line, &given, inch_before, s)?;
    if s.motion >= 81 && s.motion != NO_MOTION {
        return cycle(line, span, given, s, out);
    }
    if given.cycle.peck.is_some() {
        return Err(at(line, "Q: a peck depth outside a G83 cycle".into()));
    }
    if !moves(line, &given, s)? {
        return Ok(());
    }
    motion(line, span, given, s, out, tolerance)
}

impl Given {
    /// One word: a mode set in `s`, or a value gathered for the block.
    fn word(&mut self, line: u64, w: &Word, s: &mut State) -> Result<()> {
        let v = w.value;
        match w.letter {
            'G' => self.g(line, w, s)?,
            'X' | 'Y' | 'Z' => {
                self.target[(w.letter as u8 - b'X') as usize] = Some(v);
                self.drop.push(w.span.clone());
            }
            'I' | 'J' | 'K' => {
                self.centre[(w.letter as u8 - b'I') as usize] = Some(v);
                self.drop.push(w.span.clone());
            }
            'R' => {
                self.radius = Some(v);
                self.drop.push(w.span.clone());
            }
            l @ ('U' | 'V' | 'W' | 'A' | 'B' | 'C') if s.external.0.contains(&l) => {
                self.external_axis(line, w, s)?;
            }
            'A' | 'B' | 'C' => {
                rotary(line, w, s)?;
                self.abc = true;
            }
            'T' => {
                if v < 0.0 || v.fract() != 0.0 || v > 1e6 {
                    return Err(at(line, format!("T{v}: expected a tool number 0..1000000")));
                }
                s.tool_number = Some(v as u32);
            }
            'F' => self.feed = Some(v),
            'Q' => {
                self.cycle.peck = Some(v);
                self.drop.push(w.span.clone());
            }
            'P' => self.cycle.dwell = Some((v, w.span.clone())),
            'S' | 'M' | 'N' | 'O' | 'H' | 'D' => {}
            other => return Err(at(line, format!("'{other}': not a word of the supported subset (G M T F S N O P Q X Y Z I J K R, A B C with rotary = abc, U V W A B C mapped by external = LETTERS)"))),
        }
        Ok(())
    }

    /// A `G` word: a motion or cycle gathered, or a mode (plane, units, distances, retract) set.
    fn g(&mut self, line: u64, w: &Word, s: &mut State) -> Result<()> {
        let v = w.value;
        let g = v.round();
        if (v - g).abs() > 1e-9 || !(0.0..100.0).contains(&g) {
            return Err(at(
                line,
                format!("G{v}: not in the supported subset ({SUBSET})"),
            ));
        }
        match g as u8 {
            g @ 0..=3 => self.motion = Some((g, w.span.clone())),
            g @ 81..=83 => {
                self.motion = Some((g, w.span.clone()));
                self.drop.push(w.span.clone());
            }
            g @ (98 | 99) => {
                s.retract_to_r = g == 99;
                self.drop.push(w.span.clone());
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
        Ok(())
    }

    /// A word of an external axis (`external = LETTERS`): its value in `s.e`, in mm or deg.
    fn external_axis(&mut self, line: u64, w: &Word, s: &mut State) -> Result<()> {
        let l = w.letter;
        let k = s.external.0.iter().position(|e| *e == l).unwrap_or(0);
        let v = match (l, s.inch) {
            ('U' | 'V' | 'W', true) => w.value * 25.4,
            _ => w.value,
        };
        s.e[k] = match (s.incremental, s.e[k]) {
            (false, _) => Some(v),
            (true, Some(before)) => Some(before + v),
            (true, None) => {
                return Err(at(
                    line,
                    format!(
                        "{l}: an increment (G91) before the axis has a value: give it in G90 first"
                    ),
                ))
            }
        };
        self.external = true;
        self.external_words.push(w.span.clone());
        Ok(())
    }

    fn centre_given(&self) -> bool {
        self.centre.iter().any(Option::is_some)
    }
}

/// A rotary word (`rotary = abc`): the tool angle in `s.abc`, in deg.
fn rotary(line: u64, w: &Word, s: &mut State) -> Result<()> {
    if !s.rotary {
        return Err(at(
            line,
            format!(
                "{}: rotary words need the header comment (stiffid: rotary = abc)",
                w.letter
            ),
        ));
    }
    if !(-360.0..=360.0).contains(&w.value) {
        return Err(at(
            line,
            format!(
                "{}{}: expected a tool angle from -360 to 360 deg",
                w.letter,
                stiffid_core::common::words::number(w.value)
            ),
        ));
    }
    s.abc[(w.letter as u8 - b'A') as usize] = w.value;
    Ok(())
}

/// The block's motion and feed rate put in force (a cycle starting here remembers its start).
fn motion_and_feed(line: u64, given: &Given, inch_before: bool, s: &mut State) -> Result<()> {
    if let Some((g, _)) = &given.motion {
        if *g >= 81 && s.motion < 81 {
            s.cycle = cycles::Modal::starting_at(s.position.z);
        }
        s.motion = *g;
    }
    if let Some(f) = given.feed {
        s.feed = Some(f * if s.inch { 25.4e-3 } else { 1e-3 } / 60.0);
        s.feed_line = line;
    } else if s.inch != inch_before && s.feed.is_some() {
        return Err(at(line, format!("G{}: the units change while the feed rate F of line {} is in force, and controllers differ on whether it follows them: give F again in this block", if s.inch { 20 } else { 21 }, s.feed_line)));
    }
    Ok(())
}

/// A block in a canned cycle in force: the cycle's words handed to [`cycles::block`].
fn cycle(
    line: u64,
    span: Range<usize>,
    given: Given,
    s: &mut State,
    out: &mut GCode,
) -> Result<()> {
    let other_geometry = given.centre_given() || given.abc || given.external;
    let mut w = given.cycle;
    w.xyz = given.target;
    w.retract = given.radius;
    w.given = given.motion.is_some();
    cycles::block(line, span, w, other_geometry, given.drop, s, out)
}

/// Whether the block moves (an end point, an angle, an external axis, an arc's centre or radius);
/// an error for what cannot move.
fn moves(line: u64, given: &Given, s: &State) -> Result<bool> {
    let arc_only = s.motion >= 2 && (given.centre_given() || given.radius.is_some());
    let moves = given.target.iter().any(Option::is_some) || given.abc || given.external || arc_only;
    if given.external && s.motion >= 2 {
        return Err(at(line, "an external axis moving along an arc: the cell's axes and the arc would not stay together; split the arc into G1 moves".into()));
    }
    if !moves {
        if given.centre_given() || given.radius.is_some() {
            return Err(at(line, "I, J, K or R without an end point".into()));
        }
        return Ok(false);
    }
    if s.motion == NO_MOTION {
        return Err(at(line, "a motion after G80 without G0, G1, G2 or G3: controllers differ on the motion in force after a canned cycle; give it".into()));
    }
    Ok(true)
}

/// The move's end point in m from the block's `X Y Z` (absolute or incremental, mm or inch).
fn end_point(line: u64, given: &Given, s: &State) -> Result<Vector3<f64>> {
    let scale = if s.inch { 25.4e-3 } else { 1e-3 };
    let mut end = s.position;
    for k in 0..3 {
        if let Some(v) = given.target[k] {
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
    Ok(end)
}

/// A straight or circular move: its points added to `out`, and its block.
fn motion(
    line: u64,
    span: Range<usize>,
    given: Given,
    s: &mut State,
    out: &mut GCode,
    tolerance: f64,
) -> Result<()> {
    let tool = may_move(line, s)?;
    let external = external_values(line, s)?;
    let end = end_point(line, &given, s)?;
    let [a, b, c] = s.abc.map(f64::to_radians);
    let orientation = UnitQuaternion::from_euler_angles(a, b, c) * tool;
    let first = out.points.len();
    for p in positions(line, &given, end, s, tolerance)? {
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
            external: external.clone(),
        });
    }
    s.position = end;
    let arc_word = given.motion.filter(|(g, _)| *g >= 2).map(|(_, span)| span);
    out.blocks.push(Block {
        line: span,
        points: first..out.points.len(),
        drop: given.drop,
        external_words: given.external_words,
        arc_word,
        inch: s.inch,
        incremental: s.incremental,
        cycle: None,
    });
    Ok(())
}

/// The positions the move passes, in m: its end point, or an arc's points within `tolerance`.
fn positions(
    line: u64,
    given: &Given,
    end: Vector3<f64>,
    s: &State,
    tolerance: f64,
) -> Result<Vec<Vector3<f64>>> {
    let scale = if s.inch { 25.4e-3 } else { 1e-3 };
    match s.motion {
        2 | 3 => arc(
            line,
            s,
            end,
            given.centre.map(|c| c.map(|v| v * scale)),
            given.radius.map(|r| r * scale),
            tolerance,
        ),
        _ => Ok(vec![end]),
    }
}
