//! `stiffid.figures`: the figures of a calibration or identification as SVG strings, drawn from
//! its document by the same code as the command's reports ([`stiffid_figures`]), no Matplotlib.

use crate::error::value;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use serde_json::{Map, Number, Value};

/// The figures of ``document``: a calibration's (the dict ``calibrate(...)`` returns) or an
/// identification's (the dict ``identify(...)`` returns, or the
/// model comparison's dict), as a dict of SVG documents (str) keyed by the figure's name, in the
/// order ``calibrate --report`` and ``identify --report`` show them: for a calibration
/// ``errors`` (each reading's error before and after, held-out readings marked), ``residuals``
/// (their distribution against the tracker's noise) and ``parameters_<unit>`` (fitted minus
/// nominal with 95% intervals); for an identification (the six drives or a model with virtual
/// springs) ``measured`` (each measured displacement coordinate against the predicted one),
/// ``parameters`` (each parameter's 95% interval, % of its stiffness), ``qq`` (the residuals'
/// normal QQ plot against the noise), ``folds`` (with cross-validation: each fold's stiffness against the full
/// fit's), ``prediction`` (the held-out scores of the prediction intervals) or, for a model
/// comparison, ``models`` (held-out shares with one standard error). Show one in Jupyter with
/// ``IPython.display.SVG(svg)``. ``InputError`` when ``document`` is neither.
#[pyfunction]
pub fn figures<'py>(py: Python<'py>, document: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyDict>> {
    let doc = json(document)?;
    let drawn = match doc.get("geometry").is_some() && doc.get("errors").is_some() {
        true => stiffid_figures::calibrate::figures(&doc),
        false => stiffid_figures::identify::figures(&doc),
    }
    .map_err(|e| value(format!("document: {e}")))?;
    let out = PyDict::new(py);
    for f in drawn {
        let svg = py
            .detach(|| stiffid_figures::svg(&f.chart))
            .map_err(|e| value(e.to_string()))?;
        out.set_item(f.name, svg)?;
    }
    Ok(out)
}

/// A document of Python objects (dicts, lists, tuples, NumPy arrays, numbers, strings, None; an
/// object with `to_dict`) as JSON; NaN as null.
pub fn json(o: &Bound<'_, PyAny>) -> PyResult<Value> {
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
