//! The library's error type.

use thiserror::Error;

/// Everything that can go wrong in stiffid, each variant naming what was wrong and where.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum Error {
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
    /// One measurement of a data set cannot be used.
    #[error("measurement {number}, {field}: {message}")]
    Measurement {
        /// Its 1-based position in the list of measurements.
        number: usize,
        /// What is wrong in it: `posture`, `point`, `q1`..`q6` (an axis angle), `wrench` or
        /// `displacement`.
        field: String,
        /// What was expected.
        message: String,
    },
    /// A row of a table file (CSV) cannot be used. `line` is 1-based, as an editor shows it.
    #[error("line {line}, column {column}: {message}")]
    Row {
        /// The line in the file.
        line: u64,
        /// The column (or columns, e.g. `x_mm..rz_deg`) as named in the header.
        column: String,
        /// What was wrong and what was expected, with the value given (shortened).
        message: String,
    },
    /// Inverse kinematics found no posture within the joint limits that reaches the pose.
    #[error("pose not reached within the joint limits: {position_error_mm:.3} mm and {rotation_error_deg:.3} deg away at best (outside the workspace, or only reachable beyond a joint limit)")]
    Unreachable {
        /// The remaining distance of the tool point, mm.
        position_error_mm: f64,
        /// The remaining rotation of the tool frame, deg.
        rotation_error_deg: f64,
    },
    /// A number was NaN or infinite where a finite number is needed.
    #[error("{what} is not finite")]
    NotFinite {
        /// What held the non-finite number.
        what: String,
    },
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
