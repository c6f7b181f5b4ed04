//! The output documents of the jobs: the JSON (and CSV) that stiffid writes, built from the jobs'
//! reports ([`crate::app`]), one module per job.
//!
//! Every document is a plain serde type: units in every key (`stiffness_nm_per_rad`,
//! `residual_mm`), SI values converted to the units of the files (mm, deg, N) here and nowhere
//! else, and `Option` (`null` in JSON) where a value is missing or not finite, never `NaN`. With the
//! `schema` feature every document derives `schemars::JsonSchema`: the command line's hidden
//! `stiffid schema NAME` prints it, and `docs/schemas/` holds them (a test keeps them equal).
//!
//! The command line writes these documents as they are (`--json`, `--out`); the Python package
//! turns the same documents into dicts (and arrays where its API promises arrays), so the two
//! front ends give the same document for the same call.

pub mod feasibility;
pub mod parameters;

/// `v` if finite, else `None`.
pub fn finite(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

/// [`finite`] of each of `values`.
pub fn finite_each<const N: usize>(values: impl Into<[f64; N]>) -> [Option<f64>; N] {
    values.into().map(finite)
}

/// A length in m, in mm.
pub fn mm(v: f64) -> f64 {
    v * 1e3
}

/// Axis angles (rad) of a group as rows of degrees, q1..q6.
pub fn degrees(postures: &[nalgebra::Vector6<f64>]) -> Vec<[f64; 6]> {
    let row = |q: &nalgebra::Vector6<f64>| std::array::from_fn(|a| q[a].to_degrees());
    postures.iter().map(row).collect()
}

/// `text` as one CSV field: quoted (quotes doubled) when it holds a comma, quote or line break.
pub fn csv_field(text: &str) -> String {
    match text.contains([',', '"', '\n', '\r']) {
        true => format!("\"{}\"", text.replace('"', "\"\"")),
        false => text.to_string(),
    }
}
