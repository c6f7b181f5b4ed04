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

pub mod candidates;
pub mod feasibility;
pub mod group;
pub(crate) mod mass;
pub mod parameters;
pub(crate) mod transform;
// Not API: the documents' own adapters, public for their test in tests/it (this crate has no
// unit-test harness) and hidden from the documented API.
#[doc(hidden)]
pub mod units;

pub use stiffid_view as scene;

/// The JSON Schemas of the documents' fields that hold one of a choice's names.
#[cfg(feature = "schema")]
pub(crate) mod schema {
    use schemars::{json_schema, Schema};
    use stiffid_core::common::choice::{names, Choice};

    pub(crate) use stiffid_core::common::kind::Kind;

    /// A string that is one of `T`'s names.
    pub(crate) fn one_of<T: Choice>() -> Schema {
        json_schema!({ "type": "string", "enum": names::<T>() })
    }
}

/// A stiffness criterion's name (`relative-a`, ...), as a JSON Schema.
#[cfg(feature = "schema")]
pub(crate) fn criterion(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
    schema::one_of::<stiffid_design::Criterion>()
}

/// `v` if finite, else `None`.
pub fn finite(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

/// [`finite`] of each of `values`.
pub(crate) fn finite_each<const N: usize>(values: impl Into<[f64; N]>) -> [Option<f64>; N] {
    values.into().map(finite)
}

/// A matrix as an array of rows.
pub(crate) fn rows<const R: usize, const C: usize>(
    m: &nalgebra::SMatrix<f64, R, C>,
) -> [[f64; C]; R] {
    std::array::from_fn(|r| std::array::from_fn(|c| m[(r, c)]))
}

/// A length in m, in mm.
pub fn mm(v: f64) -> f64 {
    v * 1e3
}

/// A prediction interval (m) in mm, `null` for an unbounded end.
pub(crate) fn interval_mm(
    interval: stiffid_core::model::prediction::Interval,
) -> [[Option<f64>; 2]; 3] {
    interval.map(|c| c.map(|v| finite(mm(v))))
}

/// A vector in m, in mm.
pub fn mm3(v: &nalgebra::Vector3<f64>) -> [f64; 3] {
    [mm(v.x), mm(v.y), mm(v.z)]
}

/// Axis angles (rad) of a group as rows of degrees, q1..q6.
pub(crate) fn degrees(postures: &[nalgebra::Vector6<f64>]) -> Vec<[f64; 6]> {
    let row = |q: &nalgebra::Vector6<f64>| std::array::from_fn(|a| q[a].to_degrees());
    postures.iter().map(row).collect()
}

/// A CSV text of `header` and `rows` (fields as they are, each row one record) written by
/// [`csv::Writer`]: a field is quoted, its quotes doubled, when it holds a comma, quote or line
/// break; lines end in `\n`. Not API: public for its test in tests/it, hidden.
#[doc(hidden)]
pub fn csv_text<R, F>(header: &[String], rows: R) -> String
where
    R: IntoIterator<Item = F>,
    F: IntoIterator<Item = String>,
{
    let mut w = csv::WriterBuilder::new()
        .flexible(true)
        .from_writer(Vec::new());
    // Into memory, with rows of any length (`flexible`): no write can fail.
    w.write_record(header).expect("writing to memory");
    for row in rows {
        w.write_record(row).expect("writing to memory");
    }
    let bytes = w.into_inner().expect("writing to memory");
    String::from_utf8(bytes).expect("fields are UTF-8")
}
