//! The JSON Schemas in `docs/schemas/`: each is what `stiffid schema NAME` generates from the
//! types that write the document. That each validates the real output of its command, and rejects
//! it with a key missing or an unknown key added, is checked by the Python tests
//! (`crates/stiffid-py/tests/test_schemas.py`, with the reference validator).

use std::path::{Path, PathBuf};

use crate::common;

use common::stiffid;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn schema_path(name: &str) -> PathBuf {
    repo().join(format!("docs/schemas/{name}.schema.json"))
}

/// The names `stiffid schema` lists.
fn names() -> Vec<String> {
    let out = stiffid(&["schema"]);
    common::assert_success(&out);
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| l.split_whitespace().next().unwrap().to_string())
        .collect()
}

#[test]
fn the_shipped_schemas_are_the_generated_ones() {
    let names = names();
    assert!(names.len() >= 10, "{names:?}");
    for name in &names {
        let out = stiffid(&["schema", name]);
        common::assert_success(&out);
        let shipped = std::fs::read(schema_path(name)).unwrap_or_default();
        assert!(
            shipped == out.stdout,
            "docs/schemas/{name}.schema.json is not what `stiffid schema {name}` generates; \
             regenerate it with: cargo run --release -p stiffid-cli -- schema {name} > docs/schemas/{name}.schema.json"
        );
    }
    let mut shipped: Vec<String> = std::fs::read_dir(repo().join("docs/schemas"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    shipped.sort();
    let mut expected: Vec<String> = names.iter().map(|n| format!("{n}.schema.json")).collect();
    expected.sort();
    assert_eq!(
        shipped, expected,
        "docs/schemas holds a schema stiffid does not generate"
    );
}

/// Every document says what it is: its schema requires `kind`, one name per document (the
/// schema's name; each of identify's three forms its own), so no union is told apart by its
/// keys. The stiffness file's schema, of what is read, does not require it.
#[test]
fn every_document_has_a_kind() {
    let mut kinds = Vec::new();
    for name in names().iter().filter(|n| *n != "stiffness") {
        let text = std::fs::read_to_string(schema_path(name)).unwrap();
        let schema: serde_json::Value = serde_json::from_str(&text).unwrap();
        let forms: Vec<&serde_json::Value> = match schema["anyOf"].as_array() {
            Some(forms) => (forms.iter())
                .map(|f| {
                    &schema["$defs"][f["$ref"].as_str().unwrap().trim_start_matches("#/$defs/")]
                })
                .collect(),
            None => vec![&schema],
        };
        for form in forms {
            let kind = form["properties"]["kind"]["const"].as_str();
            let kind = kind
                .unwrap_or_else(|| panic!("{name}: no kind"))
                .to_string();
            assert!(
                kind == *name || kind.starts_with(&format!("{name}-")),
                "{name}: {kind}"
            );
            assert_eq!(form["required"][0], "kind", "{name}");
            kinds.push(kind);
        }
    }
    let mut unique = kinds.clone();
    unique.sort();
    unique.dedup();
    assert_eq!(unique.len(), kinds.len(), "{kinds:?}");
    assert_eq!(kinds.len(), 18, "{kinds:?}");
    // The file `calibrate --stiffness-out` writes (the document's `stiffness_file`) is the
    // stiffness file's one type, which names itself (`kind`, optional: the reader takes a file
    // without it, as written before).
    let text = std::fs::read_to_string(schema_path("calibrate")).unwrap();
    let schema: serde_json::Value = serde_json::from_str(&text).unwrap();
    let file = &schema["$defs"]["StiffnessFile"];
    assert_eq!(
        file["properties"]["kind"]["anyOf"][0]["$ref"],
        "#/$defs/FileKind"
    );
    let kinds = &schema["$defs"]["FileKind"]["oneOf"];
    assert_eq!(kinds[0]["const"], "stiffness");
    assert_eq!(
        keys("stiffness", None),
        keys("calibrate", Some("StiffnessFile"))
    );
}

/// The top-level keys of the shipped schema `name`, or of its definition `def`.
fn keys(name: &str, def: Option<&str>) -> std::collections::BTreeSet<String> {
    let text = std::fs::read_to_string(schema_path(name)).unwrap();
    let schema: serde_json::Value = serde_json::from_str(&text).unwrap();
    let object = match def {
        Some(d) => &schema["$defs"][d],
        None => &schema,
    };
    let properties = object["properties"].as_object();
    properties.unwrap_or_else(|| panic!("{name} {def:?}: no properties"));
    properties.unwrap().keys().cloned().collect()
}

/// A stiffness file is what `identify --out` and `calibrate --stiffness-out` write: every key of
/// the identify documents (over the drives and over a model with virtual springs) and of the
/// calibration's stiffness file is one the stiffness file reads or ignores
/// (`stiffid::internal::io::stiffness::DOCUMENT_KEYS`), else the files they write would be refused as
/// holding an unknown key; and every key ignored is one they write.
#[test]
fn a_stiffness_file_reads_every_key_the_documents_write() {
    // The identify schema's forms: the six drives, a model with virtual springs (then the
    // comparison, which writes a `[model]` fragment, not a stiffness file).
    let text = std::fs::read_to_string(schema_path("identify")).unwrap();
    let schema: serde_json::Value = serde_json::from_str(&text).unwrap();
    let forms: Vec<&str> = (schema["anyOf"].as_array().unwrap().iter())
        .map(|f| f["$ref"].as_str().unwrap().trim_start_matches("#/$defs/"))
        .collect();
    assert_eq!(forms.len(), 3, "{forms:?}");
    let mut written = keys("identify", Some(forms[0]));
    written.extend(keys("identify", Some(forms[1])));
    written.extend(keys("calibrate", Some("StiffnessFile")));
    let mut read = keys("stiffness", None);
    let ignored = ::stiffid::internal::io::stiffness::DOCUMENT_KEYS;
    read.extend(ignored.iter().map(|k| k.to_string()));
    let refused: Vec<_> = written.difference(&read).collect();
    assert!(
        refused.is_empty(),
        "keys the documents write that a stiffness file refuses: {refused:?} (add them to DOCUMENT_KEYS)"
    );
    let stale: Vec<_> = (ignored.iter())
        .filter(|k| !written.contains(**k))
        .collect();
    assert!(
        stale.is_empty(),
        "DOCUMENT_KEYS no document writes: {stale:?}"
    );
    let both: Vec<_> = (ignored.iter())
        .filter(|k| keys("stiffness", None).contains(**k))
        .collect();
    assert!(both.is_empty(), "keys both read and ignored: {both:?}");
}

/// The force document, which had none, names itself in its first key as every other does.
#[test]
fn the_force_document_names_itself_first() {
    let process = repo().join("examples/milling/aluminium.toml");
    let out = stiffid(&[
        "force",
        "--process",
        &process.display().to_string(),
        "--json",
    ]);
    common::assert_success(&out);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.starts_with("{\n  \"kind\": \"force\","), "{text}");
    let doc: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert!(!doc["operations"].as_array().unwrap().is_empty(), "{doc}");
}
