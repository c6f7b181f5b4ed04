//! Integer arguments that cannot be negative (counts, budgets, seeds): taken as `i64`, so that a
//! negative one is an `InputError` (a `ValueError`) naming the argument, where an unsigned
//! argument would raise an `OverflowError` that does not; and numbers where a bool is no number.

use crate::error::value;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyIterator, PyString};
use pyo3::{PyErr, PyResult};

/// The count `given` as the argument `name`; an `InputError` naming it when it is negative.
pub fn count(name: &str, given: i64) -> PyResult<usize> {
    usize::try_from(given).map_err(|_| negative(name, given))
}

/// [`count`] of an argument that may be left out.
pub fn optional(name: &str, given: Option<i64>) -> PyResult<Option<usize>> {
    given.map(|v| count(name, v)).transpose()
}

/// [`count`] as a `u64`: a seed that may be left out.
pub fn seed(name: &str, given: i64) -> PyResult<u64> {
    u64::try_from(given).map_err(|_| negative(name, given))
}

/// A seed read by PyO3 (`#[pyo3(from_py_with = count::seed_of)]`): an int from 0 to 2^64 - 1,
/// as the command's `--seed` takes it (a run of the command is repeated from Python with its
/// seed); never a bool. The package's functions put the argument's name in front of the message.
pub fn seed_of(given: &Bound<'_, PyAny>) -> PyResult<u64> {
    no_bool(given, "a whole number")?;
    given
        .extract::<u64>()
        .map_err(|e| match given.extract::<i64>() {
            Ok(v) if v < 0 => value(format!(
                "{v} is negative: expected a whole number, 0 or more"
            )),
            _ if e.is_instance_of::<pyo3::exceptions::PyOverflowError>(given.py()) => {
                value(format!(
                    "{given} is more than {}: expected a whole number, 0 to {0}",
                    u64::MAX
                ))
            }
            _ => e,
        })
}

fn negative(name: &str, given: i64) -> PyErr {
    value(format!(
        "{name}: {given} is negative: expected a whole number, 0 or more"
    ))
}

/// The number argument `name`, which may be left out: an `InputError` naming it for a bool
/// (`True` is not 1 here), an int beyond a float's range or anything but an int or a float.
pub fn real(name: &str, given: Option<&Bound<'_, PyAny>>) -> PyResult<Option<f64>> {
    let Some(v) = given else {
        return Ok(None);
    };
    if v.is_instance_of::<PyBool>() {
        return Err(value(format!("{name}: {v} is a bool: expected a number")));
    }
    v.extract::<f64>().map(Some).map_err(|e| {
        match e.is_instance_of::<pyo3::exceptions::PyOverflowError>(v.py()) {
            // An int beyond a float's range is a number still: say so, not "got int".
            true => value(format!(
                "{name}: an int too large for a float (at most about 1.8e308): expected a number"
            )),
            false => value(format!("{name}: expected a number, got {}", v.get_type())),
        }
    })
}

/// A number argument read by PyO3 (`#[pyo3(from_py_with = count::number)]`): an int or a float,
/// never a bool (`True` is not 1 here). PyO3 notes the argument's name on the error, which the
/// package's functions put in front of the message (`level: True is a bool: expected a number`).
pub fn number(given: &Bound<'_, PyAny>) -> PyResult<f64> {
    no_bool(given, "a number")?;
    given.extract::<f64>()
}

/// A whole-number argument read by PyO3 (`#[pyo3(from_py_with = count::whole)]`): an int, never
/// a bool; its sign is checked where it is used ([`count`], [`seed`]).
pub fn whole(given: &Bound<'_, PyAny>) -> PyResult<i64> {
    no_bool(given, "a whole number")?;
    given.extract::<i64>()
}

/// [`whole`] of an argument that may be `None`.
pub fn optional_whole(given: &Bound<'_, PyAny>) -> PyResult<Option<i64>> {
    no_bool(given, "a whole number")?;
    given.extract::<Option<i64>>()
}

fn no_bool(given: &Bound<'_, PyAny>, expected: &str) -> PyResult<()> {
    match given.is_instance_of::<PyBool>() {
        true => Err(value(format!("{given} is a bool: expected {expected}"))),
        false => Ok(()),
    }
}

/// Rows of numbers (a list of lists, or a 2-D array) as the argument `name`, none when left out:
/// an `InputError` naming the argument for a text or anything but rows, naming the element
/// (`name[i][j]`) for a bool or a non-number.
pub fn real_rows(name: &str, given: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<Vec<f64>>> {
    let Some(rows) = given else {
        return Ok(Vec::new());
    };
    (items(name, rows)?.enumerate())
        .map(|(i, row)| -> PyResult<Vec<f64>> {
            (items(name, &row?)?.enumerate())
                .map(|(j, v)| -> PyResult<f64> {
                    Ok(real(&format!("{name}[{i}][{j}]"), Some(&v?))?.unwrap_or(0.0))
                })
                .collect()
        })
        .collect()
}

/// The items of `o`, a sequence of the argument `name` (a text is none).
fn items<'py>(name: &str, o: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyIterator>> {
    let not_rows = || {
        value(format!(
            "{name}: expected rows of numbers, one list per row"
        ))
    };
    match o.is_instance_of::<PyString>() {
        true => Err(not_rows()),
        false => o.try_iter().map_err(|_| not_rows()),
    }
}
