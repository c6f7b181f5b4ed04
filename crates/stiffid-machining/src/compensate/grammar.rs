//! The grammar of a free variable's text, one for `compensate --free` ([`super::FreeOption`])
//! and `place --free` (`stiffid::app::place::Free::parse`): `NAME`, `NAME=LO..HI`,
//! `NAME=LO..HI/STEP` or `NAME=/STEP`, the range and step in the variable's unit (mm or deg)
//! from its own value; each command says which names, ranges and steps it takes.

use stiffid_core::common::error::JobOption;
use stiffid_core::{Error, Result};

/// A free variable's text in its parts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Parts<'a> {
    /// The variable's name, trimmed: never empty.
    pub name: &'a str,
    /// `LO..HI`, `LO <= HI`, finite; `None` when the text gives no range.
    pub range: Option<[f64; 2]>,
    /// The step after `/`, finite; `None` when the text gives none.
    pub step: Option<f64>,
}

/// Splits `text` into its [`Parts`].
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::Free`]) naming the text and what was expected: no
/// name before `=`, a range not `LO..HI` of two finite numbers with `LO <= HI`, `/` without a
/// step, a step not a finite number.
pub fn parts(text: &str) -> Result<Parts<'_>> {
    let (name, value) = text.split_once('=').unwrap_or((text, ""));
    let name = name.trim();
    if name.is_empty() {
        return Err(invalid(text, "expected a variable before `=`"));
    }
    let (range, step) = value.split_once('/').unwrap_or((value, ""));
    let step = match step.trim() {
        "" if value.contains('/') => return Err(invalid(text, "expected a step after `/`")),
        "" => None,
        s => Some(number(text, s)?),
    };
    let range = match range.trim() {
        "" => None,
        r => {
            let Some((lo, hi)) = r.split_once("..") else {
                return Err(invalid(text, &format!("`{r}`: expected a range LO..HI")));
            };
            let (lo, hi) = (number(text, lo)?, number(text, hi)?);
            if lo > hi {
                return Err(invalid(
                    text,
                    &format!("`{r}`: expected a range LO..HI with LO <= HI"),
                ));
            }
            Some([lo, hi])
        }
    };
    Ok(Parts { name, range, step })
}

/// A finite number, else an error naming `text`.
fn number(text: &str, s: &str) -> Result<f64> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(invalid(text, &format!("`{}`: expected a number", s.trim()))),
    }
}

/// The error of the text of a free variable: [`Error::InvalidOption`] ([`JobOption::Free`]),
/// `text: why`.
pub fn invalid(text: &str, why: &str) -> Error {
    Error::InvalidOption {
        option: JobOption::Free,
        message: format!("{text}: {why}"),
    }
}
