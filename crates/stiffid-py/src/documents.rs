//! The library's documents ([`stiffid::app::document`]) as Python objects, and the jobs' warnings as
//! `UserWarning`s: the one way Python results are built, so they equal the command's JSON.

use crate::error::value;
use numpy::PyArray1;
use pyo3::exceptions::PyUserWarning;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use serde::Serialize;
use serde_json::{Map, Number, Value};
use std::ffi::CString;
use stiffid::internal::common::warning::Warning;

/// `document` as Python objects (JSON's: dict, list, str, int, float, bool, None), with the keys
/// of `arrays` (at the top level) as NumPy float arrays (`null` as NaN).
pub fn to_python<'py>(
    py: Python<'py>,
    document: &impl Serialize,
    arrays: &[&str],
) -> PyResult<Bound<'py, PyDict>> {
    let Value::Object(map) = to_json(document)? else {
        unreachable!("every document is a JSON object")
    };
    let dict = PyDict::new(py);
    for (key, value) in &map {
        let item = match arrays.contains(&key.as_str()) && !value.is_null() {
            true => array(py, value)?,
            false => object(py, value)?,
        };
        dict.set_item(key, item)?;
    }
    Ok(dict)
}

/// `document` (any value: a list of records, a number) as Python objects, as [`to_python`].
pub fn to_object<'py>(py: Python<'py>, document: &impl Serialize) -> PyResult<Bound<'py, PyAny>> {
    object(py, &to_json(document)?)
}

/// `document` as a JSON value (the library's documents always serialise; a failure is a
/// `RuntimeError`).
pub fn to_json(document: &impl Serialize) -> PyResult<Value> {
    serde_json::to_value(document)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))
}

/// A JSON value as the Python object of the same type.
pub fn object<'py>(py: Python<'py>, value: &Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match value {
        Value::Null => py.None().into_bound(py),
        Value::Bool(b) => b.into_pyobject(py)?.to_owned().into_any(),
        Value::Number(n) => match (n.as_u64(), n.as_i64()) {
            (Some(u), _) => u.into_pyobject(py)?.into_any(),
            (None, Some(i)) => i.into_pyobject(py)?.into_any(),
            _ => n.as_f64().unwrap_or(f64::NAN).into_pyobject(py)?.into_any(),
        },
        Value::String(s) => s.into_pyobject(py)?.into_any(),
        Value::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(object(py, item)?)?;
            }
            list.into_any()
        }
        Value::Object(map) => {
            let dict = PyDict::new(py);
            for (key, value) in map {
                dict.set_item(key, object(py, value)?)?;
            }
            dict.into_any()
        }
    })
}

/// A JSON array of numbers (nested, rectangular) as a NumPy float array of its shape, `null` as
/// NaN.
fn array<'py>(py: Python<'py>, value: &Value) -> PyResult<Bound<'py, PyAny>> {
    let mut shape = Vec::new();
    let mut v = value;
    while let Value::Array(items) = v {
        shape.push(items.len());
        match items.first() {
            Some(first) => v = first,
            None => break,
        }
    }
    let mut flat = Vec::new();
    flatten(value, &mut flat);
    let flat = PyArray1::from_vec(py, flat);
    flat.call_method1("reshape", (shape,))
}

fn flatten(value: &Value, out: &mut Vec<f64>) {
    match value {
        Value::Array(items) => items.iter().for_each(|v| flatten(v, out)),
        other => out.push(other.as_f64().unwrap_or(f64::NAN)),
    }
}

/// Raises each warning as a `UserWarning` with its message (an exception if the warnings are
/// turned into errors).
pub fn warn(py: Python<'_>, warnings: &[Warning]) -> PyResult<()> {
    let category = py.get_type::<PyUserWarning>();
    for w in warnings {
        let message = CString::new(w.message.replace('\0', " ")).expect("no NUL");
        PyErr::warn(py, category.as_any(), &message, 1)?;
    }
    Ok(())
}

/// How deep the dicts and lists of a document given to a function may nest: the documents
/// stiffid writes nest fewer than ten deep; a dict that holds itself nests without end.
const MAX_DEPTH: usize = 64;

/// A document of Python objects (dicts, lists, tuples, NumPy arrays, numbers, strings, None; an
/// object with `to_dict`) as JSON; NaN as null. An `InputError` (`document`) for anything else,
/// and for dicts and lists nested deeper than 64 (a dict that holds itself).
pub fn json(o: &Bound<'_, PyAny>) -> PyResult<Value> {
    json_within(o, MAX_DEPTH)
}

/// [`json`] of `o` nested at most `depth` deeper.
fn json_within(o: &Bound<'_, PyAny>, depth: usize) -> PyResult<Value> {
    let Some(depth) = depth.checked_sub(1) else {
        return Err(value(format!(
            "document: nested more than {MAX_DEPTH} deep (a dict or list that holds itself?)"
        )));
    };
    let json = |o: &Bound<'_, PyAny>| json_within(o, depth);
    if o.is_none() {
        return Ok(Value::Null);
    }
    if let Ok(b) = o.cast::<PyBool>() {
        return Ok(Value::Bool(b.is_true()));
    }
    if let Ok(i) = o.cast::<PyInt>() {
        return Ok(match i.extract::<i64>() {
            Ok(v) => Value::Number(v.into()),
            Err(_) => Value::Number(Number::from_f64(i.extract::<f64>()?).unwrap_or(0.into())),
        });
    }
    if let Ok(s) = o.cast::<PyString>() {
        return Ok(Value::String(s.to_string()));
    }
    if let Ok(d) = o.cast::<PyDict>() {
        let mut map = Map::new();
        for (k, v) in d.iter() {
            map.insert(k.str()?.to_string(), json(&v)?);
        }
        return Ok(Value::Object(map));
    }
    if o.cast::<PyList>().is_ok() || o.cast::<PyTuple>().is_ok() {
        return o
            .try_iter()?
            .map(|v| json(&v?))
            .collect::<PyResult<_>>()
            .map(Value::Array);
    }
    if o.cast::<PyFloat>().is_ok() || o.hasattr("__float__")? && !o.hasattr("tolist")? {
        return Ok(Number::from_f64(o.extract::<f64>()?).map_or(Value::Null, Value::Number));
    }
    for method in ["to_dict", "tolist"] {
        if o.hasattr(method)? {
            return json(&o.call_method0(method)?);
        }
    }
    Err(value(format!(
        "document: a {} is not part of a document",
        o.get_type().name()?
    )))
}
