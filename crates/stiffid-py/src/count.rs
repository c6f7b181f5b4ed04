//! Integer arguments that cannot be negative (counts, budgets, seeds): taken as `i64`, so that a
//! negative one is an `InputError` (a `ValueError`) naming the argument, where an unsigned
//! argument would raise an `OverflowError` that does not.

use crate::error::value;
use pyo3::{PyErr, PyResult};

/// The count `given` as the argument `name`; an `InputError` naming it when it is negative.
pub fn count(name: &str, given: i64) -> PyResult<usize> {
    usize::try_from(given).map_err(|_| negative(name, given))
}

/// [`count`] of an argument that may be left out.
pub fn optional(name: &str, given: Option<i64>) -> PyResult<Option<usize>> {
    given.map(|v| count(name, v)).transpose()
}

/// [`count`] as a `u64`: a seed.
pub fn seed(name: &str, given: i64) -> PyResult<u64> {
    u64::try_from(given).map_err(|_| negative(name, given))
}

fn negative(name: &str, given: i64) -> PyErr {
    value(format!(
        "{name}: {given} is negative: expected a whole number, 0 or more"
    ))
}
