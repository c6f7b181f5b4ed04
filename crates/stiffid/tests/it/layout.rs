//! The library's layout by pipeline stage (docs/ARCHITECTURE.md): at most 16 entries at the
//! root of `src/`, no import circle between its top-level modules (a module's code, outside
//! comments and tests, names `crate::OTHER` only for modules below it) nor between its files, no
//! job folder of `app/` importing another, and no library file over 700 lines.

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

/// Every library file: its path under `src/` and its code before the first `#[cfg(test)]`
/// (test files, `tests.rs` and `tests/`, left out).
fn library_files() -> Vec<(PathBuf, String)> {
    let mut files = Vec::new();
    sources(&src(), &mut files);
    files.sort();
    files
        .into_iter()
        .map(|f| {
            let text = std::fs::read_to_string(&f).unwrap();
            let code = text.split("#[cfg(test)]").next().unwrap().to_string();
            (f.strip_prefix(src()).unwrap().to_path_buf(), code)
        })
        .collect()
}

#[test]
fn no_library_file_is_over_700_lines() {
    let long: Vec<String> = library_files()
        .iter()
        .map(|(f, code)| (f, code.lines().count()))
        .filter(|(_, n)| *n > 700)
        .map(|(f, n)| format!("{} ({n} lines)", f.display()))
        .collect();
    assert!(long.is_empty(), "split by idea: {long:?}");
}

/// `text` with comments, strings and character literals blanked (lifetimes kept).
fn strip(text: &str) -> String {
    let c: Vec<char> = text.chars().collect();
    let (mut out, mut i) = (String::new(), 0);
    let at = |i: usize, s: &str| c[i..].iter().take(s.len()).copied().eq(s.chars());
    while i < c.len() {
        if at(i, "//") {
            i = (i..c.len()).find(|&j| c[j] == '\n').unwrap_or(c.len());
        } else if at(i, "/*") {
            i = (i + 2..c.len())
                .find(|&j| at(j, "*/"))
                .map_or(c.len(), |j| j + 2);
        } else if c[i] == 'r'
            && (i == 0 || !(c[i - 1].is_alphanumeric() || c[i - 1] == '_'))
            && (i + 1..c.len())
                .find(|&j| c[j] != '#')
                .is_some_and(|j| c[j] == '"')
        {
            let hashes = (i + 1..c.len()).take_while(|&j| c[j] == '#').count();
            let close: String = std::iter::once('"')
                .chain("#".repeat(hashes).chars())
                .collect();
            let from = i + 2 + hashes;
            i = (from..c.len())
                .find(|&j| at(j, &close))
                .map_or(c.len(), |j| j + close.len());
            out.push_str("\"\"");
        } else if c[i] == '"' {
            let mut j = i + 1;
            while j < c.len() && c[j] != '"' {
                j += if c[j] == '\\' { 2 } else { 1 };
            }
            i = j + 1;
            out.push_str("\"\"");
        } else if c[i] == '\'' && i + 1 < c.len() && c[i + 1] == '\\' {
            i = (i + 2..c.len())
                .find(|&j| c[j] == '\'')
                .map_or(c.len(), |j| j + 1);
            out.push_str("' '");
        } else if c[i] == '\'' && i + 2 < c.len() && c[i + 2] == '\'' {
            i += 3;
            out.push_str("' '");
        } else {
            out.push(c[i]);
            i += 1;
        }
    }
    out
}

/// The paths of `use a::{b::{c, d}, e}` spelt out: `a::b::c`, `a::b::d`, `a::e`.
fn expand(tree: &str) -> Vec<String> {
    if !tree.contains('{') {
        let leaf = tree.split_whitespace().next().unwrap_or("");
        return vec![leaf.to_string()];
    }
    let tree = tree.trim();
    let open = tree.find('{').unwrap();
    let prefix: String = tree[..open]
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect();
    let inner = &tree[open + 1..tree.len() - 1];
    let (mut parts, mut depth, mut start) = (Vec::new(), 0, 0);
    for (k, ch) in inner.char_indices() {
        match ch {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                parts.push(&inner[start..k]);
                start = k + 1;
            }
            _ => {}
        }
    }
    parts.push(&inner[start..]);
    (parts.into_iter().filter(|p| !p.trim().is_empty()))
        .flat_map(|p| expand(p).into_iter().map(|e| format!("{prefix}{e}")))
        .collect()
}

/// A module's path (`["cell", "bodies"]`) and the paths its code names, each with whether it is
/// a public re-export (`pub use`).
type Module = (Vec<String>, Vec<(String, bool)>);

fn modules() -> Vec<Module> {
    library_files()
        .into_iter()
        .map(|(file, code)| {
            let mut path: Vec<String> = (file.with_extension("").iter())
                .map(|s| s.to_string_lossy().into_owned())
                .collect();
            if matches!(path.last().map(String::as_str), Some("mod" | "lib")) {
                path.pop();
            }
            let code = strip(&code);
            let mut named = Vec::new();
            let mut rest = String::new();
            let mut tail = code.as_str();
            while let Some(at) = tail.find("use ") {
                let word =
                    at == 0 || !tail[..at].ends_with(|c: char| c.is_alphanumeric() || c == '_');
                let end = tail[at..].find(';').map_or(tail.len(), |e| at + e);
                if !word {
                    rest.push_str(&tail[..at + 4]);
                    tail = &tail[at + 4..];
                    continue;
                }
                let public =
                    tail[..at].trim_end().ends_with(')') || tail[..at].trim_end().ends_with("pub");
                rest.push_str(&tail[..at]);
                named.extend(expand(&tail[at + 4..end]).into_iter().map(|p| (p, public)));
                tail = &tail[(end + 1).min(tail.len())..];
            }
            rest.push_str(tail);
            for start in ["crate::", "super::", "self::"] {
                for (at, _) in rest.match_indices(start) {
                    if rest[..at].ends_with(|c: char| c.is_alphanumeric() || c == '_' || c == ':') {
                        continue;
                    }
                    let p: String = (rest[at..].chars())
                        .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':')
                        .collect();
                    named.push((p.trim_end_matches(':').to_string(), false));
                }
            }
            (path, named)
        })
        .collect()
}

/// The module (file) that `path`, named in `module`, leads to: the deepest module of the path,
/// through public re-exports; `None` for a path outside the crate.
fn resolve(
    graph: &BTreeMap<Vec<String>, Vec<(String, bool)>>,
    module: &[String],
    path: &str,
    depth: usize,
) -> Option<Vec<String>> {
    let mut segments: Vec<&str> = path.split("::").collect();
    let mut at: Vec<String> = match segments[0] {
        "crate" => Vec::new(),
        "super" | "self" => module.to_vec(),
        first if graph.contains_key(&[module, &[first.to_string()]].concat()) => module.to_vec(),
        _ => return None,
    };
    while let Some(&s) = segments.first() {
        match s {
            "crate" | "self" => {}
            "super" => {
                at.pop();
            }
            _ => break,
        }
        segments.remove(0);
    }
    for s in segments {
        let next = [at.clone(), vec![s.to_string()]].concat();
        if graph.contains_key(&next) {
            at = next;
            continue;
        }
        let exported =
            (graph[&at].iter()).find(|(p, public)| *public && p.rsplit("::").next() == Some(s));
        if let (Some((p, _)), true) = (exported, depth < 8) {
            return resolve(graph, &at.clone(), p, depth + 1).or(Some(at));
        }
        break;
    }
    Some(at)
}

/// The import graph between library files: an edge from a file to every other file its code
/// names an item of (through re-exports), a folder's `mod.rs` and the files in it excepted (a
/// child extends its parent).
fn file_graph() -> BTreeMap<String, BTreeSet<String>> {
    let graph: BTreeMap<Vec<String>, Vec<(String, bool)>> = modules().into_iter().collect();
    let related = |a: &[String], b: &[String]| a.starts_with(b) || b.starts_with(a);
    graph
        .iter()
        .map(|(module, named)| {
            let to = (named.iter())
                .filter_map(|(p, _)| resolve(&graph, module, p, 0))
                .filter(|t| !related(t, module))
                .map(|t| t.join("/"))
                .collect();
            (module.join("/"), to)
        })
        .collect()
}

/// The files in a circle of imports: the strongly connected components of more than one file.
fn circles(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    let reach = |from: &str| {
        let (mut seen, mut stack) = (BTreeSet::new(), vec![from.to_string()]);
        while let Some(n) = stack.pop() {
            for m in &graph[&n] {
                if seen.insert(m.clone()) {
                    stack.push(m.clone());
                }
            }
        }
        seen
    };
    let reached: BTreeMap<&String, BTreeSet<String>> =
        graph.keys().map(|n| (n, reach(n))).collect();
    let mut out: Vec<Vec<String>> = Vec::new();
    for n in graph.keys() {
        let circle: Vec<String> = (reached[n].iter())
            .filter(|m| reached[*m].contains(n))
            .cloned()
            .collect();
        if circle.len() > 1 && !out.contains(&circle) {
            out.push(circle);
        }
    }
    out
}

#[test]
fn no_import_circle_between_files() {
    let graph = file_graph();
    assert!(
        graph["cell/feasibility"].contains("cell/bodies"),
        "{graph:?}"
    );
    assert!(graph["metrology/calibration/error_model/loads"]
        .contains("metrology/calibration/error_model/parameter"));
    let found = circles(&graph);
    assert!(found.is_empty(), "import circles between files: {found:?}");
}

#[test]
fn file_circles_are_found() {
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
        circles(&g(&[("a", "b"), ("b", "c"), ("c", "a"), ("c", "d")])),
        vec![vec!["a".to_string(), "b".into(), "c".into()]]
    );
    assert!(circles(&g(&[("a", "b"), ("a", "c"), ("b", "c")])).is_empty());
    assert_eq!(
        expand("crate::{a::{b, c as d, base}, e}"),
        ["crate::a::b", "crate::a::c", "crate::a::base", "crate::e"]
    );
    assert_eq!(
        strip("x /* y */ \"a\\\"b\" 'c' '\\n' 'a r#\"q\"# // z"),
        "x  \"\" ' ' ' ' 'a \"\" "
    );
}

/// The job folder a library file belongs to (`app/<job>/...`), `None` outside one: `app/document`
/// and the files directly in `app/` are what the jobs share.
fn job_folder(file: &str) -> Option<&str> {
    let mut parts = file.split('/');
    let (Some("app"), Some(job)) = (parts.next(), parts.next()) else {
        return None;
    };
    (job != "document" && src().join("app").join(job).is_dir()).then_some(job)
}

#[test]
fn no_job_folder_imports_another() {
    let graph = file_graph();
    let crossing: Vec<String> = (graph.iter())
        .flat_map(|(from, to)| to.iter().map(move |t| (from, t)))
        .filter_map(|(from, to)| match (job_folder(from), job_folder(to)) {
            (Some(a), Some(b)) if a != b => Some(format!("{from} -> {to}")),
            _ => None,
        })
        .collect();
    assert!(
        graph["app/plan/document"]
            .iter()
            .any(|t| t.starts_with("app/document")),
        "{graph:?}"
    );
    assert!(
        crossing.is_empty(),
        "move what jobs share to app/document: {crossing:#?}"
    );
    assert_eq!(job_folder("app/select/document"), Some("select"));
    assert_eq!(job_folder("app/select"), Some("select"));
    assert_eq!(job_folder("app/document/scene"), None);
    assert_eq!(job_folder("app/readings"), None);
}

/// The names `lib.rs` makes public at the crate's root: its `pub mod` modules and the items of
/// its `pub use` lines.
fn public_surface(lib: &str) -> BTreeSet<String> {
    let code = strip(lib);
    let mut names = BTreeSet::new();
    for statement in code.split(';') {
        // From the line the statement starts on (attributes and blank lines before it left out).
        let at = (statement.match_indices('\n').map(|(i, _)| i + 1))
            .chain([0])
            .filter(|&i| statement[i..].trim_start().starts_with("pub "))
            .min()
            .unwrap_or(statement.len());
        let statement = statement[at..].trim();
        if let Some(module) = statement.strip_prefix("pub mod ") {
            names.insert(module.trim().to_string());
        } else if let Some(tree) = statement.strip_prefix("pub use ") {
            for path in expand(tree) {
                let name = path.rsplit("::").next().unwrap_or("").trim();
                names.insert(name.to_string());
            }
        }
    }
    names
}

/// The names listed in `docs/ARCHITECTURE.md`'s section "Public surface": every `stiffid::NAME`
/// that starts a list line.
fn listed_surface(architecture: &str) -> BTreeSet<String> {
    let section = (architecture.split("\n## "))
        .find(|s| s.starts_with("Public surface"))
        .expect("docs/ARCHITECTURE.md has a section 'Public surface'");
    let mut names = BTreeSet::new();
    for line in section.lines().filter(|l| l.starts_with("- ")) {
        let head = line.split("`: ").next().unwrap_or("");
        for (at, _) in head.match_indices("`stiffid::") {
            let name: String = (head[at + 10..].chars())
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            names.insert(name);
        }
    }
    names
}

#[test]
fn the_public_surface_is_the_one_architecture_lists() {
    let lib = std::fs::read_to_string(src().join("lib.rs")).unwrap();
    let architecture =
        std::fs::read_to_string(src().join("../../../docs/ARCHITECTURE.md")).unwrap();
    let (public, listed) = (public_surface(&lib), listed_surface(&architecture));
    assert!(
        public.contains("app") && public.contains("Setup"),
        "{public:?}"
    );
    assert!(public.len() >= 20, "{public:?}");
    assert_eq!(
        public, listed,
        "lib.rs's pub mod and pub use against docs/ARCHITECTURE.md's 'Public surface'"
    );
    // The parsers themselves.
    let lib =
        "#![deny(x)]\npub mod a;\nmod hidden;\npub use x::{B, c::D};\n/// pub mod not_code;\n";
    assert_eq!(
        public_surface(lib),
        ["B", "D", "a"].map(String::from).into()
    );
    let doc = "# A\n## Public surface\n\n- `stiffid::a`, `stiffid::B`: x `stiffid::no`\n## Next\n- `stiffid::c`: y\n";
    assert_eq!(listed_surface(doc), ["B", "a"].map(String::from).into());
}
