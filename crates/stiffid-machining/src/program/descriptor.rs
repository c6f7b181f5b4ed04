//! What a controller language is, as data: its names, files, target forms, external axes'
//! names, program names' rules and how a bound is commented ([`Descriptor`]), which each
//! language declares once in its folder as its [`super::Controller::LANGUAGE`].

use super::controller::BoundComment;

/// A controller language as data (module docs); each field says what the trait's method of its
/// name gives ([`super::DynController`]).
#[derive(Debug, Clone, Copy)]
pub struct Descriptor {
    /// The language's name in documents and options (`krl`, `rapid`, `ls`, `inform`).
    pub key: &'static str,
    /// The language's name for people (`KUKA KRL`).
    pub title: &'static str,
    /// The file extensions read as this language, lowercase; the first is the one written.
    pub extensions: &'static [&'static str],
    /// The extensions read but never written, each with why (KRL's `.dat`: data only).
    pub data_files: &'static [(&'static str, &'static str)],
    /// The motions read, for the message of a program with none.
    pub motions: &'static str,
    /// The forms of its joint targets, for messages (`E6AXIS, AXIS`).
    pub joint_forms: &'static str,
    /// The forms of its Cartesian targets in the part frame, for messages; `None`: the language
    /// has no Cartesian targets stiffid reads.
    pub part_forms: Option<&'static str>,
    /// How a program's external axes are named where it gives no name.
    pub external_axes: AxisNames,
    /// What a target says for an axis it does not move, for messages (RAPID ` (9E9: not
    /// used)`), or empty.
    pub unused_axis: &'static str,
    /// Whether a value 0 of an axis the cell lacks means no axis (KRL: `E1`..`E6` in every
    /// `E6AXIS`).
    pub zero_is_no_axis: bool,
    /// The rules of its program names.
    pub names: NameRules,
    /// How a target's bound is written as a comment.
    pub bound_comment: BoundComment,
    /// The words (with the blank after them) that start a motion line of a program stiffid
    /// wrote (`PTP `), for [`super::Controller::motion_lines`]'s default.
    pub motion_words: &'static [&'static str],
    /// The highest tool and base (user frame) numbers a program selects on the controller
    /// (KSS `TOOL_DATA[16]`, `BASE_DATA[32]`; FANUC `UTOOL[10]`, `UFRAME[9]`); a setup's table
    /// entry beyond them is stated instead ([`super::generate::numbered`]); `(0, 0)`: the
    /// language states its frames.
    pub frame_numbers: (u32, u32),
    /// Whether the controller measures axis 3 from the horizontal (FANUC's J2/J3 interaction),
    /// so that its joint positions on a URDF robot need the setup's `robot_axis_map` to couple
    /// joint 3 with joint 2 (warned where the setup does not).
    pub axis_3_from_horizontal: bool,
}

/// The rules of a language's program names.
#[derive(Debug, Clone, Copy)]
pub struct NameRules {
    /// The keyword at the start of the line that declares the program's name (LS `/PROG`,
    /// INFORM `//NAME`); `None`: no line does (a RAPID module's name is not its file's).
    pub declared_by: Option<&'static str>,
    /// How the controller names a program after its file.
    pub file: FileName,
    /// The longest program name the controller takes.
    pub max_length: usize,
    /// The longest program name written by default (at most `max_length`).
    pub default_length: usize,
    /// The words a program may not be named (the language's reserved words, and the names of
    /// the data stiffid declares in a program it writes).
    pub reserved: &'static [&'static str],
}

/// How a controller names a program after its file's stem.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileName {
    /// The stem as it is (KRL).
    Stem,
    /// The stem in upper case (LS, INFORM).
    Upper,
    /// The name is not the file's (a RAPID module).
    NotFile,
}

impl FileName {
    /// The program name of a file `stem`; `None`: not the file's.
    pub(crate) fn name(self, stem: &str) -> Option<String> {
        match self {
            FileName::Stem => Some(stem.to_string()),
            FileName::Upper => Some(stem.to_ascii_uppercase()),
            FileName::NotFile => None,
        }
    }
}

/// How a program's external axes are named where it gives no name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AxisNames {
    /// The prefix and the axis' number from 1 (KRL, LS `E1`; INFORM `external axis 1`).
    Numbered(&'static str),
    /// The prefix and a letter from `a` (RAPID `eax_a`).
    Lettered(&'static str),
}

impl AxisNames {
    /// The name of the `k`-th external axis (0-based).
    pub(crate) fn name(self, k: usize) -> String {
        match self {
            AxisNames::Numbered(prefix) => format!("{prefix}{}", k + 1),
            AxisNames::Lettered(prefix) => format!("{prefix}{}", (b'a' + k as u8) as char),
        }
    }
}

/// What a language's new programs can hold and how they write it, as data: what each data method
/// of [`super::Generator`] gives ([`super::Generator::writing`]), declared once in the language's
/// `generate.rs`.
#[derive(Debug, Clone, Copy)]
pub struct Writing {
    /// The most moves (or calls) one file holds, where the language limits them (LS's lines of a
    /// program, INFORM's positions of a job).
    pub lines_per_file: Option<usize>,
    /// What a sub-program's routine name adds before the program's name (RAPID `r`).
    pub routine_prefix: &'static str,
    /// Whether every program states the tool's mass and centre of mass (RAPID's `tooldata`).
    pub states_mass: bool,
    /// Whether a Cartesian target is written as a pose; `false`: every target is written as its
    /// axis angles (INFORM's pulses).
    pub cartesian: bool,
    /// Whether a program states its axes in encoder pulses, which the setup must give
    /// (`[controller] pulses_per_deg`).
    pub pulses: bool,
    /// How it writes a circular move; `None`: its arcs are written as their chord points.
    pub arcs: Option<Arcs>,
    /// The external axes a program holds under the arm (a track).
    pub carrier: ExternalGroup,
    /// The external axes a program holds under the workpiece (a positioner).
    pub positioner: ExternalGroup,
    /// How it writes the G-code's process words; `None`: it writes none (a program with process
    /// words is refused).
    pub process: Option<&'static super::generate::ProcessForm>,
}

/// How a language writes a circular move ([`Writing::arcs`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Arcs {
    /// The positions it states ([`super::generate::arcs`]).
    pub form: super::generate::arcs::Form,
    /// Whether a program of joint targets writes its arcs too (INFORM's `MOVC` of taught
    /// positions); `false`: with Cartesian targets only (joint targets are interpolated axis by
    /// axis).
    pub joint_targets: bool,
}

/// The external axes of one role a language's program holds ([`Writing::carrier`],
/// [`Writing::positioner`]).
#[derive(Debug, Clone, Copy)]
pub struct ExternalGroup {
    /// The most axes.
    pub most: usize,
    /// Where a program writes them, for messages (KRL `E1 to E6`).
    pub form: &'static str,
}
