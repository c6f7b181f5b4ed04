//! Robot programs: the joint targets of KUKA KRL, ABB RAPID, FANUC LS and Yaskawa INFORM
//! programs and the Cartesian targets of KRL, RAPID and LS ones ([`cartesian`]), read in the
//! order the controller moves to them and written back with everything else byte for byte.
//!
//! - [`krl`]: `PTP`/`LIN` (and `SPTP`/`SLIN`, `CIRC`/`SCIRC`) motions to an aggregate
//!   `{A1 .., ..., A6 ..}` or to a point declared in the `.src` or the `.dat` beside it
//!   ([`parse_with_data`]) as `E6AXIS`/`AXIS`, with its external axes `E1`..`E6`; the inline
//!   forms' frames by number.
//! - [`rapid`]: `MoveAbsJ` (also `\Conc`) to a literal `[[j1,..,j6],[e1,..,e6]]` or to a
//!   `jointtarget` declared in the same module (over one line or several), with its external axes
//!   `eax_a`..`eax_f` (`9E9`: not used).
//! - [`ls`]: `J`/`L` motions and `C` motions (the via point and the end, two targets) in `/MN`
//!   to `P[i]` positions of `/POS` in joint representation (`J1= .. deg` to `J6`, group 1's
//!   extended axes `E1`.. and a second group `GP2`); `INC` after a motion that ends `FINE` is
//!   resolved (the increment from the previous target, written back as the increment between the
//!   compensated targets); the instructions around the motions passed over where they cannot
//!   change the path or the frames, refused naming the line where they can.
//! - [`inform`]: `MOVJ`/`MOVL`/`MOVC` to `C` teaching positions in pulses, with base (`BC`) and
//!   station (`EC`) positions; the pulses per degree from the setup ([`Context`]) or a
//!   `'stiffid:` comment of the job.
//!
//! Each language is a folder ([`krl`], [`rapid`], [`ls`], [`inform`]: its reader, its Cartesian
//! targets and configuration data, its program writer and its names) implementing
//! [`Controller`], what a controller language does (its [`Descriptor`] and a few methods); the
//! registry of [`Dialect`] (one line per language) is the one place a dialect maps to its
//! folder, and
//! everything else here (the targets and their writing back, [`speed`], [`cartesian`]'s solve,
//! [`external`], [`rename`], [`generate`]'s shared part) asks the trait.
//!
//! A target's external axes are the cell's in the cell's order ([`external`]).
//!
//! Cartesian targets (KRL `E6POS`/`POS`/`FRAME` aggregates and points, RAPID `MoveL`/`MoveJ` to
//! `robtarget`s, LS positions in Cartesian representation) are read with their frame, tool and
//! configuration data ([`cartesian`]); their axis angles are NaN until [`cartesian::resolve`]
//! gives the ones the controller moves to (inverse kinematics in the configuration the data
//! name). A program may mix both kinds. A compensated Cartesian target is written back as the
//! pose the controller must be told, with the configuration data of the compensated posture.
//!
//! RAPID's `MoveC` is read as its circle point and end point, and `Offs`/`RelTool` of a point with
//! constant arguments as the pose they land on ([`rapid`]).
//!
//! Every other motion instruction is refused naming its line and what to do, never skipped: a
//! circular or spline motion (the path between the points is not the compensated one; LS `C`
//! aside, whose via point and end are both targets), a relative
//! motion the file cannot resolve exactly, an offset or target held in a register on the
//! controller (LS `Offset`, `Tool_Offset` by a condition, a `PR[]` the program sets or without
//! the backup's `POSREG.VA`), a point declared outside the file or
//! assigned at run time (unless the backup's files, [`Context::backup`], declare it), a search
//! or triggered motion (RAPID `SearchL`, `TriggL`, `MoveLDO`). KRL and RAPID read a motion inside
//! a loop or branch, or in another routine of the file, where it is (what it moves with followed
//! along every path, `paths`); LS and INFORM follow their labels, jumps, branches and loops
//! the same way (LS over its order of run, [`ls`]) and refuse a call of a program that may move
//! between two motions.
//!
//! The targets come in the order of the motion instructions, which is the order the path follows; a
//! declared point moved to twice is one target per visit. [`JointProgram::write`] replaces the six
//! numbers (a Cartesian target: its pose's numbers and, where they changed, its configuration data)
//! of each target whose value changed (with 9 decimals, INFORM in whole pulses) and nothing else
//! ([`JointProgram::write_with_external`] the external values too); a declared point visited by
//! motions whose compensations differ is written as several points, each other value declared
//! beside the first under a free name (where the reader does not say where the point
//! is declared, the visits must agree).
//!
//! Statements that set what the motions use (frames, tools, speeds) are followed through
//! branches and loops along every path (`paths`); with [`Context::leave_refused`], a motion
//! refused for what only the run decides is left as found, not compensated, and named in
//! [`JointProgram::left`]; the controller backup's files given with a program
//! ([`Context::backup`]) hold the data it declares elsewhere.

mod arithmetic;
pub mod cartesian;
mod controller;
mod descriptor;
mod ends;
pub mod external;
mod files;
pub mod generate;
pub mod inform;
pub mod krl;
pub mod ls;
pub(crate) mod paths;
mod points;
pub mod rapid;
pub mod rename;
pub mod speed;
mod write;
pub use files::{data_out, read_backup, read_files};
pub use write::Written;

pub(crate) use super::text::lines;
pub(crate) use super::text::number_at;
pub use controller::{
    Arcs, AxisNames, BoundComment, Controller, Descriptor, DynController, ExternalGroup, FileName,
    Generator, NameRules, Read, Writing,
};
use nalgebra::{Isometry3, Translation3};
use std::ops::Range;
use stiffid_core::setup::{NumberedFrames, Pulses};
use stiffid_core::{Error, Result, Setup};

/// Decimals of a written joint value, deg (1e-9 deg: the compensation's precision; controllers
/// round to their own).
pub(crate) const DECIMALS: usize = 9;

/// The most joint targets a program may hold.
pub(crate) const MAX_TARGETS: usize = 1_000_000;

/// The registry: each controller language's variant of [`Dialect`], its doc line and its
/// controller (a unit struct of its folder implementing [`Controller`]). A new language adds
/// its folder and one line here.
macro_rules! registry {
    ($($(#[doc = $doc:expr])* $variant:ident => $controller:expr,)*) => {
        /// The robot-program language.
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        pub enum Dialect {
            $($(#[doc = $doc])* $variant,)*
        }

        impl Dialect {
            /// Every dialect, in the order options and messages list them.
            pub const ALL: [Dialect; [$(stringify!($variant)),*].len()] = [$(Dialect::$variant),*];

            /// The controller language that reads and writes the dialect: the one place a
            /// dialect maps to its code.
            pub fn controller(self) -> &'static dyn DynController {
                match self {
                    $(Dialect::$variant => &$controller,)*
                }
            }
        }
    };
}

registry! {
    /// KUKA KRL (`.src`, `.dat`).
    Krl => krl::Krl,
    /// ABB RAPID (`.mod`, `.modx`, `.prg`).
    Rapid => rapid::Rapid,
    /// FANUC LS (`.ls`), joint representation.
    FanucLs => ls::FanucLs,
    /// Yaskawa INFORM (`.jbi`), pulse positions.
    Inform => inform::Inform,
}

impl Dialect {
    /// The dialect of a file name's extension (case-insensitive), if it is one of ours.
    pub(crate) fn from_extension(extension: &str) -> Option<Self> {
        let extension = extension.to_ascii_lowercase();
        (Dialect::ALL.into_iter())
            .find(|d| d.controller().extensions().contains(&extension.as_str()))
    }
}

/// One joint target of a program: one motion instruction's destination.
#[derive(Debug, Clone, PartialEq)]
pub struct JointTarget {
    /// The line of its motion instruction, 1-based.
    pub line: u64,
    /// Axis angles q1..q6, deg (an incremental target resolved to its absolute angles; a
    /// Cartesian target's NaN until [`cartesian::resolve`]).
    pub q_deg: [f64; 6],
    /// The external axes' values as the program gives them, one per axis of
    /// [`JointProgram::axes`], mm for a linear axis and deg for a rotary one (as the controller
    /// writes them); `None` where the target gives no value (RAPID `9E9`, an `E` member the KRL
    /// aggregate leaves out).
    pub external: Vec<Option<f64>>,
    /// Where each of the six numbers sits in the text (bytes): in the motion or in the point's
    /// declaration.
    spans: [Range<usize>; 6],
    /// Where each external value sits in the text, as `external`.
    external_spans: Vec<Option<Range<usize>>>,
    /// The line of the six numbers (the declaration's for a named point).
    origin: u64,
    /// The numbers hold the increment from the previous target (LS `INC`).
    incremental: bool,
    /// A Cartesian target's pose, frame and configuration data ([`cartesian`]): its
    /// [`JointTarget::q_deg`] are NaN until [`cartesian::resolve`] gives them.
    pub cartesian: Option<Box<cartesian::Cartesian>>,
    /// How the controller moves to it: a joint motion, or a linear one at its programmed
    /// speed ([`speed`]).
    pub speed: speed::Speed,
    /// A point the controller holds, not the file (KRL's `XHOME`, from the setup's
    /// `[controller] home_deg`): compensated as every target, never written back.
    held: bool,
    /// The via point of a circular motion (KRL `CIRC`, RAPID `MoveC`, LS `C`): the next target
    /// is its end, the target before its start.
    pub(crate) via: bool,
    /// A declared point's declaration and name there, and where the motion names it
    /// ([`points`]): where a second point is declared when two visits' compensations differ.
    point: Option<Box<points::Point>>,
    /// Where its motion is in the whole text, when its numbers are in another file's text (a
    /// RAPID procedure's parameter bound to its caller's target): the file it is a motion of
    /// ([`JointProgram::called_in`]).
    motion_at: Option<usize>,
}

impl JointTarget {
    /// The same point as the target of the motion on `line`; `incremental` as it says.
    pub(crate) fn moved_to(&self, line: u64, incremental: bool) -> Self {
        JointTarget {
            line,
            incremental,
            ..self.clone()
        }
    }

    /// The target declared by the statement at `declaration` (bytes of the text, whole lines)
    /// whose name there is at `name`.
    pub(crate) fn declared_at(mut self, declaration: Range<usize>, name: Range<usize>) -> Self {
        self.point = Some(Box::new(points::Point {
            declaration,
            name,
            reference: None,
            foreign: None,
        }));
        self
    }

    /// The target as declared in another file of the controller (`foreign`: its declaration,
    /// as the program declares its copy, and the name's bytes in it), the program's copy going
    /// at byte `insert` of the program's text ([`points::Foreign`]).
    pub(crate) fn declared_elsewhere(
        mut self,
        foreign: points::Foreign,
        name: Range<usize>,
        insert: usize,
    ) -> Self {
        self.point = Some(Box::new(points::Point {
            declaration: insert..insert,
            name,
            reference: None,
            foreign: Some(Box::new(foreign)),
        }));
        self
    }

    /// The declared target named at `reference` (bytes of the text) by its motion.
    pub(crate) fn named_at(mut self, reference: Range<usize>) -> Self {
        if let Some(p) = self.point.as_deref_mut() {
            p.reference = Some(reference);
        }
        self
    }

    /// Whether the controller holds the point, not the file (KRL's `XHOME`): it is never
    /// written back, so its compensation is not applied.
    pub fn is_held(&self) -> bool {
        self.held
    }

    /// A Cartesian target on `line` (its axis angles NaN until resolved).
    pub(crate) fn cartesian(line: u64, c: cartesian::Cartesian) -> Self {
        JointTarget {
            line,
            q_deg: [f64::NAN; 6],
            external: Vec::new(),
            spans: Default::default(),
            external_spans: Vec::new(),
            origin: line,
            incremental: false,
            cartesian: Some(Box::new(c)),
            speed: speed::Speed::Unread(NOT_READ.into()),
            held: false,
            via: false,
            point: None,
            motion_at: None,
        }
    }

    /// The target with the external values `values` (value and span, in the dialect's slots).
    pub(crate) fn with_external(mut self, values: Vec<Option<(f64, Range<usize>)>>) -> Self {
        (self.external, self.external_spans) = values
            .into_iter()
            .map(|v| match v {
                Some((v, s)) => (Some(v), Some(s)),
                None => (None, None),
            })
            .unzip();
        self
    }
}

/// A robot program and its joint targets.
#[derive(Debug, Clone, PartialEq)]
pub struct JointProgram {
    /// The language.
    pub dialect: Dialect,
    /// The targets, in the order of the motion instructions.
    pub targets: Vec<JointTarget>,
    /// The program's external axes as it names them (KRL `E1`.., RAPID `eax_a`.., LS `E1`.. of
    /// group 1 then `GP2 J1`.., INFORM `BC1`.. then `EC1`..), in the order of
    /// [`JointTarget::external`]: the `n` first are the cell's `n` external axes, in the cell's
    /// order ([`external`]).
    pub axes: Vec<String>,
    /// Per value (the six axes, then the external ones): the pulses per deg or mm of a value
    /// written in pulses (INFORM), `None` for a decimal value.
    pulses: Vec<Option<f64>>,
    /// Per external axis, the unit the program writes it in and the line of its first value,
    /// where the language says (LS: `mm` or `deg`); empty for the others.
    units: Units,
    /// What writes the Cartesian targets back, once resolved ([`cartesian::resolve`]).
    writer: Option<Box<cartesian::Writer>>,
    /// The program's text, then its data file's when one was read (KRL's `.dat`).
    text: String,
    /// Where the data file's text begins in `text`, when one was read.
    data_at: Option<usize>,
    /// The motions left as found ([`Context::leave_refused`]), in the order of their lines.
    pub left: Vec<Left>,
    /// The programs of the controller's backup it calls that move, each compensated in place in
    /// its own file: the file's name as given and where its text begins in `text` (after the
    /// program's and its data file's).
    called: Vec<(String, usize)>,
    /// What reading the program on its setup found the user should know (a frame taught in the
    /// nominal cell, [`cartesian::resolve`]), one sentence each.
    pub notes: Vec<String>,
    /// The positions the reader copied into the program from the controller's backup (an LS
    /// motion to a position register, read from `POSREG.VA`), one sentence each naming the line.
    pub copied: Vec<String>,
    /// Per target, the axis angles read where [`JointTarget::q_deg`] holds others (joint
    /// targets computed by a nominal controller, [`cartesian::computed`]); empty: as read.
    read_deg: Vec<[f64; 6]>,
}

/// What the setup says of a program that the program itself does not: the controller's
/// encoder pulses (an INFORM job's positions) and the tool files it holds by number, which a
/// reader checks against the setup's tool ([`inform`]); the data file beside it (KRL's `.dat`);
/// a G-code program's controller ([`crate::gcode::Machine`]). The default says nothing: a program
/// read on its own.
#[derive(Debug, Clone, Copy, Default)]
pub struct Context<'a> {
    /// The controller's pulses per degree or mm of each axis (`[controller] pulses_per_deg`,
    /// `external_pulses`).
    pub pulses: Option<&'a Pulses>,
    /// The setup's tool in the controller's flange frame (`[tool] tcp_mm` after
    /// `[robot_flange]`), m, and the tools the controller holds by number (`[controller]
    /// tools`, in its flange frame).
    pub tool: Option<(Isometry3<f64>, &'a NumberedFrames)>,
    /// The bases (user frames) the controller holds by number, in its world frame (`[controller]
    /// bases`), against which a backup's own tables are checked.
    pub bases: Option<&'a NumberedFrames>,
    /// The data file beside the program (KRL's `.dat`: its points and frame data), whose
    /// targets there are written back into it (`JointProgram::write_pair`).
    pub data: Option<&'a str>,
    /// A G-code program's controller: its work offsets, start and home positions and tool
    /// lengths ([`crate::gcode::Machine::of`]); `None`: none of them known.
    pub machine: Option<&'a crate::gcode::Machine>,
    /// The controller's home posture, deg (`[controller] home_deg`), where the language reads
    /// it (a KRL program's `PTP XHOME` passes through whatever it says); `None`: not known.
    pub home_deg: Option<[f64; 6]>,
    /// The files of the controller's backup given with the program (a front end reads them;
    /// the library lists no folder): each file's name as given (its last component names it:
    /// FANUC `SYSFRAME.VA`, Yaskawa `TOOL.CND`, KRL `$config.dat`, a RAPID module `BASE.sys`)
    /// and its text. Each language reads the
    /// files it knows (`Context::backup_file`, `Context::backup_with`); empty: none given.
    pub backup: &'a [(String, String)],
    /// Leave as found the motions refused for what only the run decides (paths that set
    /// different frames, a value assigned at run time): each is then not compensated, written
    /// back as read, and named in [`JointProgram::left`] instead of refusing the program.
    pub leave_refused: bool,
    /// Which of the controller's robots the setup's robot is (`[controller] robot_number`, a
    /// Yaskawa job's `RB2`: 2); `None`: the first.
    pub robot_number: Option<u32>,
    /// The process's input and output routines (`[controller.io]`): a call of one of them (a
    /// KRL `SPINDLE_ON(5000)`) moves nothing; `None`: none given.
    pub io: Option<&'a stiffid_core::setup::program_io::Io>,
}

/// How a robot program is read beyond its own files (by default: nothing more), as a job takes
/// it from a front end ([`Context::with_reading`]).
#[derive(Debug, Clone, Copy, Default)]
pub struct Reading<'a> {
    /// The files of the controller's backup given with the program, each its name and text (a
    /// front end lists a folder with [`stiffid_core::io::input::files_under`],
    /// [`read_backup`]): [`Context::backup`].
    pub backup: &'a [(String, String)],
    /// Leave as found the motions refused for what only the run decides, each named in a
    /// warning: [`Context::leave_refused`].
    pub leave_refused: bool,
}

/// A motion left as found ([`Context::leave_refused`]): its line and why it was not compensated.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Left {
    /// The motion's line, 1-based.
    pub line: u64,
    /// Why it is not compensated (the refusal it would have been).
    pub why: String,
    /// The declared point it moves to, whose declaration its compensated visits leave as read.
    pub(crate) point: Option<points::Point>,
}

impl Left {
    /// The motion on `line` passed through as found, for the reason `why` (a motion to the home
    /// position).
    pub(crate) fn passed(line: u64, why: String) -> Self {
        Left {
            line,
            why,
            point: None,
        }
    }

    /// The motion of `target` left as found, for the reason `why`.
    pub(crate) fn of(target: &JointTarget, why: String) -> Self {
        Left {
            line: target.line,
            why,
            point: target.point.as_deref().cloned(),
        }
    }
}

impl<'a> Context<'a> {
    /// What `setup` says of its programs.
    pub fn of(setup: &'a Setup) -> Self {
        let c = setup.workcell().controller();
        Context {
            pulses: c.pulses.as_ref(),
            tool: Some((c.adapter * Translation3::from(setup.tool().tcp), &c.tools)),
            bases: Some(&c.bases),
            data: None,
            machine: None,
            home_deg: c.program.home_deg,
            backup: &[],
            leave_refused: false,
            robot_number: c.robot_number,
            io: Some(&c.program.io),
        }
    }

    /// The context with the controller backup's files `backup` (name and text).
    pub fn with_backup(self, backup: &'a [(String, String)]) -> Self {
        Context { backup, ..self }
    }

    /// The backup's file named `file` (its last path component, case-insensitive): its name as
    /// given and its text.
    pub(crate) fn backup_file(&self, file: &str) -> Option<(&'a str, &'a str)> {
        self.backup_with(|name| name.eq_ignore_ascii_case(file))
            .into_iter()
            .next()
    }

    /// The backup's files whose name (last path component) `wanted` takes, in the order given.
    pub(crate) fn backup_with(&self, wanted: impl Fn(&str) -> bool) -> Vec<(&'a str, &'a str)> {
        let backup: &'a [(String, String)] = self.backup;
        (backup.iter())
            .filter(|(name, _)| wanted(file_name(name)))
            .map(|(n, t)| (n.as_str(), t.as_str()))
            .collect()
    }

    /// The context with the G-code controller `machine`.
    pub fn with_machine(self, machine: &'a crate::gcode::Machine) -> Self {
        Context {
            machine: Some(machine),
            ..self
        }
    }

    /// The context with the data file `data` beside the program (KRL's `.dat`).
    pub fn with_data(self, data: Option<&'a str>) -> Self {
        Context { data, ..self }
    }

    /// The context with what `reading` gives: the backup's files and whether refused motions
    /// are left as found.
    pub fn with_reading(self, reading: Reading<'a>) -> Self {
        Context {
            backup: reading.backup,
            leave_refused: reading.leave_refused,
            ..self
        }
    }

    /// The context that leaves refused motions as found (`leave`, [`Context::leave_refused`]).
    pub fn with_leave_refused(self, leave: bool) -> Self {
        Context {
            leave_refused: leave,
            ..self
        }
    }

    /// The refusal `error` of a motion (an [`Error::Program`] naming its line) as a motion left
    /// as found in `left` when [`Context::leave_refused`]; else the error.
    ///
    /// # Errors
    /// `error`, unless it is a program's error and the context leaves refused motions.
    pub(crate) fn leave(&self, left: &mut Vec<Left>, error: Error) -> Result<()> {
        match error {
            Error::Program { line, message } if self.leave_refused => {
                left.push(Left {
                    line,
                    why: message,
                    point: None,
                });
                Ok(())
            }
            other => Err(other),
        }
    }
}

/// The last component of a file's name as given (`a/b/$config.dat`: `$config.dat`).
pub(crate) fn file_name(name: &str) -> &str {
    name.rsplit(['/', '\\']).next().unwrap_or(name)
}

/// Parses the joint targets of `text` in `dialect`, read on its own ([`parse_in`] with the
/// default [`Context`]).
///
/// # Errors
/// Those of [`parse_in`].
pub fn parse(text: &str, dialect: Dialect) -> Result<JointProgram> {
    parse_in(text, dialect, &Context::default())
}

/// [`parse`] of a program with the data file beside it (KRL's `.dat`: its points, frame data),
/// whose targets there are written back into it (`JointProgram::write_pair`).
///
/// # Errors
/// Those of [`parse_in`]; a motion to a point neither file declares, naming its line.
pub fn parse_with_data(text: &str, data: Option<&str>, dialect: Dialect) -> Result<JointProgram> {
    parse_in(text, dialect, &Context::default().with_data(data))
}

/// Parses the joint targets of `text` in `dialect` with what the setup says in `context`.
///
/// # Errors
/// [`Error::Program`] naming the line: every motion instruction outside the subset (module docs), a
/// joint target with a missing, repeated or non-numeric axis value, a Cartesian target with a
/// missing or malformed member or configuration data ([`cartesian`]), no motion to a target at all,
/// or more than 1 000 000; a program (or a KRL program's `.dat`) cut off before its closing word
/// or whose lines end with a lone CR (`ends`).
pub fn parse_in(text: &str, dialect: Dialect, context: &Context) -> Result<JointProgram> {
    ends::check(text, dialect)?;
    // The data file the backup holds, where none is given beside the program.
    let data = (context.data).or_else(|| dialect.controller().data_file(text, context));
    if let Some(d) = data {
        ends::check_data(d, "the program's .dat", dialect)?;
    }
    let context = &Context { data, ..*context };
    let Read {
        mut targets,
        axes,
        pulses,
        units,
        mut left,
        called,
        notes,
    } = dialect.controller().read_in(text, context)?;
    left.sort_by_key(|l| l.line);
    for t in &mut targets {
        t.external.resize(axes.len(), None);
        t.external_spans.resize(axes.len(), None);
    }
    if let (true, Some(first)) = (targets.is_empty(), left.first()) {
        let listed: Vec<String> = (left.iter().take(5))
            .map(|l| format!("line {}: {}", l.line, l.why))
            .collect();
        return Err(at(
            first.line,
            format!(
                "no motion to compensate: each motion passes through or is left as found ({}{})",
                listed.join("; "),
                if left.len() > 5 { "; .." } else { "" }
            ),
        ));
    }
    if targets.is_empty() {
        let hint = dialect.controller().motions();
        return Err(at(
            1,
            format!("no motion to a target found (expected {hint}); a program that only calls others (the main program of a split one) moves in those: give each of them"),
        ));
    }
    if targets.len() > MAX_TARGETS {
        return Err(at(
            targets[MAX_TARGETS].line,
            format!("more than {MAX_TARGETS} joint targets"),
        ));
    }
    let mut all = [text, context.data.unwrap_or("")].concat();
    let mut starts = Vec::with_capacity(called.len());
    for (name, t) in called {
        starts.push((name, all.len()));
        all.push_str(&t);
    }
    Ok(JointProgram {
        dialect,
        targets,
        axes,
        pulses,
        units,
        writer: None,
        text: all,
        data_at: context.data.map(|_| text.len()),
        left,
        called: starts,
        notes: Vec::new(),
        copied: notes,
        read_deg: Vec::new(),
    })
}

/// Per external axis of a program (its order), the unit its values are written in (`mm` or
/// `deg`) and the line of the first, where the language says (LS).
pub(crate) type Units = Vec<Option<(&'static str, u64)>>;

/// A value (deg or mm) as the nearest whole number of pulses at `per_unit` pulses per unit
/// (INFORM's pulse form): exact to half a pulse.
pub fn whole_pulses(value: f64, per_unit: f64) -> i64 {
    (value * per_unit).round() as i64
}

/// The error at `line`.
pub(crate) fn at(line: u64, message: String) -> Error {
    Error::Program { line, message }
}

/// The six axis values of a target as found so far: value and span.
pub(crate) type Found = [Option<(f64, Range<usize>)>; 6];

/// Six axis values collected by name (`A1`.., `J1`..): the target, or what is missing.
pub(crate) fn six(
    line: u64,
    found: [Option<(f64, Range<usize>)>; 6],
    names: &str,
) -> Result<JointTarget> {
    let mut q_deg = [0.0; 6];
    let mut spans: [Range<usize>; 6] = Default::default();
    for (k, f) in found.into_iter().enumerate() {
        let (v, s) = f.ok_or_else(|| {
            at(
                line,
                format!("joint target without axis {} ({names}{})", k + 1, k + 1),
            )
        })?;
        if !v.is_finite() {
            return Err(at(
                line,
                format!(
                    "axis {} ({names}{}): {v} is not a finite angle",
                    k + 1,
                    k + 1
                ),
            ));
        }
        q_deg[k] = v;
        spans[k] = s;
    }
    Ok(JointTarget {
        line,
        q_deg,
        external: Vec::new(),
        spans,
        external_spans: Vec::new(),
        origin: line,
        incremental: false,
        cartesian: None,
        speed: speed::Speed::Unread(NOT_READ.into()),
        held: false,
        via: false,
        point: None,
        motion_at: None,
    })
}

/// A target's speed before its motion instruction gives it.
const NOT_READ: &str = "the motion's speed is not read";

#[cfg(test)]
mod speed_tests;

#[cfg(test)]
mod write_tests;
