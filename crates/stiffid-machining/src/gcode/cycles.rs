//! Drilling canned cycles `G81` (drill), `G82` (drill, dwell at the bottom) and `G83` (peck
//! drill), read as the moves they make (the sequence of LinuxCNC's and FANUC's manuals) and
//! written back as those moves, `G0`/`G1`/`G4` blocks of their own, so the controller runs the
//! compensated points and never a cycle of its own.
//!
//! In a cycle (until `G0`-`G3` or `G80`) every block with `X`, `Y` or `Z` (or the `G8x` word)
//! drills one hole at its `X Y`: rapid up to `R` if below it, rapid over the hole, rapid down to
//! `R`, feed to `Z` (`G83`: pecks of `Q`, each followed by a rapid out to `R` and a rapid back to
//! [`PECK_CLEARANCE_MM`] above the depth reached), dwell `P` (`G82`), rapid out to the clearance
//! level (`G98`, the default: the higher of `R` and the level the cycle started from; `G99`: `R`).
//! Each feed has a point where the drill meets material, the part's surface (`Z = 0` of the part
//! frame, or `(stiffid: surface_mm = Z)`) when below `R`, or the depth a peck reached, stated
//! twice (the drill arrives there unloaded, then takes its thrust): the feed from there to its
//! end cuts, the rest of the cycle moves in the air or in the hole drilled ([`crate::cutting`]).
//! Each feed's end (a peck's, the bottom) is stated twice as well: reached under the thrust,
//! then the same point as a rapid, without it, from where the exit (`G82`'s dwell, the rapid
//! out) starts: the drill stops feeding there, and a robot that held the loaded pose while
//! its thrust goes would leave the hole's axis. `Z`, `R`, `Q` and `P` stay in force within a cycle.
//! The hole is drilled in the work offset and tool length offset in force (its levels
//! programmed there, its points the tip in the `G54` part frame). Under `G91`, `R` counts from
//! the level the cycle started from and `Z` from `R`, the hole's `X Y` from where the tool is; a
//! block's repeats `L` (FANUC's `K`) drill again, each from the last by its increments under
//! `G91`, in one place under `G90` (LinuxCNC's `interp_cycles.cc`, `convert_cycle_xy` and
//! `CYCLE_MACRO`, after NCMS page 98). Refused naming the line: a cycle outside the `G17`
//! plane, in a work offset that turns the part's `Z` axis, with the tool not pointing along the part's `-Z`, with `I J K` or rotary words, without
//! `Z` or `R` or a feed rate `F` in force, a bottom not below `R` or not below the part's surface, a `G83` without a positive `Q`, `P` outside `G82` and `Q`
//! outside `G83`, and a block of `R`, `Q` or `P` alone (controllers differ on whether it drills).

use super::{at, may_move, Block, GCode, GcodeDialect, Motion, Point, State, MAX_POINTS};
use nalgebra::{UnitQuaternion, Vector3};
use std::ops::Range;
use stiffid_core::Result;

/// How far above the depth reached a `G83` peck's rapid re-approach stops, mm (LinuxCNC's
/// 0.010 inch).
pub(crate) const PECK_CLEARANCE_MM: f64 = 0.254;

/// Two levels of a cycle closer than this are one, m (a nanometre: far below a controller's
/// resolution, far above floating point's error in m).
const LEVEL_TOLERANCE: f64 = 1e-9;

/// One hole of a drilling canned cycle, part frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Cycle {
    /// The line of its block, 1-based.
    pub line: u64,
    /// `81`, `82` or `83`.
    pub code: u8,
    /// The bottom of the hole (`X Y Z`), m.
    pub bottom: Vector3<f64>,
    /// The `R` level the feed starts from, m.
    pub retract: f64,
    /// The level it leaves to (`G98`: the higher of `R` and the level the cycle started from;
    /// `G99`: `R`), m.
    pub clearance: f64,
    /// `G82`'s dwell `P`, as written (the controller's unit: seconds or milliseconds).
    pub dwell: Option<f64>,
    /// `G83`'s peck depth `Q`, m.
    pub peck: Option<f64>,
    /// The level where the drill first meets material, m: the part's surface (`Z = 0` or
    /// `(stiffid: surface_mm = Z)`), or `R` when that lies below it (`GCode::drilled_in_air`).
    pub entry: f64,
}

impl GCode {
    /// Whether each point is fed by a canned cycle without cutting (`Cycle::entry`): a feed
    /// that ends at or above the material's level, which is the hole's entry until a feed has
    /// gone deeper and then the depth reached (the feed from `R` down to the surface, a peck's
    /// re-entry down to the depth the last peck reached, a peck that stays above the surface).
    /// The cycle states the point where the drill meets material twice: reached unloaded, then
    /// (a move of no length) under the thrust, from where the feed below cuts and carries it.
    /// `false` for every point outside a cycle.
    pub(crate) fn drilled_in_air(&self) -> Vec<bool> {
        let mut levels: Vec<f64> = self.cycles.iter().map(|c| c.entry).collect();
        (self.points.iter().enumerate())
            .map(|(i, p)| match (p.cycle, p.motion) {
                (Some(k), Motion::Feed) => {
                    let Some(level) = levels.get_mut(k) else {
                        return false;
                    };
                    let z = p.position.z;
                    // The point where the drill meets material, again: the cut starts there.
                    let engaged = i > 0 && {
                        let q = &self.points[i - 1];
                        q.motion == Motion::Feed && (q.position - p.position).norm() <= 1e-12
                    };
                    let air = z >= *level - 1e-12 && !engaged;
                    *level = level.min(z);
                    air
                }
                _ => false,
            })
            .collect()
    }
}

/// The cycle's words in force (modal within a cycle), in the units of their blocks (m).
#[derive(Debug, Clone, Default)]
pub(super) struct Modal {
    /// The `Z` level before the cycle's first block.
    initial: f64,
    /// The `Z` word as written (absolute, or under `G91` from `R`), m.
    depth: Option<f64>,
    /// The `R` word as written (absolute, or under `G91` from the initial level), m.
    retract: Option<f64>,
    peck: Option<f64>,
    /// `P`: its value and its text.
    dwell: Option<(f64, String)>,
    /// The line where the cycle (its code, on LinuxCNC) started: its words count from there.
    start: u64,
}

impl Modal {
    /// A cycle starting on `line` with the tool at `z`.
    pub(super) fn starting_at(line: u64, z: f64) -> Self {
        Modal {
            initial: z,
            start: line,
            ..Default::default()
        }
    }

    /// Another cycle code on `line` (`G81` then `G83`, no `G80` between): FANUC and Haas keep
    /// `Z R Q P` until `G80`; LinuxCNC needs them again, from the level the cycle started from
    /// (`interp_cycles.cc`: `convert_cycle` takes `cycle_r` only while `motion_mode` is the
    /// block's, `convert_cycle_xy` likewise `Z`, `P` and `Q`), as does a reading without a
    /// dialect (the two differ).
    pub(super) fn other_code(&mut self, line: u64, dialect: Option<GcodeDialect>) {
        if !matches!(dialect, Some(GcodeDialect::Fanuc | GcodeDialect::Haas)) {
            *self = Modal::starting_at(line, self.initial);
        }
    }
}

/// Why a cycle without its `Z` or `R` in force is refused, per dialect.
fn no_depth(start: u64, dialect: Option<GcodeDialect>) -> String {
    let how = match dialect {
        Some(GcodeDialect::Fanuc | GcodeDialect::Haas) => "FANUC and Haas keep Z and R until G80 and would drill to the levels the control holds from before, which the program does not state",
        Some(GcodeDialect::LinuxCnc) => "LinuxCNC refuses the block (interp_cycles.cc: Z and R are needed when a cycle starts, or follows another cycle code)",
        _ => "LinuxCNC refuses the block, FANUC and Haas would drill to the levels the control holds from before, which the program does not state",
    };
    format!("a canned cycle needs its depth Z and its retract level R, and neither this block nor one since the cycle started (line {start}) gives both: {how}; give them")
}

/// The words of one block that a cycle reads, as written (the block's units).
#[derive(Debug, Default)]
pub(super) struct Words {
    pub xyz: [Option<f64>; 3],
    pub retract: Option<f64>,
    pub peck: Option<f64>,
    pub dwell: Option<(f64, Range<usize>)>,
    /// The block has the `G8x` word.
    pub given: bool,
    /// The number of repeats (`L`, FANUC's `K`), as written.
    pub repeats: Option<f64>,
    /// LinuxCNC's polar `@` and `^` (module `polar`), the block's units: under `G91` added
    /// again at each repeat.
    pub polar: [Option<f64>; 2],
}

/// A block in a canned cycle (module docs): its holes' moves added to `out`, one hole per
/// repeat (`L`, FANUC's `K`).
pub(super) fn block(
    line: u64,
    span: Range<usize>,
    w: Words,
    other_geometry: bool,
    mut drop: Vec<Range<usize>>,
    s: &mut State,
    out: &mut GCode,
) -> Result<()> {
    let scale = if s.inch { 25.4e-3 } else { 1e-3 };
    if let Some((_, r)) = &w.dwell {
        drop.push(r.clone());
    }
    keep_in_force(&w, scale, &out.text, s);
    let repeats = repeats(line, &w, s)?;
    let drills = w.given || w.xyz.iter().any(Option::is_some) || w.repeats.is_some();
    if !drills {
        if w.retract.is_some() || w.peck.is_some() || w.dwell.is_some() {
            return Err(at(line, format!("G{}: R, Q or P without X, Y or Z: controllers differ on whether such a block drills; give the hole's X Y", s.motion)));
        }
        return Ok(());
    }
    if repeats == 0 {
        if w.xyz[0].is_some() || w.xyz[1].is_some() || w.polar.iter().any(Option::is_some) {
            return Err(at(line, format!("G{}: no repeat (L0 or K0) with X or Y: the cycle's words are kept without drilling, and controllers differ on whether the tool moves to X Y; give the X Y in a block of its own", s.motion)));
        }
        return Ok(());
    }
    let mut block = Block {
        line: span,
        points: out.points.len()..out.points.len(),
        drop,
        external_words: Vec::new(),
        arc_word: None,
        spline: false,
        inch: s.inch,
        incremental: s.incremental,
        to_program: s.to_program().ok_or_else(|| s.no_length(line))?,
        verbatim: false,
        take_up: 0.0,
        cycle: None,
    };
    let (mut bottoms, mut dwell) = (Vec::new(), None);
    for _ in 0..repeats {
        let xy = hole_xy(line, &w, scale, s)?;
        let hole = hole(line, xy, other_geometry, s)?;
        let (moves, bottom_index) = moves(&hole, s);
        if !moves
            .iter()
            .all(|(p, _)| p.iter().all(|v| v.abs() <= 100.0))
        {
            return Err(at(line, "position beyond 100 m".into()));
        }
        bottoms.push(out.points.len() - block.points.start + bottom_index);
        dwell = hole.dwell.as_ref().map(|(_, text)| text.clone());
        push(line, hole, &moves, bottom_index, s, out)?;
        if out.points.len() > MAX_POINTS {
            return Err(at(
                line,
                format!("more than {MAX_POINTS} path points (after the cycle's repeats)"),
            ));
        }
    }
    block.points.end = out.points.len();
    block.cycle = Some(dwell.map(|text| (bottoms, text)));
    out.blocks.push(block);
    Ok(())
}

/// The number of holes the block drills: its `L` (FANUC's `K`, module docs), 1 without.
fn repeats(line: u64, w: &Words, s: &State) -> Result<u32> {
    let Some(l) = w.repeats else {
        return Ok(1);
    };
    if l.fract() != 0.0 || !(0.0..=MAX_POINTS as f64).contains(&l) {
        return Err(at(
            line,
            format!(
                "L{}: expected a number of repeats, a whole number from 0 to {MAX_POINTS}",
                stiffid_core::common::words::number(l)
            ),
        ));
    }
    if l == 0.0
        && !matches!(
            s.machine.dialect,
            Some(GcodeDialect::Fanuc | GcodeDialect::Haas)
        )
    {
        return Err(at(line, "L0: no repeat; LinuxCNC refuses it, FANUC and Haas keep the cycle's words without drilling, and the setup does not name FANUC or Haas ([controller] dialect)".into()));
    }
    Ok(l as u32)
}

/// The X Y (m, the frame in force) of the next hole: the block's (or the current ones) under
/// `G90`; under `G91` the block's increments (or its polar ones) added to where the tool is, at
/// each repeat (LinuxCNC's `interp_cycles.cc`, FANUC's and Haas's repeats).
fn hole_xy(line: u64, w: &Words, scale: f64, s: &State) -> Result<(f64, f64)> {
    if !s.incremental {
        let x = w.xyz[0].map_or(s.position.x, |v| v * scale);
        let y = w.xyz[1].map_or(s.position.y, |v| v * scale);
        return Ok((x, y));
    }
    if !(s.known[0] && s.known[1]) {
        let known = [s.known[0], s.known[1], true];
        let why = format!(
            "G{}: a canned cycle's increments (G91) from a place not known: {}",
            s.motion,
            s.unknown(known)
        );
        return Err(at(line, why));
    }
    let (mut x, mut y) = (s.position.x, s.position.y);
    let [radius, angle] = w.polar;
    if radius.is_none() && angle.is_none() {
        x += w.xyz[0].unwrap_or(0.0) * scale;
        y += w.xyz[1].unwrap_or(0.0) * scale;
        return Ok((x, y));
    }
    if x == 0.0 && y == 0.0 {
        return Err(at(line, "polar coordinates (@ ^): G91 at the XY origin has no angle to add to (LinuxCNC refuses the block)".into()));
    }
    let r = x.hypot(y) + radius.unwrap_or(0.0) * scale;
    let t = y.atan2(x) + angle.unwrap_or(0.0).to_radians();
    Ok((r * t.cos(), r * t.sin()))
}

/// The block's `Z`, `R`, `Q` and `P` kept in force for the cycle's next blocks.
fn keep_in_force(w: &Words, scale: f64, text: &str, s: &mut State) {
    if let Some((v, r)) = &w.dwell {
        s.cycle.dwell = Some((*v, text[r.clone()].to_string()));
    }
    if let Some(z) = w.xyz[2] {
        s.cycle.depth = Some(z * scale);
    }
    if let Some(r) = w.retract {
        s.cycle.retract = Some(r * scale);
    }
    if let Some(q) = w.peck {
        s.cycle.peck = Some(q * scale);
    }
}

/// One hole as the cycle drills it (m, part frame), the tool's orientation along it.
struct Hole {
    code: u8,
    x: f64,
    y: f64,
    depth: f64,
    retract: f64,
    clearance: f64,
    peck: Option<f64>,
    /// `P`: its value and its text.
    dwell: Option<(f64, String)>,
    orientation: UnitQuaternion<f64>,
    /// Where the drill meets material ([`Cycle::entry`]).
    entry: f64,
    /// The part's surface, programmed `Z`.
    surface: f64,
    /// From a programmed `Z` to the part frame's (`State::part_z_shift`), m.
    shift: f64,
}

impl Hole {
    fn at_xy(&self, z: f64) -> Vector3<f64> {
        Vector3::new(self.x, self.y, z)
    }
}

/// The hole a drilling block makes, or the reason (module docs) it is refused.
fn hole(line: u64, (x, y): (f64, f64), other_geometry: bool, s: &State) -> Result<Hole> {
    let code = s.motion;
    let refuse = |why: &str| Err(at(line, format!("G{code}: {why}")));
    if s.plane != 17 {
        return refuse("a canned cycle outside the G17 plane; stiffid drills along the part's Z");
    }
    if other_geometry {
        return refuse("I, J, K, rotary or external axis words in a canned cycle");
    }
    if !s.known[2] {
        // X and Y unknown make no point (the rapid over the hole is the first one); the
        // level the cycle starts from must be known (G98 returns to it).
        s.known(line, &format!("G{code}: a canned cycle"))?;
    }
    let shift = s.part_z_shift(line, &format!("G{code}: a canned cycle"))?;
    let surface = s.surface - shift;
    let tool = may_move(line, s)?;
    let orientation = super::rotation::tool_turn(&s.frame, s)
        * UnitQuaternion::from_euler_angles(
            s.abc[0].to_radians(),
            s.abc[1].to_radians(),
            s.abc[2].to_radians(),
        )
        * tool;
    if (orientation * Vector3::z() + Vector3::z()).norm() > 1e-9 {
        return refuse("a canned cycle drills along the part's -Z, and the tool does not point that way (tool_rpy_deg)");
    }
    let (Some(depth), Some(retract)) = (s.cycle.depth, s.cycle.retract) else {
        return refuse(&no_depth(s.cycle.start, s.machine.dialect));
    };
    // Under G91, R counts from the level the cycle started from and Z from R (LinuxCNC's
    // `interp_cycles.cc` after [NCMS, page 98]; FANUC and Haas alike).
    let (depth, retract) = match s.incremental {
        true => (s.cycle.initial + retract + depth, s.cycle.initial + retract),
        false => (depth, retract),
    };
    if depth >= retract {
        return refuse("the bottom Z must lie below the retract level R");
    }
    if s.feed.is_none() {
        return refuse("a canned cycle feeds to Z at the feed rate F in force, and none is: give F in this block or before");
    }
    if depth >= surface {
        return refuse(&format!("the bottom Z must lie below the part's surface (Z = {} mm of the part frame; state it with the comment (stiffid: surface_mm = Z))", s.surface * 1e3));
    }
    let peck = match (code, s.cycle.peck) {
        (83, Some(q)) if q > 0.0 => Some(q),
        (83, _) => return refuse("a peck depth Q above 0 is needed"),
        (_, Some(_)) => return refuse("Q (a peck depth) belongs to G83"),
        _ => None,
    };
    let dwell = match (code, &s.cycle.dwell) {
        (82, Some(p)) if p.0 >= 0.0 => Some(p.clone()),
        (82, _) => return refuse("a dwell P of 0 or more is needed"),
        (_, Some(_)) => return refuse("P (a dwell) belongs to G82"),
        _ => None,
    };
    if let Some(q) = peck
        && (retract - depth) / q > MAX_POINTS as f64 / 3.0
    {
        return refuse(&format!("more than {MAX_POINTS} path points of pecks"));
    }
    let clearance = match s.retract_to_r {
        true => retract,
        false => retract.max(s.cycle.initial),
    };
    Ok(Hole {
        code,
        x,
        y,
        depth,
        retract,
        clearance,
        peck,
        dwell,
        orientation,
        entry: retract.min(surface),
        surface,
        shift,
    })
}

/// The hole's moves from the tool's position (module docs), and the index of the bottom's
/// thrust-free point (where a `G82` dwells).
fn moves(hole: &Hole, s: &State) -> (Vec<(Vector3<f64>, Motion)>, usize) {
    let (depth, retract) = (hole.depth, hole.retract);
    let mut moves: Vec<(Vector3<f64>, Motion)> = Vec::new();
    let mut here = s.position;
    let mut go = |p: Vector3<f64>, m: Motion, moves: &mut Vec<(Vector3<f64>, Motion)>| {
        if (p - here).norm() > 1e-12 {
            moves.push((p, m));
            here = p;
        }
    };
    let above = s.position.z.max(retract);
    if s.known[0] && s.known[1] {
        go(
            Vector3::new(s.position.x, s.position.y, above),
            Motion::Rapid,
            &mut moves,
        );
    }
    go(hole.at_xy(above), Motion::Rapid, &mut moves);
    go(hole.at_xy(retract), Motion::Rapid, &mut moves);
    let (mut reached, surface) = (retract, hole.surface);
    let mut pecks = 0.0;
    let bottom_index = loop {
        // The n-th peck's level counted from R, not stepped from the last (six steps of 0.75
        // mm in m from R3 end 2e-19 m above Z-1.5, which would take one more peck); a level
        // within LEVEL_TOLERANCE of the bottom, or a peck too small to change the level, is
        // the bottom, as LinuxCNC's loop (in the program's units) ends there.
        pecks += 1.0;
        let next = hole
            .peck
            .map(|q| retract - pecks * q)
            .filter(|n| *n > depth + LEVEL_TOLERANCE && *n < reached)
            .unwrap_or(depth);
        let from = match reached < retract {
            true => {
                go(hole.at_xy(retract), Motion::Rapid, &mut moves);
                let z = (reached + PECK_CLEARANCE_MM * 1e-3).min(retract);
                go(hole.at_xy(z), Motion::Rapid, &mut moves);
                z
            }
            false => retract,
        };
        // Where the drill meets material: the part's surface, or the depth a peck reached.
        let entry = reached.min(surface);
        if entry < from && entry > next + LEVEL_TOLERANCE {
            go(hole.at_xy(entry), Motion::Feed, &mut moves);
            // The same point again, where the thrust starts: the drill arrives unloaded and
            // cuts from there under its thrust ([`GCode::drilled_in_air`]).
            moves.push((hole.at_xy(entry), Motion::Feed));
        }
        go(hole.at_xy(next), Motion::Feed, &mut moves);
        // The same point again, the thrust gone: the drill stops feeding there, and the exit
        // (the dwell, the rapid out) starts from where it stands unloaded.
        moves.push((hole.at_xy(next), Motion::Rapid));
        reached = next;
        if next <= depth {
            break moves.len() - 1;
        }
    };
    go(hole.at_xy(hole.clearance), Motion::Rapid, &mut moves);
    (moves, bottom_index)
}

/// The hole in `out.cycles` and its moves in `out.points`.
fn push(
    line: u64,
    hole: Hole,
    moves: &[(Vector3<f64>, Motion)],
    bottom_index: usize,
    s: &mut State,
    out: &mut GCode,
) -> Result<()> {
    let index = out.cycles.len();
    let lift = s.lift();
    let tip = |p: &Vector3<f64>| s.tip(line, p, (&s.frame, lift));
    out.cycles.push(super::Cycle {
        line,
        code: hole.code,
        bottom: tip(&hole.at_xy(hole.depth))?,
        retract: hole.retract + hole.shift,
        clearance: hole.clearance + hole.shift,
        dwell: hole.dwell.as_ref().map(|(v, _)| *v),
        peck: hole.peck,
        entry: hole.entry + hole.shift,
    });
    let first = out.points.len();
    let external = super::external_values(line, s)?;
    for (p, m) in moves {
        out.points.push(Point {
            line,
            position: tip(p)?,
            orientation: hole.orientation,
            motion: *m,
            tool_number: s.tool_number,
            operation: s.operation.clone(),
            feed: s.feed,
            cycle: Some(index),
            external: external.clone(),
        });
    }
    if let Some((p, _)) = moves.last() {
        (s.position, s.known) = (*p, [true; 3]);
    }
    if let Some((p, written)) = &hole.dwell {
        super::dwell::at_bottom(line, (*p, written), first + bottom_index, s);
    }
    Ok(())
}
