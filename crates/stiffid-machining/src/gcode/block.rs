//! One block applied to the state: modes, motions, canned cycles, the points it makes.

use super::arc::arc;
use super::g53::{g53_outside_g0_g1, machine_frame, unplaced_machine_move};
use super::machine::convert;
use super::modal::{end_point, push_points};
use super::words::{check_words, Word};
use super::{at, cycles, may_move, Block, GCode, Motion, State};
use nalgebra::Vector3;
use std::ops::Range;
use stiffid_core::common::limits::LENGTH_MM;
use stiffid_core::common::words::number;
use stiffid_core::Result;

use super::spline::SPLINE;
use super::subset::unsupported;
use super::subset::SUBSET;
use super::NO_MOTION;

/// The words of one block, gathered before it moves anything (the block's units).
#[derive(Default)]
pub(super) struct Given {
    pub(super) target: [Option<f64>; 3],
    centre: [Option<f64>; 3],
    pub(super) radius: Option<f64>,
    motion: Option<(u8, Range<usize>)>,
    /// Spans the compensated block writes again (targets, centres, cycle words).
    pub(super) drop: Vec<Range<usize>>,
    pub(super) abc: bool,
    pub(super) external: bool,
    external_words: Vec<Range<usize>>,
    feed: Option<f64>,
    cycle: cycles::Words,
    /// The `Q` word's span (a peck depth, or `G64`'s tolerance).
    q_span: Option<Range<usize>>,
    /// A work offset chosen (`54`..`59.3` as ten times the code, `541` for `G54.1`).
    offset: Option<u16>,
    /// `G53`: this block's coordinates are machine coordinates.
    pub(super) g53: bool,
    /// `G28` or `G30`.
    pub(super) home: Option<u8>,
    /// `G43`, `G44` or `G49`.
    length: Option<u8>,
    /// `G64` (its `P` and `Q` are tolerances).
    g64: bool,
    /// `G4`: a dwell.
    g4: bool,
    /// The `H` word.
    h: Option<f64>,
    /// `G40`, `G41` or `G42`, and the span of a `G41`/`G42` word (dropped when written).
    comp: Option<(u8, Option<Range<usize>>)>,
    /// The `D` word and its span.
    d: Option<(f64, Range<usize>)>,
    /// LinuxCNC's polar `@` (distance) and `^` (angle), the block's units (module `polar`).
    polar: [Option<f64>; 2],
    /// The `L` word and its span (a canned cycle's repeats, `G10`'s kind).
    l: Option<(f64, Range<usize>)>,
    /// `G10`: a work offset set (module `g10`).
    g10: bool,
    /// `G92`: the coordinate system shifted (module `g92`).
    g92: bool,
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
    super::groups::one_per_group(line, words)?;
    if super::rotation::block(line, words, s)? {
        return Ok(());
    }
    let inch_before = s.inch;
    let mut given = Given::default();
    for w in words {
        given.word(line, w, s)?;
    }
    if words.iter().any(|w| w.letter == 'M' && w.value == 6.0) {
        // The tool change loads the tool selected (this block's T, else the last one), before
        // the block's tool length offset (LinuxCNC's order of execution).
        (s.changed, s.tool_number) = (true, s.selected);
    }
    super::process::gather(line, words, s);
    if given.g10 {
        return given.set_offset(line, s);
    }
    if given.g92 {
        let other = given.with_other()
            || given.l.is_some()
            || given.radius.is_some()
            || given.cycle.dwell.is_some();
        return super::g92::set(line, (given.target, other), s);
    }
    // LinuxCNC and grbl read an axis word beside G4 P as a move in the motion mode in force,
    // made after the dwell (LinuxCNC's order of execution; grbl's G4 takes no axis words).
    let moves_after_dwell = matches!(
        s.machine.dialect,
        Some(super::GcodeDialect::LinuxCnc | super::GcodeDialect::Grbl)
    ) && words.iter().any(|w| w.letter == 'P' && w.value >= 0.0)
        && given.home.is_none()
        && !given.g53;
    if given.g4 && given.moves_an_axis() && !moves_after_dwell {
        let why = match s.machine.dialect {
            Some(super::GcodeDialect::Fanuc | super::GcodeDialect::Haas) => "only X is the dwell's time (seconds with a decimal point) on FANUC and Haas, another axis word a move",
            Some(_) => "LinuxCNC and grbl refuse a G4 without its time P of 0 or more, or beside G28, G30 or G53 (an axis word beside G4 P alone is a move after the dwell)",
            None => "FANUC and Haas read G4 X as the dwell's time, LinuxCNC and grbl as a move in the motion mode in force, and the setup names no controller ([controller] dialect)",
        };
        return Err(at(line, format!("G4 with an axis word: {why}; write the dwell as G4 P in a block without axis words")));
    }
    given.modes(line, s)?;
    motion_and_feed(line, &given, inch_before, s)?;
    super::polar::resolve(line, given.polar, (&mut given.target, given.g53), s)?;
    if given.g53 && (given.home.is_some() || s.motion >= 81 && s.motion != NO_MOTION) {
        return Err(g53_outside_g0_g1(line, given.home, s));
    }
    super::dialect::before_motion(line, &given.moves(s), s)?;
    if given.home.is_some() || given.g53 || s.motion >= 81 && s.motion != NO_MOTION {
        super::cutter::refuse_while_on(line, "G28, G30, G53 or a canned cycle", s)?;
    }
    if let Some(code) = given.home {
        let other = given.centre_given() || given.radius.is_some() || given.abc || given.external;
        let named = given.target.map(|t| t.is_some());
        super::home::home(line, span, (given.target, other), code, s, out)?;
        super::dialect::at_home(line, (code, named), s);
        return Ok(());
    }
    if s.motion >= 81 && s.motion != NO_MOTION {
        return cycle(line, span, given, s, out);
    }
    if given.cycle.peck.is_some() {
        return Err(at(line, "Q: a peck depth outside a G83 cycle".into()));
    }
    if let Some((l, _)) = given.l {
        return Err(at(
            line,
            format!(
                "L{}: a number of repeats outside a canned cycle (G81-G83)",
                number(l)
            ),
        ));
    }
    if !moves(line, &given, s)? {
        return Ok(());
    }
    if given.g53 && s.incremental && s.motion < 2 {
        // Absolute machine coordinates whatever the distance mode (the dialects that say so).
        super::dialect::g53_in_g91(line, s)?;
        s.incremental = false;
        let moved = motion(line, span, given, s, out, tolerance);
        s.incremental = true;
        return moved;
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
            'A' | 'B' | 'C' if !s.rotary && w.value == 0.0 => {
                s.zero_rotary.get_or_insert(line);
            }
            'A' | 'B' | 'C' => {
                rotary(line, w, s)?;
                self.abc = true;
            }
            'T' => {
                if v < 0.0 || v.fract() != 0.0 || v > 1e6 {
                    return Err(at(line, format!("T{v}: expected a tool number 0..1000000")));
                }
                s.selected = Some(v as u32);
                if !s.changed {
                    // No tool change yet: the program's T is the tool in use (a machine
                    // without a tool changer).
                    s.tool_number = s.selected;
                    s.first_tool_named();
                }
            }
            '@' | '^' => {
                self.polar[usize::from(w.letter == '^')] = Some(v);
                self.drop.push(w.span.clone());
            }
            'F' => self.feed = Some(v),
            'Q' => {
                self.cycle.peck = Some(v);
                self.q_span = Some(w.span.clone());
            }
            'P' => self.cycle.dwell = Some((v, w.span.clone())),
            'H' => self.h = Some(v),
            'L' => self.l = Some((v, w.span.clone())),
            'D' => self.d = Some((v, w.span.clone())),
            'S' | 'M' | 'N' | 'O' => {}
            other => return Err(at(line, format!("'{other}': not a word of the supported subset (G M T F S N O P Q X Y Z I J K R, A B C with rotary = abc, U V W A B C mapped by external = LETTERS)"))),
        }
        Ok(())
    }

    /// A `G` word: a motion or cycle gathered, or a mode (plane, units, distances, retract) set.
    fn g(&mut self, line: u64, w: &Word, s: &mut State) -> Result<()> {
        let v = w.value;
        let tenths = (v * 10.0).round();
        if (v * 10.0 - tenths).abs() > 1e-6 || !(0.0..1000.0).contains(&tenths) {
            return Err(at(
                line,
                format!("G{v}: not in the supported subset ({SUBSET})"),
            ));
        }
        let tenths = tenths as u16;
        if !tenths.is_multiple_of(10) {
            return self.g_decimal(line, (tenths, w.span.clone()), s);
        }
        match (tenths / 10) as u8 {
            g @ (54..=59) => self.offset = Some(u16::from(g) * 10),
            53 => self.g53 = true,
            g @ (28 | 30) => self.home = Some(g),
            g @ (43 | 44 | 49) => self.length = Some(g),
            64 => self.g64 = true,
            61 => {}
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
            g @ (41 | 42) => self.comp = Some((g, Some(w.span.clone()))),
            40 => self.comp = Some((40, None)),
            10 => self.g10 = true,
            92 => self.g92 = true,
            g @ 17..=19 => {
                if g != s.plane {
                    super::cutter::refuse_while_on(line, &format!("G{g}: a change of plane"), s)?;
                }
                s.plane = g;
            }
            20 => (s.inch, s.units_stated) = (true, true),
            21 => (s.inch, s.units_stated) = (false, true),
            90 => s.incremental = false,
            91 => s.incremental = true,
            4 => self.g4 = true,
            69 | 80 | 94 => {}
            g => return Err(unsupported(line, &format!("G{g}"))),
        }
        Ok(())
    }

    /// A `G` word with a decimal: `G5.1`, `G54.1`, `G59.1`-`G59.3`, `G61.1`, `G90.1`, `G91.1`.
    fn g_decimal(
        &mut self,
        line: u64,
        (tenths, span): (u16, Range<usize>),
        s: &mut State,
    ) -> Result<()> {
        match tenths {
            51 => self.motion = Some((SPLINE, span)),
            541 | 591..=593 => self.offset = Some(tenths),
            611 => {}
            // G92.1, G92.2: no G92 offset in force (module `g92`).
            921 | 922 => super::g92::cancel(s),
            901 => s.ij_absolute = true,
            911 => s.ij_absolute = false,
            _ => {
                let g = format!("G{}.{}", tenths / 10, tenths % 10);
                return Err(unsupported(line, &g));
            }
        }
        Ok(())
    }

    /// The modes the block's words put in force together: `G64`'s `P Q`, a work offset, a tool
    /// length offset.
    fn modes(&mut self, line: u64, s: &mut State) -> Result<()> {
        if self.g64 {
            self.cycle.peck = None;
            self.cycle.dwell = None;
        } else if let Some(q) = self.q_span.take() {
            self.drop.push(q);
        }
        if self.offset.is_some() {
            super::cutter::refuse_while_on(line, "a work offset selected", s)?;
        }
        if self.length.is_some() {
            super::cutter::refuse_while_on(line, "a tool length offset changed", s)?;
        }
        if let Some((code, span)) = self.comp.clone() {
            super::cutter::set(line, code, self.d.as_ref().map(|d| d.0), s)?;
            s.dropped.extend(span);
            if code != 40 {
                s.dropped.extend(self.d.as_ref().map(|d| d.1.clone()));
            }
        }
        if let Some(code) = self.offset {
            let name = match code {
                541 => {
                    let p = self.cycle.dwell.take().map(|(p, _)| p);
                    match p {
                        Some(p) if p.fract() == 0.0 && (1.0..=1e4).contains(&p) => format!("G54.1 P{p}"),
                        _ => return Err(at(line, "G54.1: expected the additional work offset's number P in the block (G54.1 P1)".into())),
                    }
                }
                c if c.is_multiple_of(10) => format!("G{}", c / 10),
                c => format!("G{}.{}", c / 10, c % 10),
            };
            s.set_frame(super::modal::frame(line, name, s)?);
        }
        match self.length {
            Some(49) => s.change_length_offset(line, 0.0),
            Some(g) => self.length_offset(line, g, s)?,
            None => {}
        }
        if self.length.is_some() {
            s.home_cancel = None;
        }
        Ok(())
    }

    /// `G43`/`G44` with `H` (or, without, the tool in use as LinuxCNC reads it): the tool's
    /// length from the table put in force.
    fn length_offset(&self, line: u64, g: u8, s: &mut State) -> Result<()> {
        super::dialect::length_offset_allowed(line, g, s)?;
        if s.machine.tool_lengths.is_empty() {
            return Err(at(line, format!("G{g}: a tool length offset needs the tools' lengths: give [tool] length_mm in the process's operations (with their tool_number)")));
        }
        let n = match (self.h, s.tool_number) {
            (Some(h), _) if h.fract() == 0.0 && (0.0..=1e6).contains(&h) => Some(h as u32),
            (Some(h), _) => return Err(at(line, format!("H{h}: expected a tool number"))),
            (None, Some(t)) => Some(t),
            // One length for every tool (an operation without tool_number): whichever tool the
            // spindle holds, that is its length.
            (None, None) if s.machine.tool_lengths.iter().all(|(t, _)| t.is_none()) => None,
            (None, None) => {
                return Err(at(
                    line,
                    format!(
                        "G{g} without H before any T: which tool's length is meant is not known"
                    ),
                ))
            }
        };
        let Some(length) = s.machine.tool_length(n) else {
            let n = n.unwrap_or(0);
            return Err(at(line, format!("G{g} H{n}: the process's tool table has no length for tool {n} (give [tool] length_mm in the operation with tool_number = {n})")));
        };
        let h = if g == 44 { -length } else { length };
        s.change_length_offset(line, h);
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

    /// A `G10` block: a work offset set (module `g10`), nothing else in it.
    fn set_offset(&self, line: u64, s: &mut State) -> Result<()> {
        if self.with_other() {
            return Err(at(line, "G10 with a motion, a dwell, another offset or arc words in its block: write the G10 in a block of its own".into()));
        }
        let words = super::g10::Words {
            l: self.l.as_ref().map(|(l, _)| *l),
            p: self.cycle.dwell.as_ref().map(|(p, _)| *p),
            xyz: self.target,
            r: self.radius,
        };
        super::g10::apply(line, &words, s)
    }

    /// Whether the block has a motion, a dwell, an offset or arc words beside a `G10` or `G92`.
    fn with_other(&self) -> bool {
        self.motion.is_some()
            || self.home.is_some()
            || self.g53
            || self.offset.is_some()
            || self.length.is_some()
            || self.comp.is_some()
            || self.g4
            || self.abc
            || self.external
            || self.centre_given()
            || self.polar.iter().any(Option::is_some)
            || self.g10 && self.g92
    }

    /// Whether the block gives an axis word (X Y Z, a rotary or an external axis).
    fn moves_an_axis(&self) -> bool {
        self.target.iter().any(Option::is_some) || self.abc || self.external
    }

    /// What the dialect's rules need to know of the block's motion (module `dialect`).
    fn moves(&self, s: &State) -> super::dialect::Moves {
        let arc = (2..=3).contains(&s.motion) && (self.centre_given() || self.radius.is_some());
        super::dialect::Moves {
            target: self.target,
            home: self.home.is_some(),
            g53: self.g53,
            other: self.abc || self.external || arc,
        }
    }

    /// What a `G5.1` block gives beside its end point (module `spline`).
    fn spline(&self) -> super::spline::Words {
        let other = [
            (self.target[2].is_some(), "Z"),
            (self.centre[2].is_some(), "K"),
            (self.radius.is_some(), "R"),
            (self.cycle.dwell.is_some(), "P"),
            (self.abc || self.external, "a rotary or external axis word"),
            (self.g53, "G53"),
        ];
        super::spline::Words {
            ij: [0, 1].map(|k| self.centre[k]),
            other: other.into_iter().find(|(o, _)| *o).map(|(_, w)| w),
        }
    }

    pub(super) fn centre_given(&self) -> bool {
        self.centre.iter().any(Option::is_some)
    }
}

/// A rotary word (`rotary = abc`): the tool angle in `s.abc`, in deg.
fn rotary(line: u64, w: &Word, s: &mut State) -> Result<()> {
    if !s.rotary {
        return Err(at(
            line,
            format!(
                "{}{}: a rotary axis off its zero, and the cell has none for it (a program whose every A, B, C word is 0 is read without them): map the letter to the cell's positioner, (stiffid: external = ..), or let it turn the tool, (stiffid: rotary = abc)",
                w.letter,
                stiffid_core::common::words::number(w.value)
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
            s.cycle = cycles::Modal::starting_at(line, s.position.z);
        } else if *g >= 81 && *g != s.motion {
            s.cycle.other_code(line, s.machine.dialect);
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
    let mut given = given;
    let mut w = std::mem::take(&mut given.cycle);
    // FANUC's repeats are K (Series 0i; L in its FS15 format); K alone, no I or J, is read so on
    // FANUC only (LinuxCNC's G81 takes no K).
    let fanuc_k = s.machine.dialect == Some(super::GcodeDialect::Fanuc)
        && given.centre[..2].iter().all(Option::is_none)
        && given.l.is_none();
    let k = given.centre[2].take_if(|_| fanuc_k);
    let other_geometry = given.centre_given() || given.abc || given.external;
    w.xyz = given.target;
    w.retract = given.radius;
    w.given = given.motion.is_some();
    w.repeats = given.l.as_ref().map(|(l, _)| *l).or(k);
    w.polar = given.polar;
    given.drop.extend(given.l.map(|(_, span)| span));
    cycles::block(line, span, w, other_geometry, given.drop, s, out)
}

/// Whether the block moves (an end point, an angle, an external axis, an arc's centre or radius);
/// an error for what cannot move.
pub(super) fn moves(line: u64, given: &Given, s: &State) -> Result<bool> {
    let arc_only = s.motion >= 2 && (given.centre_given() || given.radius.is_some());
    let moves = given.target.iter().any(Option::is_some) || given.abc || given.external || arc_only;
    if s.motion < 2 && (given.centre_given() || given.radius.is_some()) {
        return Err(at(line, format!("I, J, K or R (an arc's centre or radius) in a G{} block: LinuxCNC refuses it, other controllers ignore it; leave them out of a straight move", s.motion)));
    }
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

/// A straight or circular move: its points added to `out`, and its block (a `G53` block's
/// coordinates in the machine's frame, of the spindle's gauge line).
fn motion(
    line: u64,
    span: Range<usize>,
    given: Given,
    s: &mut State,
    out: &mut GCode,
    tolerance: f64,
) -> Result<()> {
    may_move(line, s)?;
    let lift = s.lift();
    // G53's coordinates are the spindle's, the tool length offset not applied (LinuxCNC's
    // find_ends, FANUC): the position is carried as the gauge line's, the programmed point
    // raised by the offset in force (known whatever the tool in use), with the spindle's lift
    // on both sides.
    let (frame, block_lift, (from_lift, raise)) = match given.g53 {
        true => match machine_frame(line, s)? {
            Some(frame) => {
                let spindle = s.spindle_lift();
                (frame, spindle, (spindle, s.length_offset))
            }
            None => return unplaced_machine_move(line, given.target.map(|t| t.is_some()), s, out),
        },
        false => (s.frame.clone(), lift, (lift, 0.0)),
    };
    let raised = s.position + Vector3::z() * raise;
    let here = convert(
        (raised, s.known),
        (&s.frame, from_lift),
        (&frame, block_lift),
    );
    let (end, known) = end_point(line, &given.target, here, s)?;
    let back = |end, known, s: &State| {
        let (p, k) = convert((end, known), (&frame, block_lift), (&s.frame, from_lift));
        (p - Vector3::z() * raise, k)
    };
    if !known.iter().all(|k| *k) {
        if s.motion != 0 {
            let what = format!("G{}: a feed move", s.motion);
            return Err(super::modal::refuse_unknown(line, &what, known, s));
        }
        s.pending.get_or_insert(line);
        (s.position, s.known) = back(end, known, s);
        return Ok(());
    }
    if s.motion != 0 && !here.1.iter().all(|k| *k) {
        let what = match s.motion {
            1 => "G1: a feed move".to_string(),
            g => format!("G{g}: an arc"),
        };
        return Err(super::modal::refuse_unknown(line, &what, here.1, s));
    }
    if s.motion == 0 && block_lift.is_none() && s.tool_number.is_none() {
        // Before any T the spindle holds whatever tool the machine holds, whose length the
        // program does not say: the rapid's programmed point is known, its tip is not.
        s.untooled.get_or_insert(line);
        (s.position, s.known) = back(end, known, s);
        return Ok(());
    }
    let positions = if s.motion == SPLINE {
        (
            super::spline::points(line, &given.spline(), end, s, tolerance)?,
            None,
        )
    } else if s.motion >= 2 {
        let (points, centre) = positions(line, &given, end, s, tolerance)?;
        (points, Some(centre))
    } else {
        (vec![end], None)
    };
    if !here.1.iter().all(|k| *k) {
        super::cutter::refuse_while_on(line, "a move from a place not known", s)?;
    }
    let positions = super::cutter::apply(line, here.0, positions, tolerance, s, out)?;
    let motion = if s.motion == 0 {
        Motion::Rapid
    } else {
        Motion::Feed
    };
    let first = out.points.len();
    push_points(line, &positions, motion, (&frame, block_lift), s, out)?;
    (s.position, s.known) = back(end, known, s);
    let arc_word = given.motion.filter(|(g, _)| *g >= 2).map(|(_, span)| span);
    let to_program = super::machine::to_program(&frame, block_lift.unwrap_or(0.0));
    out.blocks.push(Block {
        line: span,
        points: first..out.points.len(),
        drop: given.drop,
        external_words: given.external_words,
        arc_word,
        spline: s.motion == SPLINE,
        inch: s.inch,
        incremental: s.incremental,
        to_program,
        verbatim: false,
        take_up: std::mem::take(&mut s.take_up),
        cycle: None,
    });
    if let (false, 0.0, Some(lift)) = (given.g53, s.length_offset, block_lift)
        && lift < 0.0
    {
        out.no_length_offset.get_or_insert((line, -lift));
    }
    Ok(())
}

/// The positions an arc passes, in m, within `tolerance`, and its centre in the plane.
fn positions(
    line: u64,
    given: &Given,
    end: Vector3<f64>,
    s: &State,
    tolerance: f64,
) -> Result<(Vec<Vector3<f64>>, [f64; 2])> {
    if let Some((p, _)) = &given.cycle.dwell {
        return Err(at(line, format!("P{}: an arc's number of turns (LinuxCNC's G2/G3 P) is not read: write each turn as an arc of its own", number(*p))));
    }
    let scale = if s.inch { 25.4e-3 } else { 1e-3 };
    let words = ['I', 'J', 'K'].into_iter().zip(given.centre);
    for (letter, v) in words.chain([('R', given.radius)]) {
        if let Some(v) = v.filter(|v| !LENGTH_MM.contains(v * scale * 1e3)) {
            return Err(at(
                line,
                format!(
                    "{letter}{}: an arc's centre or radius beyond 100 m",
                    number(v)
                ),
            ));
        }
    }
    arc(
        line,
        s,
        end,
        given.centre.map(|c| c.map(|v| v * scale)),
        given.radius.map(|r| r * scale),
        tolerance,
    )
}
