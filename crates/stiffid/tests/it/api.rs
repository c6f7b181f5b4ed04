//! The facade's API is the listed one: `crates/stiffid/public-api.txt`, generated from rustdoc's
//! JSON by `crates/stiffid/tools/public_api.py`, names every item a program linking `stiffid`
//! can name, and a change to the `pub` items of the files they are declared in is a change of
//! that listing (docs/ARCHITECTURE.md, "Public surface").

use std::path::{Path, PathBuf};

/// The most items the API may list.
const MAX_ITEMS: usize = 700;

/// What `public_api.py` counts as declaring an item (a field is not one).
const ITEMS: [&str; 12] = [
    "fn ",
    "struct ",
    "enum ",
    "trait ",
    "type ",
    "const ",
    "static ",
    "mod ",
    "use ",
    "unsafe fn ",
    "async fn ",
    "const fn ",
];

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn declares(line: &str) -> bool {
    line.strip_prefix("pub ")
        .is_some_and(|rest| ITEMS.iter().any(|item| rest.starts_with(item)))
}

/// FNV-1a, 64 bits (the tool's).
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// The fingerprint of the `pub` item lines of `files` (relative to the repository).
fn fingerprint(files: &[&str]) -> String {
    let mut lines: Vec<String> = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(root().join(file))
            .unwrap_or_else(|e| panic!("{file}, listed in public-api.txt: {e}"));
        lines.extend(
            (text.lines().map(str::trim))
                .filter(|l| declares(l))
                .map(String::from),
        );
    }
    lines.sort();
    format!("{:016x}", fnv1a(lines.join("\n").as_bytes()))
}

#[test]
fn the_public_api_is_the_listed_one() {
    let listing = std::fs::read_to_string(root().join("crates/stiffid/public-api.txt")).unwrap();
    let files: Vec<&str> = listing
        .lines()
        .filter_map(|l| l.strip_prefix("# source "))
        .collect();
    let recorded = (listing.lines())
        .filter_map(|l| l.strip_prefix("# fingerprint "))
        .find(|f| f.len() == 16 && f.chars().all(|c| c.is_ascii_hexdigit()))
        .expect("public-api.txt records a fingerprint");
    assert!(files.contains(&"crates/stiffid/src/lib.rs"), "{files:?}");
    assert_eq!(
        fingerprint(&files),
        recorded,
        "a `pub` item of the API's files changed: generate crates/stiffid/public-api.txt again \
         (crates/stiffid/tools/public_api.py says how) and review what the API gained or lost"
    );
    let items: Vec<&str> = listing.lines().filter(|l| !l.starts_with('#')).collect();
    assert!(items.len() <= MAX_ITEMS, "{} items", items.len());
    for item in &items {
        let (kind, path) = item.split_once(' ').expect("kind and path");
        assert!(
            (path == "stiffid" || path.starts_with("stiffid::")) && !kind.is_empty(),
            "{item}"
        );
        assert!(
            !path.contains("::internal::"),
            "{item}: the hidden module is no API"
        );
    }
}

#[test]
fn the_fingerprint_sees_items_not_fields() {
    assert!(declares(
        "pub fn run(request: &Request) -> Result<Outcome> {"
    ));
    assert!(declares("pub use stiffid_core::setup::builtin;"));
    assert!(!declares("pub seed: u64,") && !declares("pub(crate) fn hidden() {}"));
    // FNV-1a's published test vector.
    assert_eq!(fnv1a(b"a"), 0xaf63_dc4c_8601_ec8c);
}

#[test]
fn the_front_ends_reach_the_library_through_the_facade_only() {
    for front in ["stiffid-cli", "stiffid-py"] {
        let manifest =
            std::fs::read_to_string(root().join(format!("crates/{front}/Cargo.toml"))).unwrap();
        for science in [
            "core",
            "metrology",
            "identify",
            "design",
            "machining",
            "view",
        ] {
            let name = format!("stiffid-{science}");
            assert!(
                !manifest.lines().any(|l| l.trim_start().starts_with(&name)),
                "{front} depends on {name}: reach it through `stiffid::internal`"
            );
            let manifest = std::fs::read_to_string(
                root().join(format!("crates/stiffid-{science}/Cargo.toml")),
            )
            .unwrap();
            assert!(
                manifest.lines().any(|l| l.trim() == "publish = false"),
                "{name} is internal: publish = false"
            );
        }
    }
}
