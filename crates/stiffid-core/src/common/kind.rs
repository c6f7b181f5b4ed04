//! The `kind` key every JSON document carries first: what the document is, one name per document
//! and schema. Serde writes it (`#[serde(tag = "kind")]` on the document's struct); schemars
//! leaves a struct's tag out, so [`Kind`] puts it back into the schema.

use schemars::{json_schema, Schema};

/// The schema transform of a document's `kind`: a required string, always this name.
pub struct Kind(pub &'static str);

impl schemars::transform::Transform for Kind {
    fn transform(&mut self, schema: &mut Schema) {
        let kind = json_schema!({
            "description": "What the document is (one name per document and schema).",
            "type": "string",
            "const": self.0,
        });
        if let Some(p) = schema.get_mut("properties").and_then(|p| p.as_object_mut()) {
            p.insert("kind".into(), kind.into());
        }
        if let Some(r) = schema.get_mut("required").and_then(|r| r.as_array_mut()) {
            r.insert(0, "kind".into());
        }
    }
}
