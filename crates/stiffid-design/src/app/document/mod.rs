//! The documents' parts that speak of the design: a group of postures with its scores
//! ([`group`]) and the model comparison's candidates ([`candidates`]).

pub mod candidates;
pub mod group;

/// A stiffness criterion's name (`relative-a`, ...), as a JSON Schema.
#[cfg(feature = "schema")]
pub(crate) fn criterion(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
    stiffid_core::app::document::schema::one_of::<crate::Criterion>()
}
