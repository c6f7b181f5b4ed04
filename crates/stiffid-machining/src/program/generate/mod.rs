//! New robot programs from compensated targets: what a G-code path becomes for a robot controller
//! ([`generate`]), each target moved to at the path's own speed ([`Move`], from the G-code's `F`
//! words: [`moves`]).
//!
//! ## Targets
//! By default ([`Targets::Cartesian`]) every target is the compensated pose expressed in the
//! controller's own nominal kinematics: the forward kinematics of the compensated axis angles,
//! the tool centre point's position and the flange's orientation, with the configuration data
//! of the compensated posture ([`stiffid_core::robot::configuration`]). Cutting moves are linear
//! (KUKA `LIN`, ABB `MoveL`, FANUC `L`): the controller interpolates the tool in a straight line
//! between compensated points, as the G-code does between its points. The first target and rapid
//! moves (`G0`) are joint motions to Cartesian targets with their configuration (`PTP`, `MoveJ`,
//! `J`). With [`Targets::Joint`] every target is the compensated axis angles (`PTP {A1 ..}`,
//! `MoveAbsJ`, positions in joint representation), cutting moves included: the controller
//! interpolates the axes, and the tool leaves the straight line between two targets by the joint
//! interpolation's deviation.
//!
//! ## The tool and the work object
//! Every frame a program states is the controller's ([`stiffid_core::setup::Controller`]): the tool
//! from the controller's flange, an adapter plate (the setup's `[robot_flange]`) included
//! ([`Tool::frame`]), and positions, base and work object in the controller's world, the robot
//! file's base frame, a pedestal (the setup's `[robot_base]`) taken out ([`Plan::world`]).
//! - KUKA KRL (`.src`): `$TOOL` is the tool frame (the TCP with the mounted flange's
//!   orientation), `$LOAD` its mass and centre of mass when the setup gives them, `$BASE` the part
//!   frame (`[workpiece] base_from_part`) in the world; targets in the part frame.
//! - ABB RAPID (`.mod`): `PERS tooldata tspindle` (the tool frame, the mass and centre of mass,
//!   required) and `PERS wobjdata wpart` (the part frame in the world as its user frame); targets
//!   in the part frame.
//! - FANUC LS (`.ls`): positions in user frame 0 (the world) with tool frame 1 (`UT : 1`), which
//!   must hold the tool frame on the controller (an LS program cannot set it); the program states
//!   its values in remarks.
//! - Yaskawa INFORM (`.jbi`): joint targets only, in whole encoder pulses at the setup's
//!   `[controller] pulses_per_deg` (stated in the job's `'stiffid:` comments; refused without
//!   them), Cartesian targets written as their axis angles (`written_targets`); tool file 1
//!   (`///TOOL 1`), whose values the job's comments state ([`super::inform::generate`]).
//!
//! A tool or part frame the controller holds by number (the setup's `[controller] tools` and
//! `bases`) is selected by its number instead ([`numbered`]): KRL `$TOOL = TOOL_DATA[n]`,
//! `$BASE = BASE_DATA[m]`; LS `UTOOL_NUM=n`, `UFRAME_NUM=m`, positions in user frame `m`;
//! INFORM tool file `n`.
//!
//! ## Headers
//! As the controllers write them: KRL `&ACCESS RVP`, `&REL 1`, `&PARAM TEMPLATE`, `&PARAM EDITMASK`
//! before `DEF`; LS the whole `/ATTR` (owner, comment, sizes, dates, line count, protection, task
//! attributes, motion groups, control code); INFORM `///DATE` and `///COMM`. The dates are
//! reproducible: `SOURCE_DATE_EPOCH` (seconds since 1970-01-01 00:00 UTC, the reproducible-builds
//! convention) when the environment sets it, else 1970-01-01. A KRL program's points are in the
//! `.dat` beside it ([`File::data`], `crate::program::krl::data::split`), as KUKA System Software
//! stores a module.
//!
//! ## Controller rules
//! Every rule comes from the controller's manual (docs/reference.md lists the sources):
//! - the program's name is an identifier of the language, not a reserved word, within
//!   [`Settings::name_length`] (default: KRL 24, RAPID 32, LS 8 as on R-30iA controllers; at
//!   most `max_name_length`: KRL 24, RAPID 32, LS 36, INFORM 32);
//!   a generated program is called as its file is named, so the name is the file's stem;
//! - motion is initialised before the first move: KRL `BAS(#INITMOV, 0)`, `$VEL`, `$ACC` and
//!   `$APO`; RAPID `ConfJ \On`, `ConfL \On`; LS `UFRAME_NUM`, `UTOOL_NUM`; INFORM `NOP`;
//! - arcs are circular moves where the compensated arc stays within the chord tolerance of a
//!   circle, else chords with a warning ([`arcs`]);
//! - intermediate cutting points are approximated within the chord tolerance (KRL `C_DIS` with
//!   `$APO.CDIS`, RAPID a `zonedata` of that size, LS `CNT100`; INFORM `PL=1`, the controller's
//!   smallest position level, whose distance its parameters set); the last point is exact (no
//!   approximation, `fine`, `FINE`, `PL=0`), as are the first point and rapid moves;
//! - feeds are written exactly: KRL `$VEL.CP` in m/s and RAPID `v_tcp` in mm/s with 9 decimals,
//!   LS in whole `mm/sec`, else whole `cm/min` (exact for a feed in whole mm/min divisible by 10),
//!   else the nearest whole `cm/min` with a warning, INFORM `V=` in tenths of a mm/s (else the
//!   nearest with a warning); a feed above [`Settings::max_tcp_speed`] or one an LS or INFORM
//!   program cannot state (below 1 cm/min, 0.1 mm/s) is refused naming the G-code line;
//! - the LS `COMMENT` is at most 16 characters, and an LS file at most 9999
//!   numbered lines (the pendant's four digits): its sub-programs hold fewer moves when needed;
//!   an INFORM job at most 100 000 positions (five digits);
//! - no move is faster than [`Settings::max_tcp_speed`], RAPID's rapids (`vrapid`) included;
//!   rapids move at [`Settings::rapid_speed`] (RAPID `vrapid`) and
//!   [`Settings::rapid_joint_pct`] (KRL `BAS(#VEL_PTP)`, LS `J .. %` in whole percents, INFORM
//!   `VJ=` in hundredths), the setup's `[controller] rapid_speed_mm_s` and `rapid_joint_pct`;
//! - joint-target programs move with the real tool too: KRL sets `$TOOL`, `$LOAD` and `$BASE`
//!   whatever the targets, RAPID's `MoveAbsJ` names `tspindle\WObj:=wpart` (RAPID
//!   Instructions: `MoveAbsJ .. Tool [\WObj]`), LS and INFORM use tool frame (file) 1 either way;
//! - the G-code's process words ([`Process`], [`generate_with`]) are written between the
//!   motions where the G-code has them, as the setup's `[controller.io]` maps their events or
//!   as comments with one warning ([`Written::left_out`]); an LS file's numbered lines count
//!   them; the G-code's comments that stand on lines of their own (a CAM post's operation and
//!   tool comments, [`crate::gcode::Comment`]) are written as comments at their place
//!   ([`place_comments`]);
//! - a program of more than [`Settings::moves_per_file`] moves is split into sub-programs of at
//!   most that many moves (`NAME_01`, `NAME_02`, ... in files of their own), which the main
//!   program calls in order.
//!
//! Each program written reads back ([`super::parse`], joint targets) or states its targets to
//! `10^-DECIMALS` mm and deg.

pub mod arcs;
mod checks;
pub mod compensated;
pub mod date;
mod names;
pub mod numbered;
mod process;
mod settings;

pub(crate) use checks::written_targets;
pub(crate) use checks::{check_cell, check_payload, check_pulses, missing_pulses};
pub(crate) use names::check_plan;
pub(crate) use names::max_name_length;
use names::room_for;
pub(crate) use names::LS_MAX_LINES;
pub use names::{check_name, moves_per_file};
pub use process::{after_points, place, place_comments, Process, ProcessForm};
pub use settings::Settings;
pub(crate) use settings::{MIN_FEED, MOVES_PER_FILE, RAPID_PERCENT};

use super::{Dialect, DECIMALS};
use crate::gcode::{Motion, Point};
use nalgebra::{Isometry3, UnitQuaternion, Vector3, Vector6};
#[cfg(doc)]
use stiffid_core::common::error::JobOption;
use stiffid_core::robot::configuration::Configuration;
use stiffid_core::robot::ExternalAxes;
use stiffid_core::setup::Pulses;
use stiffid_core::{Error, Result, Robot};

/// How the robot moves to a target.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Move {
    /// A joint motion at the program's rapid speed: the first target and rapid moves (`G0`).
    Rapid,
    /// A cutting move at the path's feed, m/s.
    Feed(f64),
    /// The start of a circular move taught as a position of its own, at the feed (m/s), in a
    /// language whose circle is three positions (INFORM `MOVC`); the next target is its via
    /// point ([`arcs`]).
    ArcStart(f64),
    /// The via point of a circular move at the feed (m/s): the next target ends it ([`arcs`]).
    ArcVia(f64),
    /// The end of a circular move through the target before ([`Move::ArcVia`]), at the feed,
    /// m/s ([`arcs`]).
    ArcEnd(f64),
}

impl Move {
    /// The feed of a cutting move (linear or circular), m/s; `None` for a rapid move.
    pub(crate) fn feed(self) -> Option<f64> {
        match self {
            Move::Rapid => None,
            Move::Feed(f) | Move::ArcStart(f) | Move::ArcVia(f) | Move::ArcEnd(f) => Some(f),
        }
    }
}

/// What the targets of a generated program are (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Targets {
    /// Compensated poses with their configuration; cutting moves linear.
    #[default]
    Cartesian,
    /// Compensated axis angles, reached by axis-interpolated moves in KRL and RAPID (`PTP`,
    /// `MoveAbsJ`) and linear ones in LS and INFORM (`L`, `MOVL`).
    Joint,
}

impl Targets {
    /// Both, the default first.
    pub const ALL: [Targets; 2] = [Targets::Cartesian, Targets::Joint];

    /// The name in options and documents: `cartesian` or `joint`.
    pub fn name(self) -> &'static str {
        match self {
            Targets::Cartesian => "cartesian",
            Targets::Joint => "joint",
        }
    }
}

impl stiffid_core::common::choice::Choice for Targets {
    const FIELD: &'static str = "targets";
    const ALL: &'static [Self] = &Targets::ALL;
    fn name(self) -> &'static str {
        Targets::name(self)
    }
    fn help(self) -> &'static str {
        match self {
            Targets::Cartesian => {
                "Compensated poses with their configuration, cutting moves linear"
            }
            Targets::Joint => {
                "Compensated axis angles, axis-interpolated in KRL and RAPID, linear in LS and INFORM"
            }
        }
    }
}

stiffid_core::common::choice::by_name!(Targets);

/// One target: the compensated axis angles, the TCP pose they give, their configuration.
#[derive(Debug, Clone, PartialEq)]
pub struct Target {
    /// Axis angles q1..q6, deg.
    pub q_deg: [f64; 6],
    /// The TCP position (m) and the tool's orientation, base frame: the forward kinematics of
    /// the axis angles ([`Target::new`] the flange's axes; a program written for a tool whose
    /// axes are turned, `[tool] tcp_rpy_deg`, turns them the same).
    pub pose: Isometry3<f64>,
    /// The configuration of the axis angles.
    pub arm: Configuration,
    /// The cell's external axes' values at the target, mm for a linear axis and deg for a
    /// rotary one, the cell's order ([`Plan::external`]); empty on a fixed base.
    pub external: Vec<f64>,
}

impl Target {
    /// The target of `robot` at axis angles `q` (rad) with the tool centre point `tcp` (flange
    /// frame, m).
    pub fn new(robot: &Robot, tcp: &Vector3<f64>, q: &Vector6<f64>) -> Self {
        let frames = robot.frames(q);
        Self {
            q_deg: q.map(f64::to_degrees).into(),
            pose: stiffid_core::robot::ik::tool_pose(&frames, tcp),
            arm: Configuration::of(robot, q),
            external: Vec::new(),
        }
    }

    /// The target of `robot` at axis angles `q` (rad) with its external axes at `e` (SI, the
    /// cell's order of [`Robot::external`]): the pose is the tool's in the frame of the part at
    /// `e = 0` (the arm on its carriage at `e`, the positioner turned back: the pose a
    /// controller that coordinates its external axes is told), the values in mm and deg.
    pub fn at(robot: &Robot, tcp: &Vector3<f64>, q: &Vector6<f64>, e: &[f64]) -> Self {
        let Some(axes) = robot.external().filter(|a| !a.is_empty()) else {
            return Self::new(robot, tcp, q);
        };
        let pose = stiffid_core::robot::ik::tool_pose(&robot.frames_at(q, e), tcp);
        Self {
            q_deg: q.map(f64::to_degrees).into(),
            pose: axes.positioner_pose(e).inverse() * pose,
            arm: Configuration::of(robot, q),
            external: axes.to_display(e),
        }
    }
}

/// The tool a program is written for, as the controller holds it: its frame and, if known, its
/// mass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tool {
    /// The tool frame in the controller's flange frame: its origin the tool centre point, its
    /// axes those the targets' orientations are given for (the mounted flange's, after an
    /// adapter plate, turned by `[tool] tcp_rpy_deg`); lengths in m.
    pub frame: Isometry3<f64>,
    /// The mass (kg) and centre of mass (the controller's flange frame, m), if the setup gives
    /// them.
    pub payload: Option<(f64, Vector3<f64>)>,
}

/// What to write.
#[derive(Debug, Clone, Copy)]
pub struct Plan<'a> {
    /// The language.
    pub dialect: Dialect,
    /// The program's name: its file's stem.
    pub name: &'a str,
    /// The targets, in path order.
    pub targets: &'a [Target],
    /// How to move to each target (one per target).
    pub moves: &'a [Move],
    /// The tool.
    pub tool: Tool,
    /// The part frame (the work object) in the frame of the targets' poses (the setup's base
    /// frame).
    pub work: Isometry3<f64>,
    /// The controller's world frame in the frame of the targets' poses (the setup's
    /// `[robot_base]`): what the program's world positions, base and work object are relative to.
    pub world: Isometry3<f64>,
    /// The cell's external axes, which every target gives a value of ([`Target::external`]);
    /// `None` on a fixed base.
    pub external: Option<&'a ExternalAxes>,
    /// The approximation of intermediate cutting points, m (the chord tolerance).
    pub approximation: f64,
    /// The tool and part frame as the controller holds them by number, if it does
    /// ([`numbered`]); `Default`: stated.
    pub numbers: numbered::Numbers,
    /// The controller's axes' encoder pulses (`[controller] pulses_per_deg`), for a language
    /// that writes pulses (INFORM); `None`: not given.
    pub pulses: Option<&'a Pulses>,
    /// How.
    pub settings: Settings,
}

/// One program file.
#[derive(Debug, Clone, PartialEq)]
pub struct File {
    /// The program's name (the file's stem).
    pub name: String,
    /// Its text.
    pub text: String,
    /// A KRL program's `.dat` (its points, `DEFDAT NAME` .. `ENDDAT`), to be written beside it
    /// under its name with `.dat` (`crate::program::krl::data::split`); `None` in another
    /// language.
    pub data: Option<String>,
}

/// The programs written: the main program first, then its sub-programs in call order.
#[derive(Debug, Clone, PartialEq)]
pub struct Written {
    /// The files.
    pub files: Vec<File>,
    /// What the user should know (a feed LS cannot state exactly).
    pub warnings: Vec<String>,
    /// What the program leaves to the user: the process words no `[controller.io]` event maps,
    /// written as comments ([`Process`]).
    pub left_out: Vec<String>,
}

/// How the robot moves to each point of a G-code path: the first point and rapid moves
/// [`Move::Rapid`], cutting moves at the feed in force.
///
/// # Errors
/// [`Error::Program`] naming the line of a cutting move with no feed rate (`F`) in force, or one
/// faster than `max_tcp_speed` (m/s).
pub fn moves(points: &[Point], max_tcp_speed: f64) -> Result<Vec<Move>> {
    let error = |line, message: String| Err(Error::Program { line, message });
    points
        .iter()
        .enumerate()
        .map(|(i, p)| match (i, p.motion, p.feed) {
            (0, _, _) | (_, Motion::Rapid, _) => Ok(Move::Rapid),
            (_, Motion::Feed, Some(f)) if f > max_tcp_speed => error(p.line, format!(
                "a feed of {} mm/s ({} mm/min) is faster than the robot's largest TCP speed, {} mm/s (a setting: max_tcp_speed_mm_s)",
                number(f * 1e3), number(f * 6e4), number(max_tcp_speed * 1e3)
            )),
            (_, Motion::Feed, Some(f)) => Ok(Move::Feed(f)),
            (_, Motion::Feed, None) => error(
                p.line,
                "a cutting move without a feed rate (F) in force: a robot program written from the path moves at its feed".into(),
            ),
        })
        .collect()
}

/// The program of `plan` (module docs), split into sub-programs when it has more moves than
/// [`Settings::moves_per_file`].
///
/// # Errors
/// [`Error::InvalidOption`] for settings outside their limits (option named), a program name the
/// controller does not accept or that leaves no room for the sub-programs' numbers
/// ([`JobOption::ProgramName`]), more than 9999 sub-programs ([`JobOption::MovesPerFile`]);
/// [`Error::InvalidField`] for no target or more than 1 000 000, an axis angle that is not finite
/// (`targets`), a count of moves other than the targets' or a feed below 0.001 mm/s or not finite
/// (`moves`), a RAPID program and a tool without mass (`tool.mass_kg`); [`Error::Program`] for a
/// feed an LS program cannot state (naming the target's 1-based index as its line).
pub fn generate(plan: &Plan) -> Result<Written> {
    generate_with(plan, &Process::default())
}

/// [`generate`] with the G-code's process words written between the moves ([`Process`]);
/// a file's numbered lines (LS) count them.
///
/// # Errors
/// Those of [`generate`]; [`Error::InvalidField`] (`controller.io.KEY`) for an action the
/// language cannot write; [`Error::Program`] naming the G-code line of a word whose action
/// needs a value the program has not given; [`Error::InvalidOption`]
/// ([`JobOption::MovesPerFile`]) for more process lines than a file holds.
pub fn generate_with(plan: &Plan, process: &Process) -> Result<Written> {
    let generator = names::generator(plan.dialect)?;
    let form = generator
        .process_form()
        .ok_or_else(|| invalid("out", "this language writes no process instruction".into()))?;
    let (inserted, left_out) = process::inserted(plan, form, process)?;
    let settings = room_for(generator, &plan.settings, &inserted)?;
    let names = check_plan(plan.dialect, plan.name, &settings, plan.targets.len())?;
    let date = date::Stamp::at(settings.date_s);
    check_targets(plan)?;
    generator.check_settings(&plan.settings)?;
    let per_file = moves_per_file(plan.dialect, &settings);
    let files = arcs::files(plan.moves, per_file);
    let chunks: Vec<&[Target]> = files.iter().map(|r| &plan.targets[r.clone()]).collect();
    // A file ends before a circular move it cannot hold whole: one more file, maybe.
    let names = match chunks.len() > 1 && names.len() != chunks.len() + 1 {
        true => check_plan(plan.dialect, plan.name, &settings, chunks.len() * per_file)?,
        false => names,
    };
    let mut written = Written {
        files: Vec::new(),
        warnings: Vec::new(),
        left_out: left_out.into_iter().collect(),
    };
    let mut first = 0;
    let mut bodies = Vec::new();
    for (chunk, name) in chunks
        .iter()
        .zip(names.iter().skip(usize::from(chunks.len() > 1)))
    {
        let part = Part {
            first,
            targets: chunk,
            moves: &plan.moves[first..first + chunk.len()],
            last: first + chunk.len() == plan.targets.len(),
            inserted: &inserted,
        };
        bodies.push((
            name.clone(),
            generator.body(plan, &part, &mut written.warnings)?,
        ));
        first += chunk.len();
    }
    let header = generator.header(plan, &names[0], &names[1..]);
    if chunks.len() == 1 {
        let (name, text) = bodies.pop().unwrap_or_default();
        written.files.push(File {
            text: generator.wrap(&name, &header, &text, true, date),
            name,
            data: None,
        });
    } else {
        let calls = generator.calls(&names[1..]);
        written.files.push(File {
            name: names[0].clone(),
            text: generator.wrap(&names[0], &header, &calls, true, date),
            data: None,
        });
        for (name, text) in bodies {
            written.files.push(File {
                text: generator.wrap(&name, "", &text, false, date),
                name,
                data: None,
            });
        }
    }
    for f in &mut written.files {
        // A language that stores its points beside the program (KRL's `.dat`).
        if let Some((text, data)) = generator.data_file(&f.name, &f.text) {
            (f.text, f.data) = (text, Some(data));
        }
    }
    Ok(written)
}

/// A run of targets written into one file.
#[derive(Debug, Clone, Copy)]
pub struct Part<'a> {
    /// The 0-based index of its first target in the whole program.
    pub first: usize,
    /// Its targets.
    pub targets: &'a [Target],
    /// How to move to each of its targets.
    pub moves: &'a [Move],
    /// Whether it ends the whole program (its last point exact).
    pub last: bool,
    /// The lines written before each target of the whole program, then after its last
    /// ([`Process`]); empty: none.
    pub inserted: &'a [String],
}

impl Part<'_> {
    /// The lines written before its `k`-th target (0-based within the part).
    pub(crate) fn before(&self, k: usize) -> &str {
        self.inserted.get(self.first + k).map_or("", String::as_str)
    }

    /// The lines written after its last target: the program's end's, for the last part.
    pub(crate) fn after(&self) -> &str {
        let end = self.first + self.targets.len();
        match self.last {
            true => self.inserted.get(end).map_or("", String::as_str),
            false => "",
        }
    }
}

pub(super) fn invalid(field: &str, message: String) -> Error {
    Error::InvalidField {
        field: field.into(),
        message,
    }
}

fn check_targets(plan: &Plan) -> Result<()> {
    let t = plan.targets;
    if t.is_empty()
        || t.len() > super::MAX_TARGETS
        || t.iter().flat_map(|t| t.q_deg).any(|v| !v.is_finite())
    {
        return Err(invalid(
            "targets",
            format!(
                "expected 1 to {} targets of 6 finite axis angles",
                super::MAX_TARGETS
            ),
        ));
    }
    let bad_feed = plan
        .moves
        .iter()
        .any(|m| m.feed().is_some_and(|f| !(f.is_finite() && f >= MIN_FEED)));
    if plan.moves.len() != t.len() || bad_feed {
        return Err(invalid(
            "moves",
            format!(
                "expected one move per target ({}), each feed finite and at least {} mm/s",
                t.len(),
                MIN_FEED * 1e3
            ),
        ));
    }
    let form = (names::generator(plan.dialect)?).circular(plan.settings.targets);
    if !arcs::whole(plan.moves, form) {
        return Err(invalid("moves", match form {
            Some(_) => "expected every circular move whole: its start (INFORM), its via point, then its end".into(),
            None => format!("a {} program with {} targets writes no circular move", plan.dialect.controller().key().to_ascii_uppercase(), plan.settings.targets.name()),
        }));
    }
    check_external(plan)?;
    check_payload(plan.dialect, plan.settings.targets, &plan.tool)?;
    check_pulses(plan.dialect, plan.pulses)
}

/// Every target's external values against the cell's axes and what the language holds.
fn check_external(plan: &Plan) -> Result<()> {
    let n = plan.external.map_or(0, ExternalAxes::len);
    let bad = (plan.targets.iter())
        .any(|t| t.external.len() != n || t.external.iter().any(|v| !v.is_finite()));
    if bad {
        return Err(invalid(
            "targets",
            format!("expected {n} finite external axis values in every target, one per axis of the cell"),
        ));
    }
    check_cell(plan.dialect, plan.settings.targets, plan.external)
}

/// A feed (m/s) as a language states it in its own units: `speed` gives the text and whether it
/// is exact (`None` below the slowest it states, `slowest`), a rounded feed adds a warning (once)
/// that it has no `units`; `line` is the target's 1-based index in the program.
///
/// # Errors
/// [`Error::Program`] at `line` for a feed below the slowest.
pub(crate) fn stated_feed(
    feed: f64,
    line: usize,
    speed: fn(f64) -> Option<(String, bool)>,
    (slowest, units): (&str, &str),
    warnings: &mut Vec<String>,
) -> Result<String> {
    let (text, exact) = speed(feed).ok_or_else(|| Error::Program {
        line: line as u64,
        message: format!("a feed of {} mm/min is below {slowest}", number(feed * 6e4)),
    })?;
    let w = format!(
        "a feed of {} mm/min has no {units}: written as {text}",
        number(feed * 6e4)
    );
    if !exact && !warnings.contains(&w) {
        warnings.push(w);
    }
    Ok(text)
}

/// `x` with [`DECIMALS`] decimals, a negative zero without its sign.
pub(crate) fn v(x: f64) -> String {
    let s = format!("{x:.DECIMALS$}");
    match s.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => s,
    }
}

/// A number as short as it is exact to [`DECIMALS`] decimals (trailing zeros dropped).
pub(crate) fn number(x: f64) -> String {
    let s = v(x);
    match s.contains('.') {
        true => s.trim_end_matches('0').trim_end_matches('.').to_string(),
        false => s,
    }
}

/// A target's pose in the frame `work` (part frame): position (mm) and rotation.
pub(crate) fn in_work(plan: &Plan, t: &Target) -> (Vector3<f64>, UnitQuaternion<f64>) {
    let local = plan.work.inverse() * t.pose;
    (local.translation.vector * 1e3, local.rotation)
}

/// A pose (the frame of the targets' poses) in the controller's world: position (mm) and
/// rotation.
pub(crate) fn in_world(plan: &Plan, pose: &Isometry3<f64>) -> (Vector3<f64>, UnitQuaternion<f64>) {
    let local = plan.world.inverse() * pose;
    (local.translation.vector * 1e3, local.rotation)
}

/// KUKA's A, B, C and FANUC's R, P, W (deg): `R = Rz(A) Ry(B) Rx(C)`.
pub(crate) fn zyx_deg(r: &UnitQuaternion<f64>) -> [f64; 3] {
    let [roll, pitch, yaw] = stiffid_core::robot::file::rpy(r);
    [yaw.to_degrees(), pitch.to_degrees(), roll.to_degrees()]
}

#[cfg(test)]
mod date_tests;

#[cfg(test)]
mod arcs_tests;
