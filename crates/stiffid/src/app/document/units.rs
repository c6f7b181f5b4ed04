//! The unit adapters: serde `serialize_with` functions that write a field held in SI units (m,
//! rad, nalgebra vectors) in the unit its key names (`_mm`, `_deg`), so that a report in SI
//! serialises straight to its document, with no twin struct in mm to copy it into.
//!
//! Each adapter converts as [`super::mm`] and the other helpers of [`crate::app::document`] do
//! (`v * 1e3`, `f64::to_degrees`), so a document written through an adapter has the same numbers,
//! to the bit, as one copied field by field. A field written through an adapter names the type
//! its JSON has for its schema, `#[cfg_attr(feature = "schema", schemars(with = "..."))]`; each
//! adapter's documentation says which.
//!
//! The documentation of a field written through an adapter (its schema's description too) says
//! the unit the field holds, then the one it is written in, after a colon, as the example's
//! `offset` does: `m, written in mm`, `rad, written in deg`, `no unit, written in plain numbers`
//! (a unit vector), `a choice, written in its name` (a choice).
//!
//! ```
//! # use serde::Serialize;
//! # use stiffid::app::document::units;
//! #[derive(Serialize)]
//! struct Probe {
//!     /// The probe's offset, base frame: m, written in mm.
//!     #[serde(rename = "offset_mm", serialize_with = "units::mm3")]
//!     // #[cfg_attr(feature = "schema", schemars(with = "[f64; 3]"))]
//!     offset: nalgebra::Vector3<f64>,
//! }
//! let json = serde_json::to_string(&Probe { offset: nalgebra::Vector3::new(0.5, 0.0, -0.25) });
//! assert_eq!(json.unwrap(), r#"{"offset_mm":[500.0,0.0,-250.0]}"#);
//! ```

use nalgebra::{Vector3, Vector6};
use serde::{Serialize, Serializer};
use stiffid_core::model::prediction::Interval;

/// What a serde serialiser returns.
pub(crate) type Written<S> = Result<<S as Serializer>::Ok, <S as Serializer>::Error>;

/// A length in m, written in mm. Schema: `f64`.
///
/// # Errors
/// The serialiser's.
pub fn mm<S: Serializer>(v: &f64, s: S) -> Written<S> {
    s.serialize_f64(super::mm(*v))
}

/// A length in m, written in mm, `null` when not finite. Schema: `Option<f64>`.
///
/// # Errors
/// The serialiser's.
pub fn mm_finite<S: Serializer>(v: &f64, s: S) -> Written<S> {
    super::finite(super::mm(*v)).serialize(s)
}

/// A length in m or none, written in mm or `null`. Schema: `Option<f64>`.
///
/// # Errors
/// The serialiser's.
pub fn mm_option<S: Serializer>(v: &Option<f64>, s: S) -> Written<S> {
    v.map(super::mm).serialize(s)
}

/// A length in m, written in mm as the user gave it: rounded to 12 significant digits where
/// that reads shorter ([`stiffid_core::common::words::as_given`]: a margin given as 0.9 mm,
/// held as 0.0009 m, is written `0.9`, not `0.9000000000000001`). Schema: `f64`.
///
/// # Errors
/// The serialiser's.
pub(crate) fn mm_as_given<S: Serializer>(v: &f64, s: S) -> Written<S> {
    s.serialize_f64(stiffid_core::common::words::as_given(super::mm(*v)))
}

/// Lengths in m or none, written in mm or `null` each. Schema: `Vec<Option<f64>>`.
///
/// # Errors
/// The serialiser's.
pub(crate) fn mm_option_each<S: Serializer>(v: &[Option<f64>], s: S) -> Written<S> {
    s.collect_seq(v.iter().map(|v| v.map(super::mm)))
}

/// Lengths in m, written in mm each. Schema: `Vec<f64>`.
///
/// # Errors
/// The serialiser's.
pub(crate) fn mm_each<S: Serializer>(v: &[f64], s: S) -> Written<S> {
    s.collect_seq(v.iter().map(|v| super::mm(*v)))
}

/// A vector in m, written as three numbers in mm. Schema: `[f64; 3]`.
///
/// # Errors
/// The serialiser's.
pub fn mm3<S: Serializer>(v: &Vector3<f64>, s: S) -> Written<S> {
    super::mm3(v).serialize(s)
}

/// A vector in m or none, written as three numbers in mm or `null`. Schema: `Option<[f64; 3]>`.
///
/// # Errors
/// The serialiser's.
pub fn mm3_option<S: Serializer>(v: &Option<Vector3<f64>>, s: S) -> Written<S> {
    v.as_ref().map(super::mm3).serialize(s)
}

/// Vectors in m, written as rows of three numbers in mm. Schema: `Vec<[f64; 3]>`.
///
/// # Errors
/// The serialiser's.
pub fn mm3_each<S: Serializer>(v: &[Vector3<f64>], s: S) -> Written<S> {
    s.collect_seq(v.iter().map(super::mm3))
}

/// An angle in rad, written in deg. Schema: `f64`.
///
/// # Errors
/// The serialiser's.
pub fn deg<S: Serializer>(v: &f64, s: S) -> Written<S> {
    s.serialize_f64(v.to_degrees())
}

/// An angle in rad, written in mrad (`v * 1e3`). Schema: `f64`.
///
/// # Errors
/// The serialiser's.
pub fn mrad<S: Serializer>(v: &f64, s: S) -> Written<S> {
    s.serialize_f64(v * 1e3)
}

/// A posture's axis angles q1..q6 in rad, written as six numbers in deg. Schema: `[f64; 6]`.
///
/// # Errors
/// The serialiser's.
pub fn deg6<S: Serializer>(q: &Vector6<f64>, s: S) -> Written<S> {
    <[f64; 6]>::from(q.map(f64::to_degrees)).serialize(s)
}

/// Postures' axis angles in rad, written as rows of six numbers in deg.
/// Schema: `Vec<[f64; 6]>`.
///
/// # Errors
/// The serialiser's.
pub fn deg6_each<S: Serializer>(postures: &[Vector6<f64>], s: S) -> Written<S> {
    super::degrees(postures).serialize(s)
}

/// A prediction interval in m or none, written in mm, `[lower, upper]` per coordinate with
/// `null` for an unbounded end, or `null`. Schema:
/// `Option<[[Option<f64>; 2]; 3]>`.
///
/// # Errors
/// The serialiser's.
pub fn interval_mm<S: Serializer>(v: &Option<Interval>, s: S) -> Written<S> {
    v.map(super::interval_mm).serialize(s)
}

/// Seven lengths in m (the base's and links 1-6's) or none, written as seven numbers in mm or
/// `null`. Schema: `Option<[f64; 7]>`.
///
/// # Errors
/// The serialiser's.
pub(crate) fn mm7_option<S: Serializer>(v: &Option<[f64; 7]>, s: S) -> Written<S> {
    v.map(|v| v.map(super::mm)).serialize(s)
}

/// A unit vector (no unit), written as three numbers. Schema: `[f64; 3]`.
///
/// # Errors
/// The serialiser's.
pub(crate) fn plain3<S: Serializer>(v: &Vector3<f64>, s: S) -> Written<S> {
    <[f64; 3]>::from(*v).serialize(s)
}

/// A choice (a criterion, a purpose, ...) written as its name (`relative-a`). Schema: one of
/// its names (`schema_with`, e.g. `app::document::schema::one_of`, behind the `schema` feature).
///
/// # Errors
/// The serialiser's.
pub(crate) fn name<S: Serializer, T: stiffid_core::common::choice::Choice>(
    v: &T,
    s: S,
) -> Written<S> {
    s.serialize_str(v.name())
}

/// An angle in rad or none, written in mrad (`v * 1e3`) or `null`. Schema: `Option<f64>`.
///
/// # Errors
/// The serialiser's.
pub(crate) fn mrad_option<S: Serializer>(v: &Option<f64>, s: S) -> Written<S> {
    v.map(|v| v * 1e3).serialize(s)
}

/// An angle in rad or none, written in deg or `null`. Schema: `Option<f64>`.
///
/// # Errors
/// The serialiser's.
pub(crate) fn deg_option<S: Serializer>(v: &Option<f64>, s: S) -> Written<S> {
    v.map(f64::to_degrees).serialize(s)
}

/// A length in m or none, written in mm, `null` when none or not finite. Schema: `Option<f64>`.
///
/// # Errors
/// The serialiser's.
pub(crate) fn mm_finite_option<S: Serializer>(v: &Option<f64>, s: S) -> Written<S> {
    v.and_then(|v| super::finite(super::mm(v))).serialize(s)
}

/// A length in m, written in um (`v * 1e6`). Schema: `f64`.
///
/// # Errors
/// The serialiser's.
pub(crate) fn um<S: Serializer>(v: &f64, s: S) -> Written<S> {
    s.serialize_f64(v * 1e6)
}

/// An angle in rad, written in urad (`v * 1e6`). Schema: `f64`.
///
/// # Errors
/// The serialiser's.
pub(crate) fn urad<S: Serializer>(v: &f64, s: S) -> Written<S> {
    s.serialize_f64(v * 1e6)
}

/// Two angles in rad (a range), written as two numbers in deg. Schema: `[f64; 2]`.
///
/// # Errors
/// The serialiser's.
pub(crate) fn deg2<S: Serializer>(v: &[f64; 2], s: S) -> Written<S> {
    v.map(f64::to_degrees).serialize(s)
}
