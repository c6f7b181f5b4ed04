//! The user's choices as library enums: one enum per choice (the loss of a robust fit, the frame
//! of a wrench, the joint coordinates, ...), each with its name ([`Choice::name`]), a one-line
//! help, every value ([`Choice::ALL`]) and [`std::str::FromStr`] by name ([`parse`]). The command
//! line builds its option values from them and Python its keyword values, so a choice has one
//! spelling everywhere.

use crate::common::limits::short;
use crate::{Error, Result};

/// A user's choice among a few named values.
pub trait Choice: Copy + Sized + 'static {
    /// What is chosen, as a field name in errors (e.g. `robust`).
    const FIELD: &'static str;
    /// Every value, in the order help lists them.
    const ALL: &'static [Self];
    /// The value's name, lower case with dashes (e.g. `huber`).
    fn name(self) -> &'static str;
    /// One line on what the value means.
    fn help(self) -> &'static str;
}

/// The value of `T` named `text`.
///
/// # Errors
/// [`Error::InvalidField`] (`T::FIELD`) naming the value given and the known names.
pub fn parse<T: Choice>(text: &str) -> Result<T> {
    T::ALL
        .iter()
        .copied()
        .find(|v| v.name() == text)
        .ok_or_else(|| Error::InvalidField {
            field: T::FIELD.into(),
            message: format!(
                "unknown value '{}' (known: {})",
                short(text),
                names::<T>().join(", ")
            ),
        })
}

/// The names of every value of `T`.
pub fn names<T: Choice>() -> Vec<&'static str> {
    T::ALL.iter().map(|v| v.name()).collect()
}

/// Implements [`std::str::FromStr`] by [`parse`] and [`std::fmt::Display`] by the name for
/// choices.
#[doc(hidden)]
#[macro_export]
macro_rules! __choice_by_name {
    ($($t:ty),*) => {$(
        impl std::str::FromStr for $t {
            type Err = $crate::Error;
            fn from_str(s: &str) -> $crate::Result<Self> {
                $crate::common::choice::parse(s)
            }
        }
        impl std::fmt::Display for $t {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str($crate::common::choice::Choice::name(*self))
            }
        }
    )*};
}
pub use __choice_by_name as by_name;
