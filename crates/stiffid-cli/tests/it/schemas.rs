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
