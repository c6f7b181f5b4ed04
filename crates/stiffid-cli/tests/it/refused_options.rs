//! Every option combination the library refuses with a typed option error, through the command:
//! exit 2, one line, the library's message with each option spelled as its flag. The table is
//! shared with the Python tests (`crates/stiffid-py/tests/test_refused_options.py`), which run
//! the same combinations through Python and expect the same message with each option spelled as
//! its keyword.

use crate::common::{assert_usage_error, fanuc_csv, stiffid, temp_dir};
use serde_json::Value;
use std::path::Path;

const TABLE: &str = include_str!("../../../stiffid/tests/data/refused_options.json");

/// `template` with every `{name}` spelled by `spell`.
pub fn render(template: &str, spell: impl Fn(&str) -> String) -> String {
    let mut out = String::new();
    let mut rest = template;
    while let Some(open) = rest.find('{') {
        let close = open + rest[open..].find('}').expect("a closing brace");
        out += &rest[..open];
        out += &spell(&rest[open + 1..close]);
        rest = &rest[close + 1..];
    }
    out + rest
}

fn example(path: &str) -> String {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(path);
    p.to_str().unwrap().to_string()
}

#[test]
fn every_refused_option_combination_is_the_librarys_typed_error() {
    let table: Value = serde_json::from_str(TABLE).unwrap();
    let dir = temp_dir("refused-options");
    let group: String = std::iter::once("posture,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg".into())
        .chain(
            (table["group"].as_array().unwrap().iter().enumerate()).map(|(i, q)| {
                let q: Vec<String> = q
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|v| v.to_string())
                    .collect();
                format!("{},{}", i + 1, q.join(","))
            }),
        )
        .collect::<Vec<_>>()
        .join("\n");
    let group_file = dir.join("group.csv");
    std::fs::write(&group_file, group + "\n").unwrap();
    let out = dir.join("out.csv");
    let places = [
        ("{fanuc_data}", fanuc_csv().to_str().unwrap().to_string()),
        ("{milling_stiffness}", example("milling/stiffness.json")),
        ("{group}", group_file.to_str().unwrap().to_string()),
        ("{out}", out.to_str().unwrap().to_string()),
    ];
    let refused = table["refused"].as_array().unwrap();
    assert!(refused.len() >= 30, "{}", refused.len());
    for case in refused {
        let args: Vec<String> = (case["cli"].as_array().unwrap().iter())
            .map(|a| {
                let a = a.as_str().unwrap();
                (places.iter())
                    .find(|(p, _)| *p == a)
                    .map_or(a.to_string(), |(_, v)| v.clone())
            })
            .collect();
        let refs: Vec<&str> = args.iter().map(String::as_str).collect();
        let expected = render(case["error"].as_str().unwrap(), |name| {
            format!("--{}", name.replace('_', "-"))
        });
        let line = assert_usage_error(&stiffid(&refs), &[]);
        assert_eq!(line.trim_end(), format!("error: {expected}"), "{args:?}");
        assert!(!out.exists(), "{args:?} wrote {}", out.display());
    }
}
