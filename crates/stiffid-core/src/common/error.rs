//! The library's error type.

pub use super::job_option::{combination, JobOption};
use thiserror::Error;

/// Everything that can go wrong in stiffid, each variant naming what was wrong and where.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// An error about one input (a file, the arrays of a call), named first.
    #[error("{source_name}: {error}")]
    Input {
        /// The input: a file's name, or `arrays`.
        source_name: String,
        /// What was wrong in it.
        error: Box<Error>,
    },
    /// A file or text could not be parsed. `source_name` is the file (or preset) name.
    #[error("{source_name}: {message}")]
    Parse {
        /// The file or preset being read.
        source_name: String,
        /// What was wrong, naming the field and what was expected.
        message: String,
    },
    /// A field has a value outside what it may hold.
    #[error("{field}: {message}")]
    InvalidField {
        /// The field, as named in files (for example `joint[2].a_mm`).
        field: String,
        /// What was expected.
        message: String,
    },
    /// An option of a job's request has a value outside what it may hold. A front end names the
    /// option its own way: Python by its keyword (`max_step_deg`, as this error's text does),
    /// the command by its option (`--margin-deg`).
    #[error("{option}: {message}")]
    InvalidOption {
        /// The option.
        option: JobOption,
        /// What was expected.
        message: String,
    },
    /// A gate the caller set failed: the job ran and its result lies beyond the bound an option
    /// gave (`compensate`'s `max_error_mm`, a calibration check that finds the robot drifted).
    /// Not bad input: the command exits with code 1 (2 for every other error), Python raises
    /// `GateError`. The option is named as for [`Error::InvalidOption`].
    #[error("{option}: {message}")]
    Gate {
        /// The option that set the gate.
        option: JobOption,
        /// What the result was and the bound it failed.
        message: String,
    },
    /// Options of a job's request set together that cannot go together, or an option set
    /// without the one it needs. A front end names the options its own way, as for
    /// [`Error::InvalidOption`] ([`combination`]).
    #[error("{}", combination(.option, .with, .needs, .reason, |o| o.name().to_string()))]
    OptionCombination {
        /// The option refused.
        option: JobOption,
        /// With `needs`, the option it needs; else the options set with it that it cannot go
        /// with.
        with: Vec<JobOption>,
        /// Whether `option` needs `with` (else it cannot go with them).
        needs: bool,
        /// Why, or empty.
        reason: String,
    },
    /// A URDF's collision mesh was not found (no file, or a `package://` package in none of the
    /// package paths). Only the cell's body checks need meshes: the robot still loads for
    /// kinematics and identification ([`crate::robot::Bodies::Missing`]).
    #[error("{source_name}: {message}")]
    MeshNotFound {
        /// The URDF being read.
        source_name: String,
        /// The link, the mesh and where it was looked for.
        message: String,
    },
    /// The robot is not a 6-axis serial chain of revolute joints as required.
    #[error("{source_name}: {message}")]
    Chain {
        /// The robot description being read.
        source_name: String,
        /// What is wrong with the chain.
        message: String,
    },
    /// No built-in preset or setup has this name.
    #[error("unknown {kind} '{name}' (known: {known})")]
    Unknown {
        /// "robot preset", "setup" or "criterion".
        kind: &'static str,
        /// The name asked for.
        name: String,
        /// The names that exist, comma-separated.
        known: String,
    },
    /// A reference that looks like a file path names neither an existing file nor a built-in.
    #[error("{kind} '{reference}': no file {path} and no {builtin} of that name (known: {known})")]
    NotFound {
        /// "robot" or "setup".
        kind: &'static str,
        /// The reference as given, shortened.
        reference: String,
        /// The path looked at, shortened.
        path: String,
        /// "preset" or "built-in setup".
        builtin: &'static str,
        /// The built-in names, comma-separated.
        known: String,
    },
    /// The data cannot identify these joints' compliances.
    #[error("{} cannot be identified: {reason}", joint_list(joints))]
    Unidentifiable {
        /// The joints concerned, 1-based.
        joints: Vec<usize>,
        /// Why: no posture loads them, or their columns of `Psi` are dependent.
        reason: String,
    },
    /// Fewer observation rows than unknowns.
    #[error(
        "{rows} observation rows cannot identify 6 compliances (need at least 6 independent rows)"
    )]
    TooFewRows {
        /// The number of rows given.
        rows: usize,
    },
    /// A group of postures cannot separate these combinations of the model's parameters (a model
    /// with virtual springs; for the drives alone, [`Error::Unidentifiable`]).
    #[error(
        "the group cannot separate {}: choose postures that load these parameters differently",
        combinations.join("; ")
    )]
    Inseparable {
        /// The combinations, written out, e.g. `0.71 k6 - 0.71 flange_rz`.
        combinations: Vec<String>,
    },
    /// One measurement of a data set cannot be used.
    #[error("measurement {number}, {field}: {message}")]
    Measurement {
        /// Its 1-based position in the list of measurements.
        number: usize,
        /// What is wrong in it.
        field: MeasurementField,
        /// What was expected.
        message: String,
    },
    /// No group of postures that passes every feasibility check of the cell was found.
    #[error(
        "no feasible group found: the {check} check failed in {failed} of the {} \
         searched; what decides it: {remedy}",
        crate::common::words::count(*.postures, "posture")
    )]
    Infeasible {
        /// The check failed by the most postures, e.g. `self-collision`.
        check: String,
        /// In how many postures it failed.
        failed: usize,
        /// How many postures were checked.
        postures: usize,
        /// The setup fields that decide the check, with their values
        /// ([`crate::cell::CheckKind::remedy`]).
        remedy: String,
    },
    /// A table file (CSV) cannot be read: the line and, where there is one, the column.
    #[error("line {line}{}: {problem}", column_name(*column, name))]
    Column {
        /// The 1-based line of the text.
        line: u64,
        /// The 1-based column (field) of the line, if the problem is in one.
        column: Option<usize>,
        /// The column's name (or columns', e.g. `x_mm..rz_deg`) as the format names it; empty if
        /// the problem is in no column.
        name: String,
        /// What is wrong.
        problem: ColumnProblem,
    },
    /// A JSON text cannot be read: not JSON, or a key missing or of another shape.
    #[error("line {line}, column {column}: {message}; expected {expected}")]
    Json {
        /// The 1-based line of the text.
        line: usize,
        /// The 1-based column (character) of the line.
        column: usize,
        /// What the JSON reader found wrong.
        message: String,
        /// What the text should hold.
        expected: &'static str,
    },
    /// Inverse kinematics found no posture within the joint limits that reaches the pose
    /// ([`crate::robot::ik::solve`]).
    #[error("pose not reached within the joint limits: {position_error_mm:.3} mm and {rotation_error_deg:.3} deg away at best (outside the workspace, or only reachable beyond a joint limit); {}", unreached(*stop, *starts))]
    Unreachable {
        /// The remaining distance of the tool point, mm.
        position_error_mm: f64,
        /// The remaining rotation of the tool frame, deg.
        rotation_error_deg: f64,
        /// Why the descent from the start that came closest stopped:
        /// [`crate::common::stop::Stop::DampingExhausted`] (no step lowered the error: a local
        /// minimum, a joint limit, the edge of the workspace) or
        /// [`crate::common::stop::Stop::IterationLimit`] (the error still falling after the most
        /// steps: more steps may reach the pose).
        stop: crate::common::stop::Stop,
        /// The starts tried: the given posture and the seeded random ones.
        starts: usize,
    },
    /// An axis angle outside a box of axis angles ([`crate::common::limits::JointBox::check`]): the
    /// robot's joint limits or the setup's bounds.
    #[error(
        "{field} = {} deg: expected within {within} [{lower_deg:.2}, {upper_deg:.2}] deg",
        crate::common::words::distinct(*value_deg, *lower_deg, *upper_deg)
    )]
    OutsideBox {
        /// The angle as the user gave it, e.g. `bounds.upper_deg[3]` or `--q-deg[2]`.
        field: String,
        /// The value given, deg.
        value_deg: f64,
        /// The box, e.g. "the robot's limits" or "the setup's bounds".
        within: &'static str,
        /// The lower end of the axis' range, deg.
        lower_deg: f64,
        /// The upper end of the axis' range, deg.
        upper_deg: f64,
    },
    /// A setup field that only some criteria and computations use is not given, and this one
    /// needs it ([`crate::Setup::try_nominal_stiffness`],
    /// [`crate::Setup::try_characteristic_length`], `stiffid_design::Criterion::check`).
    #[error(
        "the setup has no {field}: {needed_by} needs it ({})",
        missing_hint(field)
    )]
    MissingField {
        /// The field as setup files name it: `nominal_stiffness_nm_per_rad` or
        /// `characteristic_length_mm`.
        field: &'static str,
        /// What needs it: a criterion (`criterion relative-a`) or a computation.
        needed_by: String,
    },
    /// A machining or robot program cannot be read, or its compensation cannot be written.
    #[error("line {line}: {message}")]
    Program {
        /// The 1-based line of the program.
        line: u64,
        /// What is wrong and what was expected.
        message: String,
    },
    /// A number was NaN or infinite where a finite number is needed.
    #[error("{what} is not finite")]
    NotFinite {
        /// What held the non-finite number.
        what: String,
    },
}

/// The part of a [`Error::Measurement`] that is wrong.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeasurementField {
    /// The posture index or label (e.g. one label at two sets of axis angles).
    Posture,
    /// The measuring point.
    Point,
    /// Axis angle `q_{i+1}` (0-based index `i`).
    Axis(usize),
    /// The force part of the wrench.
    Force,
    /// The moment part of the wrench.
    Moment,
    /// The measured displacement.
    Displacement,
    /// The external axis values (`e1_mm`, ...).
    External,
}

impl std::fmt::Display for MeasurementField {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            MeasurementField::Posture => write!(f, "posture"),
            MeasurementField::Point => write!(f, "point"),
            MeasurementField::Axis(i) => write!(f, "q{}", i + 1),
            MeasurementField::Force => write!(f, "force"),
            MeasurementField::Moment => write!(f, "moment"),
            MeasurementField::Displacement => write!(f, "displacement"),
            MeasurementField::External => write!(f, "external axes"),
        }
    }
}

/// What is wrong in a line of a table file (CSV) ([`Error::Column`]).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ColumnProblem {
    /// No header (an empty file).
    #[error("the file is empty: expected the header '{expected}' and one row per measurement")]
    Empty {
        /// The minimal header.
        expected: String,
    },
    /// A header other than the one the format has.
    #[error("expected the header '{expected}'{hint}")]
    Header {
        /// The header of the format.
        expected: String,
        /// Why the header may look wrong (a `;` separator), with a leading space; else empty.
        hint: String,
    },
    /// A header without rows.
    #[error("expected at least one {what} after the header")]
    NoRows {
        /// What a row holds, e.g. "measurement row".
        what: &'static str,
    },
    /// More rows than the format allows.
    #[error("more than {limit} {what}")]
    TooMany {
        /// The most rows allowed.
        limit: usize,
        /// What a row holds, plural, e.g. "postures".
        what: &'static str,
    },
    /// The CSV reader failed (e.g. invalid UTF-8 or quoting).
    #[error("cannot read the row: {message}")]
    Unreadable {
        /// The reader's message.
        message: String,
    },
    /// A header name that is not a known column.
    #[error("unknown column '{given}'{}; expected {expected}", suggestion.as_ref().map_or(String::new(), |s| format!(" (did you mean '{s}'?)")))]
    Unknown {
        /// The name given, shortened.
        given: String,
        /// A known column the name probably meant.
        suggestion: Option<String>,
        /// The accepted columns.
        expected: String,
    },
    /// A column named twice.
    #[error("column '{given}' appears twice")]
    Duplicate {
        /// The name given, shortened.
        given: String,
    },
    /// A needed column is absent from the header.
    #[error("missing column '{missing}'")]
    Missing {
        /// The absent column.
        missing: String,
    },
    /// Columns that exclude each other (two forms or two frames of one quantity).
    #[error("give either {first} or {second}, not both")]
    Conflict {
        /// One set of columns.
        first: String,
        /// The other.
        second: String,
    },
    /// A row with another number of fields than the header.
    #[error("expected {expected} fields as in the header, got {got}")]
    FieldCount {
        /// Fields in the header.
        expected: usize,
        /// Fields in the row.
        got: usize,
    },
    /// A field that is not a finite number.
    #[error("'{value}' is not a finite number")]
    NotANumber {
        /// The field, shortened.
        value: String,
    },
    /// A number outside the range it must lie in, e.g. an axis angle outside the joint limits.
    #[error("{name} = {} is outside {within} [{lower:.1}, {upper:.1}]", crate::common::words::number(*value))]
    Outside {
        /// The column's name.
        name: String,
        /// The value given, in the column's unit.
        value: f64,
        /// What the range is, e.g. "the robot's limits".
        within: &'static str,
        /// The lower end of the range, in the column's unit.
        lower: f64,
        /// The upper end of the range, in the column's unit.
        upper: f64,
    },
    /// An empty posture label.
    #[error("empty posture label")]
    EmptyLabel,
    /// A measuring-point field that is not 1, 2, ...
    #[error("'{value}' is not a measuring point number (1, 2, ...)")]
    NotAPoint {
        /// The field, shortened.
        value: String,
    },
    /// Columns of which one set must be given.
    #[error("missing columns: expected {first} or {second}")]
    Neither {
        /// One set of columns.
        first: String,
        /// The other.
        second: String,
    },
    /// A field that is none of the words it may hold.
    #[error("'{value}': expected {expected}")]
    Choice {
        /// The field, shortened.
        value: String,
        /// The words it may hold, e.g. "base or tool".
        expected: &'static str,
    },
    /// A path point that cannot be compensated (`stiffid_machining::compensate::path`).
    #[error("{reason}{}", other_lines(others, *failed))]
    Uncompensated {
        /// Why: a pose not reached (the message of [`Error::Unreachable`]), compensated axis
        /// angles outside the joint limits or a compensation that did not converge.
        reason: String,
        /// The lines of the other points that fail too (the first ten).
        others: Vec<u64>,
        /// How many points fail in all (this one included).
        failed: usize,
    },
    /// A measurement the library rejected ([`Error::Measurement`]), placed in the file.
    #[error("{message}")]
    Measurement {
        /// What was expected.
        message: String,
    },
}

/// Where a value for a missing setup field comes from ([`Error::MissingField`]).
fn missing_hint(field: &str) -> &'static str {
    match field {
        "nominal_stiffness_nm_per_rad" => {
            "a rough prior will do: one scaled from the robot's payload class \
             (stiffid::setup::prior::nominal_stiffness, with its source)"
        }
        "loading" => {
            "a [loading] table: load_n, the rope load in N, and anchor_mm, the pulley's position \
             in the base frame; a calibration needs none"
        }
        "tool.loading_point_mm" => {
            "where the rope pulls on the tool, flange frame, mm, under [tool]; a calibration \
             needs none"
        }
        "test.postures_deg" => {
            "the postures where the deflection matters to you, axis angles in degrees, under \
             [test]"
        }
        _ => {
            "the length that minimises the robot's median dexterity will do (the robot's own \
             characteristic length: Python's Robot.characteristic_length_mm, or the one \
             `stiffid setups new` writes)"
        }
    }
}

fn column_name(column: Option<usize>, name: &str) -> String {
    match (column, name.is_empty()) {
        (None, true) => String::new(),
        (None, false) => format!(", column {name}"),
        (Some(c), true) => format!(", column {c}"),
        (Some(c), false) => format!(", column {c} ({name})"),
    }
}

fn other_lines(others: &[u64], failed: usize) -> String {
    if others.is_empty() {
        return String::new();
    }
    let lines: Vec<String> = others.iter().map(u64::to_string).collect();
    let more = match failed - 1 > others.len() {
        true => format!(", ... ({} in all)", failed - 1),
        false => String::new(),
    };
    format!(
        "; the same for the points on lines {}{more}",
        lines.join(", ")
    )
}

/// Result with the library's [`enum@Error`].
pub type Result<T> = std::result::Result<T, Error>;

fn joint_list(joints: &[usize]) -> String {
    let names: Vec<String> = joints.iter().map(|j| j.to_string()).collect();
    match names.len() {
        1 => format!("joint {}", names[0]),
        _ => format!("joints {}", names.join(", ")),
    }
}

impl Error {
    /// The error itself, past the [`Error::Input`] that name where it happened: what kind of
    /// failure it is.
    pub fn root(&self) -> &Error {
        match self {
            Error::Input { error, .. } => error.root(),
            other => other,
        }
    }

    /// Whether this is a failed gate ([`Error::Gate`]) rather than bad input or a computation
    /// without an answer: the command's exit code 1.
    pub fn is_gate(&self) -> bool {
        matches!(self.root(), Error::Gate { .. })
    }
}

impl Error {
    /// An [`Error::InvalidField`] (as [`crate::common::limits::check`] makes it) as the error of
    /// the job option `option`; any other error as it is.
    pub fn for_option(self, option: JobOption) -> Self {
        match self {
            Error::InvalidField { message, .. } => Error::InvalidOption { option, message },
            e => e,
        }
    }
}

/// The clause of [`Error::Unreachable`] that says why the closest of `starts` starts stopped.
fn unreached(stop: crate::common::stop::Stop, starts: usize) -> String {
    use crate::common::stop::Stop;
    let why = match stop {
        Stop::IterationLimit => {
            "with the error still falling: more steps (max_iterations) may come closer"
        }
        Stop::DampingExhausted | Stop::Stalled => "where no step lowered the error",
        Stop::Converged => "within the tolerances",
    };
    let starts = crate::common::words::count(starts, "start");
    format!("the closest of {starts} stopped at {stop}, {why}")
}
