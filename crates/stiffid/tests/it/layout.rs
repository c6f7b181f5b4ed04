//! The library's layout by pipeline stage (docs/ARCHITECTURE.md): at most 16 entries at the
//! root of `src/`, and no import circle between its top-level modules (a module's code, outside
//! comments and tests, names `crate::OTHER` only for modules below it).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// The `.rs` files under `dir`, test modules left out.
fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if path.is_dir() {
            if name != "tests" {
                sources(&path, out);
            }
        } else if name.ends_with(".rs") && name != "tests.rs" {
            out.push(path);
        }
    }
}

/// The top-level modules a module's code names (`crate::NAME`), outside comments and
/// `#[cfg(test)]` items (everything after the first is left out: test modules come last).
fn imports(module: &Path, tops: &BTreeSet<String>) -> BTreeSet<String> {
    let own = module.file_name().unwrap().to_string_lossy().into_owned();
    let mut files = Vec::new();
    sources(module, &mut files);
    let mut found = BTreeSet::new();
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        let code = text.split("#[cfg(test)]").next().unwrap();
        for line in code.lines().filter(|l| !l.trim_start().starts_with("//")) {
            for (at, _) in line.match_indices("crate::") {
                let name: String = line[at + 7..]
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                if tops.contains(&name) && name != own {
                    found.insert(name);
                }
            }
            // `use crate::{a::.., b::..}`: every group member at the top.
            if let Some(group) = line.trim_start().strip_prefix("use crate::{") {
                for part in group.split(',') {
                    let name = part.trim().split("::").next().unwrap_or("").to_string();
                    if tops.contains(&name) && name != own {
                        found.insert(name);
                    }
                }
            }
        }
    }
    found
}

fn top_modules() -> BTreeSet<String> {
    std::fs::read_dir(src())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir())
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect()
}

#[test]
fn the_root_holds_at_most_sixteen_entries() {
    let entries = std::fs::read_dir(src()).unwrap().count();
    assert!(entries <= 16, "{entries} entries at the library's root");
    assert!(top_modules().len() >= 10, "the stages are directories");
}

/// A depth-first search for a circle in the import graph; returns one if there is any.
fn circle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn visit(
        node: &str,
        graph: &BTreeMap<String, BTreeSet<String>>,
        path: &mut Vec<String>,
        done: &mut BTreeSet<String>,
    ) -> Option<Vec<String>> {
        if let Some(at) = path.iter().position(|n| n == node) {
            return Some(path[at..].to_vec());
        }
        if done.contains(node) {
            return None;
        }
        path.push(node.to_string());
        for next in &graph[node] {
            if let Some(c) = visit(next, graph, path, done) {
                return Some(c);
            }
        }
        path.pop();
        done.insert(node.to_string());
        None
    }
    let mut done = BTreeSet::new();
    graph
        .keys()
        .find_map(|n| visit(n, graph, &mut Vec::new(), &mut done))
}

#[test]
fn no_import_circle_between_top_level_modules() {
    let tops = top_modules();
    let graph: BTreeMap<String, BTreeSet<String>> = tops
        .iter()
        .map(|t| (t.clone(), imports(&src().join(t), &tops)))
        .collect();
    assert!(
        graph["common"].is_empty(),
        "common imports {:?}",
        graph["common"]
    );
    assert!(graph["app"].len() > 5, "the jobs import the stages");
    if let Some(c) = circle(&graph) {
        panic!(
            "import circle between top-level modules: {}",
            c.join(" -> ")
        );
    }
}

#[test]
fn a_circle_is_found() {
    let g = |edges: &[(&str, &str)]| {
        let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for (a, b) in edges {
            graph
                .entry(a.to_string())
                .or_default()
                .insert(b.to_string());
            graph.entry(b.to_string()).or_default();
        }
        graph
    };
    assert_eq!(
        circle(&g(&[("a", "b"), ("b", "c"), ("c", "a")])),
        Some(vec!["a".into(), "b".into(), "c".into()])
    );
    assert_eq!(circle(&g(&[("a", "b"), ("b", "c"), ("a", "c")])), None);
}
