//! What a controller language does, in one trait: [`Controller`] (what the language is as data,
//! a [`Descriptor`]: its names, files, forms, names' rules and bound comments; its configuration
//! data's type; read a program's targets and speeds, state its Cartesian targets' poses) and, for
//! a language stiffid writes new programs in, [`Generator`] (the header with the tool and the
//! frames, the moves, the sub-program calls). [`DynController`] is a `Controller` as the
//! registry holds it, its configuration data without their type.
//!
//! Each language implements them in its own folder ([`super::krl`], [`super::rapid`],
//! [`super::ls`], [`super::inform`]); the registry of [`super::Dialect`] is the one place that
//! maps a dialect to its controller. Everything else (the targets and their writing back, the speeds,
//! the Cartesian solve, the names' checks, the bounds' comments) is shared and asks the trait.

use super::cartesian::flags::{ConfigurationData, Flags};
pub use super::descriptor::{
    Arcs, AxisNames, Descriptor, ExternalGroup, FileName, NameRules, Writing,
};
use super::generate::date::Stamp;
use super::generate::{Part, Plan, Targets};
use super::{JointTarget, Units};
use nalgebra::{UnitQuaternion, Vector3};
use stiffid_core::robot::configuration::Configuration;
use stiffid_core::robot::external::Role;
use stiffid_core::Result;

/// What a reader finds in a program: its targets in motion order, its external axes' names, per
/// value the pulses per unit of a value written in pulses (empty: every value decimal), per
/// external axis the unit written and its line (empty where the language does not say).
#[derive(Debug, Clone, Default)]
pub struct Read {
    /// The targets, in the order of the motion instructions.
    pub targets: Vec<JointTarget>,
    /// The external axes as the program names them.
    pub axes: Vec<String>,
    /// Per value (six axes, then external), the pulses per deg or mm; `None` or absent: decimal.
    pub pulses: Vec<Option<f64>>,
    /// Per external axis, the unit written (`mm`, `deg`) and the line of its first value.
    pub units: Units,
    /// The motions left as found ([`super::Context::leave_refused`]).
    pub left: Vec<super::Left>,
    /// The programs of the controller's backup the program calls that move (LS `CALL`): each
    /// file's name as given and its text, in the order their texts follow the program's (and its
    /// data file's) in the spans of `targets` (the program's `called` texts).
    pub called: Vec<(String, String)>,
    /// What the reader took from the controller's backup that the user should know (a motion
    /// to an LS position register read from its `POSREG.VA`), one sentence each.
    pub notes: Vec<String>,
}

/// How a target's bound is written as a comment (`app::compensate::certify`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BoundComment {
    /// At the end of the line that ends the motion instruction, after `marker`; `statement`:
    /// the character that ends an instruction over several lines (`None`: every line ends one).
    EndOfLine {
        /// The comment marker (KRL `;`, RAPID `!`).
        marker: char,
        /// What ends a statement (RAPID `;`), if a statement may span lines.
        statement: Option<char>,
    },
    /// A comment line of its own before the motion's line, after `marker` (INFORM `'`).
    LineBefore {
        /// The comment marker.
        marker: char,
    },
    /// The position's comment (LS `P[i:"0.0123 mm"]`).
    PositionComment,
}

/// A controller language (module docs): what it is as data in [`Controller::LANGUAGE`], its
/// configuration data's type [`Controller::Flags`], and the few methods that read its programs
/// and state its poses; everything else has a default reading the descriptor. The registry
/// ([`super::Dialect`]) holds each language as a [`DynController`], which every `Controller`
/// is. Each method says what it gives; the names follow the controller's manual.
pub trait Controller: Sync + 'static {
    /// Its configuration data (KRL's status and turn, RAPID's `confdata`, LS `CONFIG`), as the
    /// controller's manual defines them from the posture.
    type Flags: ConfigurationData;
    /// What the language is, as data.
    const LANGUAGE: &'static Descriptor;

    /// The targets, external axes, pulses and units of program `text` (module docs of
    /// [`super`]), each target with its speed.
    ///
    /// # Errors
    /// [`stiffid_core::Error::Program`] naming the line of a motion outside the subset read.
    fn read(&self, text: &str) -> Result<Read>;
    /// A Cartesian target's orientation from its numbers in the language's order (the position,
    /// mm, then KRL A, B, C deg, RAPID a quaternion, LS W, P, R deg).
    fn rotation(&self, numbers: &[f64]) -> UnitQuaternion<f64>;
    /// The numbers that state a pose (position `p`, mm, and rotation `r`), in the order
    /// [`Controller::rotation`] reads them.
    fn pose_numbers(&self, p: &Vector3<f64>, r: &UnitQuaternion<f64>) -> Vec<f64>;
    /// The text of a pose's `k`-th number (in [`Controller::pose_numbers`]' order) as the
    /// language writes it; by default with `DECIMALS` decimals.
    fn pose_text(&self, k: usize, value: f64) -> String {
        let _ = k;
        super::generate::v(value)
    }

    /// [`Controller::read`] with what the setup says in `context` and the data file beside the
    /// program (KRL's `.dat`, `context.data`); by default, a language whose programs state
    /// everything reads them as [`Controller::read`] does.
    ///
    /// # Errors
    /// Those of [`Controller::read`].
    fn read_in(&self, text: &str, context: &super::Context) -> Result<Read> {
        let _ = context;
        self.read(text)
    }
    /// The program name declared on `line` (trimmed at its start): the offset in `line` of the
    /// end of the declaring keyword; by default the descriptor's [`NameRules::declared_by`] at
    /// the line's start.
    fn declares_name(&self, line: &str) -> Option<usize> {
        let keyword = Self::LANGUAGE.names.declared_by?;
        line.strip_prefix(keyword).map(|r| line.len() - r.len())
    }
    /// The lines (1-based) of the motion instructions of a program stiffid wrote, in order; by
    /// default those starting with one of the descriptor's [`Descriptor::motion_words`].
    fn motion_lines(&self, text: &str) -> Vec<u64> {
        lines_starting(text, Self::LANGUAGE.motion_words)
    }
    /// What writes new programs in the language; `None` (the default): programs are read and
    /// written back compensated, never generated.
    fn generator(&self) -> Option<&'static dyn Generator> {
        None
    }
    /// The extensions (lowercase) of the files of a controller's backup the language reads
    /// beside a program ([`super::Context::backup`]); by default its programs' own.
    fn backup_extensions(&self) -> &'static [&'static str] {
        Self::LANGUAGE.extensions
    }
    /// Whether the controller holds one file of the backup's file name `name` (its last path
    /// component): two different files of the name in one backup are then refused, as no one
    /// controller holds both; by default every name.
    fn held_once(&self, name: &str) -> bool {
        let _ = name;
        true
    }
    /// The program `text`'s data file among the backup's files of `context` (KRL's `.dat` of
    /// the module), read and written as one beside it ([`super::Context::data`]); by default
    /// none.
    fn data_file<'a>(&self, text: &str, context: &super::Context<'a>) -> Option<&'a str> {
        let _ = (text, context);
        None
    }
    /// A file of the program `written` back from its text `read`, finished as the language
    /// needs (an INFORM job's `///NPOS` counting the positions copied into it); by default as
    /// it is.
    fn written(&self, read: &str, written: String) -> String {
        let _ = read;
        written
    }
    /// The characters a program's name may hold besides letters, digits and `_`; by default
    /// none.
    fn name_symbols(&self) -> &'static str {
        ""
    }
    /// The files of a backup the language reads by name (INFORM's `TOOL.CND`, `UFRAME.CND`,
    /// `VAR.DAT`), upper case: one of a folder that is not text is refused, not passed over; by
    /// default none.
    fn backup_names(&self) -> &'static [&'static str] {
        &[]
    }
    /// What the program's external axis `name` ([`super::JointProgram::axes`]) carries where
    /// the language says (INFORM: a base axis `BC` the arm, a station axis `EC` the part); by
    /// default `None`: the program's axes are the cell's in order, whatever they carry.
    fn axis_role(&self, name: &str) -> Option<Role> {
        let _ = name;
        None
    }
}

/// A [`Controller`] as the registry holds it ([`super::Dialect::controller`]): its
/// configuration data without their type ([`Flags`]). Every [`Controller`] is one; the data
/// methods read its [`Descriptor`].
pub trait DynController: Sync {
    /// What the language is, as data ([`Controller::LANGUAGE`]).
    fn descriptor(&self) -> &'static Descriptor;
    /// [`Controller::read`].
    ///
    /// # Errors
    /// Those of [`Controller::read`].
    fn read(&self, text: &str) -> Result<Read>;
    /// [`Controller::read_in`].
    ///
    /// # Errors
    /// Those of [`Controller::read`].
    fn read_in(&self, text: &str, context: &super::Context) -> Result<Read>;
    /// [`Controller::rotation`].
    fn rotation(&self, numbers: &[f64]) -> UnitQuaternion<f64>;
    /// [`Controller::pose_numbers`].
    fn pose_numbers(&self, p: &Vector3<f64>, r: &UnitQuaternion<f64>) -> Vec<f64>;
    /// [`Controller::pose_text`].
    fn pose_text(&self, k: usize, value: f64) -> String;
    /// The configuration data of the posture `arm` as the controller writes them.
    fn flags(&self, arm: &Configuration) -> Flags;
    /// The configuration data's name in the language, for messages (`S and T`).
    fn flags_name(&self) -> &'static str;
    /// [`Controller::declares_name`].
    fn declares_name(&self, line: &str) -> Option<usize>;
    /// [`Controller::motion_lines`].
    fn motion_lines(&self, text: &str) -> Vec<u64>;
    /// [`Controller::generator`].
    fn generator(&self) -> Option<&'static dyn Generator>;
    /// [`Controller::backup_extensions`].
    fn backup_extensions(&self) -> &'static [&'static str];
    /// [`Controller::held_once`].
    fn held_once(&self, name: &str) -> bool;
    /// [`Controller::data_file`].
    fn data_file<'a>(&self, text: &str, context: &super::Context<'a>) -> Option<&'a str>;
    /// [`Controller::written`].
    fn written(&self, read: &str, written: String) -> String;
    /// [`Controller::axis_role`].
    fn axis_role(&self, name: &str) -> Option<Role>;

    /// The language's name in documents and options (`krl`, `rapid`, `ls`, `inform`).
    fn key(&self) -> &'static str {
        self.descriptor().key
    }
    /// The language's name for people (`KUKA KRL`).
    fn title(&self) -> &'static str {
        self.descriptor().title
    }
    /// The file extensions read as this language, lowercase; the first is the one written.
    fn extensions(&self) -> &'static [&'static str] {
        self.descriptor().extensions
    }
    /// Why a program is not written to a file of `extension` (lowercase) though it reads it
    /// (KRL's `.dat`), if so.
    fn refuses_output(&self, extension: &str) -> Option<&'static str> {
        (self.descriptor().data_files.iter())
            .find(|(e, _)| *e == extension)
            .map(|(_, why)| *why)
    }
    /// The motions read, for the message of a program with none.
    fn motions(&self) -> &'static str {
        self.descriptor().motions
    }
    /// The forms of its joint targets, for messages (`E6AXIS, AXIS`).
    fn joint_forms(&self) -> &'static str {
        self.descriptor().joint_forms
    }
    /// The forms of its Cartesian targets in the part frame, for messages; `None`: the language
    /// has no Cartesian targets stiffid reads.
    fn part_forms(&self) -> Option<&'static str> {
        self.descriptor().part_forms
    }
    /// The name of the program's `k`-th external axis (0-based) where the program gives none.
    fn external_axis(&self, k: usize) -> String {
        self.descriptor().external_axes.name(k)
    }
    /// What a target says for an axis it does not move, for messages (RAPID ` (9E9: not
    /// used)`), or empty.
    fn unused_axis(&self) -> &'static str {
        self.descriptor().unused_axis
    }
    /// Whether a value 0 of an axis the cell lacks means no axis (KRL: `E1`..`E6` in every
    /// `E6AXIS`).
    fn zero_is_no_axis(&self) -> bool {
        self.descriptor().zero_is_no_axis
    }
    /// The program name of a file stem, as the controller calls it (LS, INFORM upper case);
    /// `None`: the name is not the file's (a RAPID module).
    fn program_name(&self, stem: &str) -> Option<String> {
        self.descriptor().names.file.name(stem)
    }
    /// The longest program name the controller takes.
    fn max_name_length(&self) -> usize {
        self.descriptor().names.max_length
    }
    /// The longest program name written by default (at most [`DynController::max_name_length`]).
    fn default_name_length(&self) -> usize {
        self.descriptor().names.default_length
    }
    /// The words a program may not be named (the language's reserved words, and the names of
    /// the data stiffid declares in a program it writes).
    fn reserved_words(&self) -> &'static [&'static str] {
        self.descriptor().names.reserved
    }
    /// The characters a program's name may hold besides letters, digits and `_` (INFORM `-`).
    fn name_symbols(&self) -> &'static str;
    /// [`Controller::backup_names`].
    fn backup_names(&self) -> &'static [&'static str];
    /// How a target's bound is written as a comment.
    fn bound_comment(&self) -> BoundComment {
        self.descriptor().bound_comment
    }
}

impl<C: Controller> DynController for C {
    fn descriptor(&self) -> &'static Descriptor {
        C::LANGUAGE
    }
    fn read(&self, text: &str) -> Result<Read> {
        Controller::read(self, text)
    }
    fn read_in(&self, text: &str, context: &super::Context) -> Result<Read> {
        Controller::read_in(self, text, context)
    }
    fn rotation(&self, numbers: &[f64]) -> UnitQuaternion<f64> {
        Controller::rotation(self, numbers)
    }
    fn pose_numbers(&self, p: &Vector3<f64>, r: &UnitQuaternion<f64>) -> Vec<f64> {
        Controller::pose_numbers(self, p, r)
    }
    fn pose_text(&self, k: usize, value: f64) -> String {
        Controller::pose_text(self, k, value)
    }
    fn flags(&self, arm: &Configuration) -> Flags {
        Flags::new(C::Flags::of(arm))
    }
    fn flags_name(&self) -> &'static str {
        <C::Flags as ConfigurationData>::NAME
    }
    fn declares_name(&self, line: &str) -> Option<usize> {
        Controller::declares_name(self, line)
    }
    fn motion_lines(&self, text: &str) -> Vec<u64> {
        Controller::motion_lines(self, text)
    }
    fn generator(&self) -> Option<&'static dyn Generator> {
        Controller::generator(self)
    }
    fn backup_extensions(&self) -> &'static [&'static str] {
        Controller::backup_extensions(self)
    }
    fn held_once(&self, name: &str) -> bool {
        Controller::held_once(self, name)
    }
    fn data_file<'a>(&self, text: &str, context: &super::Context<'a>) -> Option<&'a str> {
        Controller::data_file(self, text, context)
    }
    fn written(&self, read: &str, written: String) -> String {
        Controller::written(self, read, written)
    }
    fn axis_role(&self, name: &str) -> Option<Role> {
        Controller::axis_role(self, name)
    }
    fn name_symbols(&self) -> &'static str {
        Controller::name_symbols(self)
    }
    fn backup_names(&self) -> &'static [&'static str] {
        Controller::backup_names(self)
    }
}

/// Writes new programs in a language (module docs of [`super::generate`]): the four methods
/// that write its text, and what its programs can hold as data ([`Generator::writing`]), which
/// the other methods read by default.
pub trait Generator: Sync {
    /// The main program's header: the tool, the frames and the motion settings; `main` its
    /// name and `subs` its sub-programs'.
    fn header(&self, plan: &Plan, main: &str, subs: &[String]) -> String;
    /// The moves of `part`.
    ///
    /// # Errors
    /// [`stiffid_core::Error::Program`] for a move the language cannot state.
    fn body(&self, plan: &Plan, part: &Part, warnings: &mut Vec<String>) -> Result<String>;
    /// The main program's calls of its sub-programs `subs`, in order.
    fn calls(&self, subs: &[String]) -> String;
    /// The whole file of program `name` (`main`: the main program), dated `date` where the
    /// language states a date.
    fn wrap(&self, name: &str, header: &str, body: &str, main: bool, date: Stamp) -> String;
    /// What its programs can hold and how they write it, as data.
    fn writing(&self) -> &'static Writing;

    /// The most moves (or calls) one file holds, where the language limits them
    /// ([`Writing::lines_per_file`]).
    fn lines_per_file(&self) -> Option<usize> {
        self.writing().lines_per_file
    }
    /// What a sub-program's routine name adds before the program's name (RAPID `r`;
    /// [`Writing::routine_prefix`]).
    fn routine_prefix(&self) -> &'static str {
        self.writing().routine_prefix
    }
    /// Whether a program with `targets` states the tool's mass and centre of mass
    /// ([`Writing::states_mass`], whatever the targets).
    fn needs_mass(&self, targets: Targets) -> bool {
        let _ = targets;
        self.writing().states_mass
    }
    /// Whether a Cartesian target is written as a pose; `false`: every target is written as its
    /// axis angles, whatever [`super::generate::Targets`] asks (INFORM's pulses;
    /// [`Writing::cartesian`]).
    fn writes_cartesian(&self) -> bool {
        self.writing().cartesian
    }
    /// A written file `text` of program `name` split into the program and the data file the
    /// controller stores beside it (KRL: the `.src` naming its points and the `.dat` declaring
    /// them); `None`: the language keeps one file.
    fn data_file(&self, name: &str, text: &str) -> Option<(String, String)> {
        let _ = (name, text);
        None
    }
    /// Whether a program states its axes in encoder pulses, which the setup must give
    /// (`[controller] pulses_per_deg`; [`Writing::pulses`]).
    fn needs_pulses(&self) -> bool {
        self.writing().pulses
    }
    /// How the language writes a circular move in a program of `targets`
    /// ([`super::generate::arcs`]; [`Writing::arcs`]); `None`: its arcs are written as their
    /// chord points.
    fn circular(&self, targets: Targets) -> Option<super::generate::arcs::Form> {
        let arcs = self.writing().arcs?;
        (arcs.joint_targets || targets == Targets::Cartesian).then_some(arcs.form)
    }
    /// The most external axes of `role` a program holds ([`Writing::carrier`],
    /// [`Writing::positioner`]).
    fn most_external(&self, role: Role) -> usize {
        group(self.writing(), role).most
    }
    /// Where a program writes the external axes of `role`, for messages (KRL `E1..E6`).
    fn external_form(&self, role: Role) -> &'static str {
        group(self.writing(), role).form
    }
    /// How the language writes the G-code's process words ([`super::generate::Process`];
    /// [`Writing::process`]); `None`: it writes none (a program with process words is refused).
    fn process_form(&self) -> Option<&'static super::generate::ProcessForm> {
        self.writing().process
    }
    /// Checks what the language can state of `settings` (LS: a whole percent of joint speed).
    ///
    /// # Errors
    /// [`stiffid_core::Error::InvalidField`] naming the setting's setup field.
    fn check_settings(&self, _settings: &super::generate::Settings) -> Result<()> {
        Ok(())
    }
}

/// The external axes of `role` a language's programs hold.
fn group(writing: &Writing, role: Role) -> ExternalGroup {
    match role {
        Role::Carrier => writing.carrier,
        Role::Positioner => writing.positioner,
    }
}

/// The lines (1-based) of `text` that start (after blanks) with one of `motions`.
pub(crate) fn lines_starting(text: &str, motions: &[&str]) -> Vec<u64> {
    (text.lines().enumerate())
        .filter(|(_, l)| motions.iter().any(|m| l.trim_start().starts_with(m)))
        .map(|(i, _)| i as u64 + 1)
        .collect()
}
