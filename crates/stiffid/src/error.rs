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
        /// "robot preset" or "setup".
        kind: &'static str,
        /// The name asked for.
        name: String,
        /// The names that exist, comma-separated.
        known: String,
    },
    /// A number was NaN or infinite where a finite number is needed.
    #[error("{what} is not finite")]
    NotFinite {
        /// What held the non-finite number.
        what: String,
    },
}

/// Result with the library's [`Error`].
pub type Result<T> = std::result::Result<T, Error>;
