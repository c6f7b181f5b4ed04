//! NumPy arrays in and out: shapes checked with messages naming the argument, degrees and
//! millimetres at the boundary.

use crate::error::value;
use nalgebra::{Vector3, Vector6};
use numpy::ndarray::{Array2, Array3};
use numpy::{AllowTypeChange, IntoPyArray, PyArray1, PyArray2, PyArray3, PyArrayLikeDyn};
use pyo3::prelude::*;
use stiffid::internal::common::limits::{self, JointBox};
use stiffid::internal::common::words::number;

/// Rows of `N` numbers from an array-like of shape `(N,)` (one row, `single`) or `(n, N)`.
pub struct Rows<const N: usize> {
    /// The rows, in order.
    pub rows: Vec<[f64; N]>,
    /// Whether the input was one row of shape `(N,)`.
    pub single: bool,
}

/// Reads `obj` (any array-like of numbers) as [`Rows`]; `what` names the argument in errors.
/// Refuses another shape, and a NaN or infinite value (naming its row and column).
pub fn rows<const N: usize>(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Rows<N>> {
    let expected = format!("expected an array of shape ({N},) or (n, {N})");
    let array: PyArrayLikeDyn<'_, f64, AllowTypeChange> = obj
        .extract()
        .map_err(|_| value(format!("{what}: {expected} of numbers")))?;
    let view = array.as_array();
    let single = match view.shape() {
        [c] if *c == N => true,
        [_, c] if *c == N => false,
        shape => {
            let dims: Vec<String> = shape.iter().map(usize::to_string).collect();
            let got = match dims.len() {
                1 => format!("({},)", dims[0]),
                _ => format!("({})", dims.join(", ")),
            };
            return Err(value(format!("{what}: {expected}, got shape {got}")));
        }
    };
    let flat: Vec<f64> = view.iter().copied().collect();
    let rows: Vec<[f64; N]> = flat
        .chunks_exact(N)
        .map(|c| std::array::from_fn(|i| c[i]))
        .collect();
    for (r, row) in rows.iter().enumerate() {
        if let Some(c) = row.iter().position(|v| !v.is_finite()) {
            return Err(value(format!(
                "{what}[{r}, {c}] = {} is not a finite number",
                row[c]
            )));
        }
    }
    Ok(Rows { rows, single })
}

/// Exactly one row of `N` numbers (shape `(N,)`), each within `range`.
pub fn vector<const N: usize>(
    obj: &Bound<'_, PyAny>,
    what: &str,
    range: &limits::Range,
) -> PyResult<[f64; N]> {
    let r = rows::<N>(obj, what)?;
    if !r.single {
        return Err(value(format!("{what}: expected an array of shape ({N},)")));
    }
    limits::check(what, &r.rows[0], range).map_err(crate::error::raise)?;
    Ok(r.rows[0])
}

/// Exactly `n` finite numbers (shape `(n,)`); `what` names the argument in errors.
pub fn values(obj: &Bound<'_, PyAny>, what: &str, n: usize) -> PyResult<Vec<f64>> {
    let array: PyArrayLikeDyn<'_, f64, AllowTypeChange> = obj.extract().map_err(|_| {
        value(format!(
            "{what}: expected an array of shape ({n},) of numbers"
        ))
    })?;
    let view = array.as_array();
    if view.shape() != [n] {
        return Err(value(format!(
            "{what}: expected an array of shape ({n},), got shape {:?}",
            view.shape()
        )));
    }
    let v: Vec<f64> = view.iter().copied().collect();
    if let Some(i) = v.iter().position(|x| !x.is_finite()) {
        return Err(value(format!(
            "{what}[{i}] = {} is not a finite number",
            v[i]
        )));
    }
    Ok(v)
}

/// An `n x n` matrix of numbers (shape `(n, n)`); `what` names the argument in errors.
pub fn square(obj: &Bound<'_, PyAny>, what: &str, n: usize) -> PyResult<nalgebra::DMatrix<f64>> {
    let array: PyArrayLikeDyn<'_, f64, AllowTypeChange> = obj
        .extract()
        .map_err(|_| value(format!("{what}: expected a ({n}, {n}) array of numbers")))?;
    let view = array.as_array();
    if view.shape() != [n, n] {
        return Err(value(format!(
            "{what}: expected a ({n}, {n}) array, got shape {:?}",
            view.shape()
        )));
    }
    Ok(nalgebra::DMatrix::from_fn(n, n, |r, c| view[[r, c]]))
}

/// Postures in degrees (rows of six axis angles) as radians, each within the box `limits`
/// (`within` names it, e.g. "the setup's bounds"), at most `max` postures.
pub fn postures(
    obj: &Bound<'_, PyAny>,
    what: &str,
    (limits, within): (&JointBox, &str),
    max: usize,
) -> PyResult<(Vec<Vector6<f64>>, bool)> {
    let r = rows::<6>(obj, what)?;
    if r.rows.is_empty() || r.rows.len() > max {
        return Err(value(format!(
            "{what}: expected 1 to {max} postures, got {}",
            r.rows.len()
        )));
    }
    let mut out = Vec::with_capacity(r.rows.len());
    for (i, row) in r.rows.iter().enumerate() {
        let q = Vector6::from_iterator(row.iter().map(|d| d.to_radians()));
        if let Some(v) = limits.first_violation(&q) {
            return Err(value(format!(
                "{what}: posture {i}, q{}_deg = {} is outside {within} [{:.1}, {:.1}]",
                v.axis + 1,
                number(row[v.axis]),
                v.lower.to_degrees(),
                v.upper.to_degrees()
            )));
        }
        out.push(q);
    }
    Ok((out, r.single))
}

/// A vector as a 1-D array.
pub fn vec1<'py>(py: Python<'py>, v: impl IntoIterator<Item = f64>) -> Bound<'py, PyArray1<f64>> {
    v.into_iter().collect::<Vec<f64>>().into_pyarray(py)
}

/// Counts or line numbers as a 1-D integer array (`int64`, NumPy's default integer).
pub fn integers<'py>(
    py: Python<'py>,
    v: impl IntoIterator<Item = u64>,
) -> Bound<'py, PyArray1<i64>> {
    let saturated = v.into_iter().map(|n| i64::try_from(n).unwrap_or(i64::MAX));
    saturated.collect::<Vec<i64>>().into_pyarray(py)
}

/// Rows of `N` as an `(n, N)` array.
pub fn table<'py, const N: usize>(py: Python<'py>, rows: &[[f64; N]]) -> Bound<'py, PyArray2<f64>> {
    Array2::from_shape_fn((rows.len(), N), |(r, c)| rows[r][c]).into_pyarray(py)
}

/// An `(rows, columns)` array of `entry(row, column)`.
pub fn grid<'py>(
    py: Python<'py>,
    rows: usize,
    columns: usize,
    entry: impl Fn(usize, usize) -> f64,
) -> Bound<'py, PyArray2<f64>> {
    Array2::from_shape_fn((rows, columns), |(r, c)| entry(r, c)).into_pyarray(py)
}

/// Postures (rad) as an `(n, 6)` array of degrees.
pub fn degrees<'py>(py: Python<'py>, postures: &[Vector6<f64>]) -> Bound<'py, PyArray2<f64>> {
    Array2::from_shape_fn((postures.len(), 6), |(r, c)| postures[r][c].to_degrees())
        .into_pyarray(py)
}

/// Points (m) as an `(n, 3)` array of millimetres.
pub fn millimetres<'py>(py: Python<'py>, points: &[Vector3<f64>]) -> Bound<'py, PyArray2<f64>> {
    Array2::from_shape_fn((points.len(), 3), |(r, c)| points[r][c] * 1e3).into_pyarray(py)
}

/// Square matrices of size `N` (given by a function of the index, row, column) as an `(n, N, N)`
/// array.
pub fn stack<'py, const N: usize>(
    py: Python<'py>,
    n: usize,
    entry: impl Fn(usize, usize, usize) -> f64,
) -> Bound<'py, PyArray3<f64>> {
    Array3::from_shape_fn((n, N, N), |(k, r, c)| entry(k, r, c)).into_pyarray(py)
}
