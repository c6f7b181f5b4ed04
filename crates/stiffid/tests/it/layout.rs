//! The library's layout by concern (docs/ARCHITECTURE.md): crates that stand on each other
//! without a circle, on floors (core, the science, the views, the jobs: no science crate on the
//! views or the jobs, no `app/` folder outside the jobs crate `stiffid`), no import circle
//! between the files of a crate (a folder's `mod.rs` and `lib.rs` included), no job folder of
//! `app/` importing another, no library file over 700 lines, each crate's public surface and
//! count of public items the ones docs/ARCHITECTURE.md lists, no more documents built by the
//! front ends, no unit test in a crate whose tests are off (`[lib] test = false`: compiled once,
//! its tests in tests/it), and every field the jobs write through a unit adapter documenting the
//! unit it holds and the one it is written in.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The library crates, from the ground up: core, the science, the views, and this facade (the
/// jobs) last.
pub(crate) const CRATES: [&str; 7] = [
    "stiffid-core",
    "stiffid-metrology",
    "stiffid-identify",
    "stiffid-design",
    "stiffid-machining",
    "stiffid-view",
    "stiffid",
];

/// The science crates: each depends only on core and the science it uses.
const SCIENCE: [&str; 4] = [
    "stiffid-metrology",
    "stiffid-identify",
    "stiffid-design",
    "stiffid-machining",
];

fn crate_dir(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(name)
}

fn src_of(name: &str) -> PathBuf {
    crate_dir(name).join("src")
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
        } else if name.ends_with(".rs") && name != "tests.rs" && !name.ends_with("_tests.rs") {
            out.push(path);
        }
    }
}

/// The workspace's crates a crate's manifest depends on (`[dependencies]`, not the
/// dev-dependencies).
fn crate_dependencies(name: &str) -> BTreeSet<String> {
    let manifest = std::fs::read_to_string(crate_dir(name).join("Cargo.toml")).unwrap();
    let deps = (manifest
        .split("\n[")
        .find(|s| s.starts_with("dependencies]")))
    .unwrap_or_default();
    (deps.lines())
        .filter_map(|l| l.split(['.', ' ', '=']).next())
        .filter(|d| d.starts_with("stiffid"))
        .map(String::from)
        .collect()
}

/// The floors: a science crate depends only on core and the science below it (not on the
/// views, the jobs or a front end); the views only on core; the jobs (the facade) on every
/// library crate and on nothing above (the figures and the front ends stand on it).
#[test]
fn science_below_views_below_jobs_below_front_ends() {
    for name in SCIENCE {
        let deps = crate_dependencies(name);
        let allowed = |d: &String| d == "stiffid-core" || SCIENCE.contains(&d.as_str());
        let above: Vec<&String> = deps.iter().filter(|d| !allowed(d)).collect();
        assert!(
            above.is_empty(),
            "{name} depends on {above:?}, above the science"
        );
        assert!(deps.contains("stiffid-core"), "{name}: {deps:?}");
    }
    let view = crate_dependencies("stiffid-view");
    assert_eq!(
        view,
        ["stiffid-core".to_string()].into(),
        "stiffid-view: {view:?}"
    );
    let jobs = crate_dependencies("stiffid");
    let library: BTreeSet<String> = CRATES[..CRATES.len() - 1]
        .iter()
        .map(|c| c.to_string())
        .collect();
    assert_eq!(
        jobs, library,
        "the facade (the jobs) stands on every library crate, nothing above"
    );
    for above in ["stiffid-figures", "stiffid-cli", "stiffid-py"] {
        let deps = crate_dependencies(above);
        assert!(
            deps.contains("stiffid"),
            "{above} uses the jobs through the facade: {deps:?}"
        );
    }
    assert!(
        !crate_dir("stiffid-calibrate").exists(),
        "the calibration jobs are the facade's"
    );
}

/// The jobs live in the facade: no other library crate has an `app/` folder.
#[test]
fn only_the_facade_holds_jobs() {
    for name in CRATES {
        let app = src_of(name).join("app");
        assert_eq!(app.is_dir(), name == "stiffid", "{}", app.display());
    }
}

#[test]
fn no_circle_between_crates() {
    let graph: BTreeMap<String, BTreeSet<String>> = CRATES
        .iter()
        .map(|c| (c.to_string(), crate_dependencies(c)))
        .collect();
    assert!(graph["stiffid-core"].is_empty(), "{graph:?}");
    assert!(
        graph["stiffid-machining"].contains("stiffid-core"),
        "{graph:?}"
    );
    assert_eq!(
        graph["stiffid"].len(),
        CRATES.len() - 1,
        "the facade re-exports every crate"
    );
    if let Some(c) = circle(&graph) {
        panic!("circle between crates: {}", c.join(" -> "));
    }
    // Each crate depends only on crates listed before it: the stack reads from the ground up.
    for (at, name) in CRATES.iter().enumerate() {
        for dep in &graph[*name] {
            let below = CRATES[..at].contains(&dep.as_str());
            assert!(below, "{name} depends on {dep}, listed above it");
        }
    }
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

/// A crate's files as `(path under src/, code)`.
type Files = Vec<(PathBuf, String)>;

/// `read(name)`, computed once per crate in `cache` for every test that asks (the sources do not
/// change during a run; the layout tests read them again and again otherwise).
fn once_per_crate(
    cache: &std::sync::Mutex<BTreeMap<String, Files>>,
    name: &str,
    read: impl FnOnce() -> Files,
) -> Files {
    let mut read_already = cache.lock().unwrap_or_else(|e| e.into_inner());
    read_already
        .entry(name.to_string())
        .or_insert_with(read)
        .clone()
}

/// Every library file: its path under `src/` and its code before the first `#[cfg(test)]`
/// (test files, `tests.rs` and `tests/`, left out).
pub(crate) fn library_files(name: &str) -> Files {
    static READ: std::sync::Mutex<BTreeMap<String, Files>> = std::sync::Mutex::new(BTreeMap::new());
    once_per_crate(&READ, name, || {
        let mut files = Vec::new();
        sources(&src_of(name), &mut files);
        files.sort();
        files
            .into_iter()
            .map(|f| {
                let text = std::fs::read_to_string(&f).unwrap();
                let path = f.strip_prefix(src_of(name)).unwrap().to_path_buf();
                (path, without_tests(&text))
            })
            .collect()
    })
}

/// [`library_files`] with their code [`strip`]ped.
pub(crate) fn stripped_library_files(name: &str) -> Files {
    static READ: std::sync::Mutex<BTreeMap<String, Files>> = std::sync::Mutex::new(BTreeMap::new());
    once_per_crate(&READ, name, || {
        (library_files(name).into_iter())
            .map(|(path, code)| (path, strip(&code)))
            .collect()
    })
}

/// `text` without its `#[cfg(test)]` items: each such attribute with the item it marks, a
/// `mod NAME;` line or a braced item to its closing brace (wherever it sits in the file, so no
/// public item after a test module leaves the count).
fn without_tests(text: &str) -> String {
    let mut code = text.to_string();
    while let Some(at) = code.find("#[cfg(test)]") {
        let end = item_end(&code, at + "#[cfg(test)]".len());
        code.replace_range(at..end, "");
    }
    code
}

/// Where the item starting at byte `from` of `code` ends: after its `;` at the top level, or
/// after the brace that closes its first `{`; comments, strings and character literals skipped.
fn item_end(code: &str, from: usize) -> usize {
    let b = code.as_bytes();
    let (mut i, mut depth) = (from, 0usize);
    while i < b.len() {
        match b[i] {
            b'/' if b.get(i + 1) == Some(&b'/') => {
                i = code[i..].find('\n').map_or(b.len(), |n| i + n);
            }
            b'/' if b.get(i + 1) == Some(&b'*') => {
                i = code[i + 2..].find("*/").map_or(b.len(), |n| i + n + 4) - 1;
            }
            b'"' => i = string_end(code, i, None),
            b'r' if !b[i - 1].is_ascii_alphanumeric()
                && matches!(b.get(i + 1), Some(b'"' | b'#')) =>
            {
                let hashes = b[i + 1..].iter().take_while(|&&c| c == b'#').count();
                i = string_end(code, i + 1 + hashes, Some(hashes));
            }
            b'\'' if b.get(i + 2) == Some(&b'\'') => i += 2,
            b'\'' if b.get(i + 1) == Some(&b'\\') => {
                i = code[i + 2..].find('\'').map_or(b.len(), |n| i + 2 + n);
            }
            b'{' => depth += 1,
            b'}' if depth == 1 => return i + 1,
            b'}' => depth -= 1,
            b';' if depth == 0 => return i + 1,
            _ => {}
        }
        i += 1;
    }
    b.len()
}

/// The byte of the closing quote of the string whose opening quote is at `open`: a raw string's
/// when `raw` gives its count of `#` (a backslash escapes nothing there).
fn string_end(code: &str, open: usize, raw: Option<usize>) -> usize {
    let b = code.as_bytes();
    let mut i = open + 1;
    while i < b.len() {
        match (b[i], raw) {
            (b'\\', None) => i += 1,
            (b'"', None) => return i,
            (b'"', Some(h)) if b[i + 1..].iter().take(h).filter(|&&c| c == b'#').count() == h => {
                return i + h;
            }
            _ => {}
        }
        i += 1;
    }
    b.len()
}

/// A test module or item leaves the code, wherever it sits; what follows it stays (a brace in a
/// string, a comment or a character literal of the test does not end it early).
#[test]
fn test_items_leave_the_code_and_what_follows_them_stays() {
    let text =
        "pub fn a() {}\n#[cfg(test)]\nmod a_tests;\npub fn b() {}\n#[cfg(test)]\nmod t {\n    \
                fn f() { let _ = (\"}\", r#\"}\"#, '}'); } // }\n}\npub fn c() {}\n";
    let code = without_tests(text);
    assert_eq!(code.matches("pub fn").count(), 3, "{code}");
    assert!(
        !code.contains("a_tests") && !code.contains("fn f"),
        "{code}"
    );
}

#[test]
fn no_library_file_is_over_700_lines() {
    let long: Vec<String> = (CRATES.iter())
        .flat_map(|c| library_files(c).into_iter().map(move |f| (c, f)))
        .map(|(c, (f, code))| (c, f, code.lines().count()))
        .filter(|(_, _, n)| *n > 700)
        .map(|(c, f, n)| format!("{c}/src/{} ({n} lines)", f.display()))
        .collect();
    assert!(long.is_empty(), "split by idea: {long:?}");
}

/// `text` with comments, strings and character literals blanked (lifetimes kept).
pub(crate) fn strip(text: &str) -> String {
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

fn modules(name: &str) -> Vec<Module> {
    stripped_library_files(name)
        .into_iter()
        .map(|(file, code)| {
            let mut path: Vec<String> = (file.with_extension("").iter())
                .map(|s| s.to_string_lossy().into_owned())
                .collect();
            if matches!(path.last().map(String::as_str), Some("mod" | "lib")) {
                path.pop();
            }
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

/// The import graph between the files of crate `name`: an edge from a file to every other file
/// its code names an item of (through re-exports). A public re-export (`pub use`) is the
/// module's face, not a use of it: it draws no edge of its own. A folder's `mod.rs` and the files
/// directly in it are left out of each other's edges (a child that extends its parent); every
/// other edge of a `mod.rs` or `lib.rs` counts.
fn file_graph(name: &str) -> BTreeMap<String, BTreeSet<String>> {
    let graph: BTreeMap<Vec<String>, Vec<(String, bool)>> = modules(name).into_iter().collect();
    let child = |a: &[String], b: &[String]| {
        (a.len() + 1 == b.len() && b.starts_with(a)) || (b.len() + 1 == a.len() && a.starts_with(b))
    };
    graph
        .iter()
        .map(|(module, named)| {
            let to = (named.iter())
                .filter(|(_, public)| !public)
                .filter_map(|(p, _)| resolve(&graph, module, p, 0))
                .filter(|t| t != module && !child(t, module))
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
    let core = file_graph("stiffid-core");
    assert!(core["cell/feasibility"].contains("cell/bodies"), "{core:?}");
    let metrology = file_graph("stiffid-metrology");
    assert!(
        metrology["calibration/error_model/loads"].contains("calibration/error_model/parameter")
    );
    // A file naming a file of another folder is an edge.
    let machining = file_graph("stiffid-machining");
    assert!(machining["gcode/words"].contains("text"), "{machining:?}");
    for name in CRATES {
        let found = circles(&file_graph(name));
        assert!(
            found.is_empty(),
            "import circles between the files of {name}: {found:?}"
        );
    }
}

/// The import graph between the folders of crate `name`: every file of [`file_graph`] stands for
/// its folder (a folder's `mod.rs` and the files directly in it are one node), so that a circle
/// running through a folder's `mod.rs` and its files, which the file graph leaves out, is seen.
/// A folder and the folders inside it are left out of each other's edges, as at the file level.
fn folder_graph(files: &BTreeMap<String, BTreeSet<String>>) -> BTreeMap<String, BTreeSet<String>> {
    let folder = |f: &String| -> String {
        let prefix = format!("{f}/");
        match files.keys().any(|k| k.starts_with(&prefix)) {
            true => f.clone(),
            false => f
                .rsplit_once('/')
                .map_or(String::new(), |(p, _)| p.to_string()),
        }
    };
    let nested = |a: &str, b: &str| {
        a.is_empty()
            || b.is_empty()
            || a.starts_with(&format!("{b}/"))
            || b.starts_with(&format!("{a}/"))
    };
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (from, to) in files {
        let a = folder(from);
        let edges = graph.entry(a.clone()).or_default();
        for b in to.iter().map(folder) {
            if a != b && !nested(&a, &b) {
                edges.insert(b);
            }
        }
    }
    let ends: Vec<String> = graph.values().flatten().cloned().collect();
    for end in ends {
        graph.entry(end).or_default();
    }
    graph
}

#[test]
fn no_import_circle_between_folders() {
    for name in CRATES {
        let found = circles(&folder_graph(&file_graph(name)));
        assert!(
            found.is_empty(),
            "import circles between the folders of {name}: {found:?}"
        );
    }
    // A circle through a folder's mod.rs and its file, which the file graph does not see.
    let files: BTreeMap<String, BTreeSet<String>> = [
        ("c/fit", vec![]),
        ("c/fit/strength", vec!["c/maps"]),
        ("c/maps", vec![]),
        ("c/maps/linear", vec!["c/fit"]),
    ]
    .into_iter()
    .map(|(a, b)| (a.to_string(), b.into_iter().map(String::from).collect()))
    .collect();
    assert!(circles(&files).is_empty());
    assert_eq!(
        circles(&folder_graph(&files)),
        vec![vec!["c/fit".to_string(), "c/maps".to_string()]]
    );
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
fn job_folder<'a>(name: &str, file: &'a str) -> Option<&'a str> {
    let mut parts = file.split('/');
    let (Some("app"), Some(job)) = (parts.next(), parts.next()) else {
        return None;
    };
    (job != "document" && src_of(name).join("app").join(job).is_dir()).then_some(job)
}

/// The job folders of other crates that a file's code names (`stiffid::app::select`).
fn other_jobs(code: &str) -> Vec<String> {
    let code = strip(code);
    let mut found = Vec::new();
    for name in CRATES {
        let root = format!("{}::app::", name.replace('-', "_"));
        for (at, _) in code.match_indices(&root) {
            let tail = &code[at + root.len()..];
            // `app::{a, b::c}`: each member's first name; `app::a`: its name.
            let names: Vec<String> = match tail.strip_prefix('{') {
                Some(group) => expand(&format!("{{{}}}", &group[..group.find('}').unwrap_or(0)]))
                    .into_iter()
                    .map(|p| p.split("::").next().unwrap_or("").to_string())
                    .collect(),
                None => vec![(tail.chars())
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect()],
            };
            for job in names.into_iter().filter(|j| !j.is_empty()) {
                if job_folder(name, &format!("app/{job}")).is_some() {
                    found.push(format!("{name}: {job}"));
                }
            }
        }
    }
    found
}

#[test]
fn no_job_folder_imports_another() {
    let mut crossing = Vec::new();
    for name in CRATES {
        let graph = file_graph(name);
        crossing.extend(
            (graph.iter())
                .flat_map(|(from, to)| to.iter().map(move |t| (from, t)))
                .filter_map(
                    |(from, to)| match (job_folder(name, from), job_folder(name, to)) {
                        (Some(a), Some(b)) if a != b => Some(format!("{name}: {from} -> {to}")),
                        _ => None,
                    },
                ),
        );
        for (file, code) in library_files(name) {
            let file = file.with_extension("").to_string_lossy().into_owned();
            if job_folder(name, &file).is_some() {
                let jobs = other_jobs(&code);
                crossing.extend(jobs.into_iter().map(|j| format!("{name}: {file} -> {j}")));
            }
        }
    }
    let jobs = file_graph("stiffid");
    assert!(
        (jobs["app/plan/document"].iter()).any(|t| t.starts_with("app/document")),
        "{jobs:?}"
    );
    assert!(
        crossing.is_empty(),
        "move what jobs share to an app/document: {crossing:#?}"
    );
    assert_eq!(job_folder("stiffid", "app/select/document"), Some("select"));
    assert_eq!(job_folder("stiffid", "app/select"), Some("select"));
    assert_eq!(job_folder("stiffid", "app/document/mass"), None);
    assert_eq!(job_folder("stiffid", "app/readings"), None);
    assert_eq!(
        other_jobs("use stiffid::app::predict::Request;"),
        ["stiffid: predict"]
    );
}

/// The names `lib.rs` makes public at the crate's root: its `pub mod` modules, the items of its
/// `pub use` lines and the items it defines `pub` (functions, types, traits, constants).
fn public_surface(lib: &str) -> BTreeSet<String> {
    let code = strip(lib);
    let mut names = BTreeSet::new();
    let word = |s: &str| -> String {
        (s.chars())
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    };
    let starts = (code.match_indices('\n').map(|(i, _)| i + 1)).chain([0]);
    for at in starts {
        // Items compiled only as doctests are no part of the surface.
        let doctest = code[..at].trim_end().ends_with("#[cfg(doctest)]");
        let Some(rest) = code[at..].strip_prefix("pub ").filter(|_| !doctest) else {
            continue;
        };
        if let Some(tree) = rest.strip_prefix("use ") {
            let tree = &tree[..tree.find(';').unwrap_or(tree.len())];
            // `pub use a::b as c;`: the name is the alias.
            if let (false, Some((_, alias))) = (tree.contains('{'), tree.split_once(" as ")) {
                names.insert(alias.trim().to_string());
                continue;
            }
            for path in expand(tree) {
                names.insert(path.rsplit("::").next().unwrap_or("").trim().to_string());
            }
            continue;
        }
        for kind in [
            "mod ", "fn ", "struct ", "enum ", "trait ", "type ", "const ", "static ",
        ] {
            if let Some(name) = rest.strip_prefix(kind) {
                names.insert(word(name));
            }
        }
    }
    names
}

/// The names listed in `docs/ARCHITECTURE.md`'s section "Public surface" for crate `krate`
/// (`stiffid_core`): every `` `krate::NAME` `` that starts a list line.
fn listed_surface(architecture: &str, krate: &str) -> BTreeSet<String> {
    let section = (architecture.split("\n## "))
        .find(|s| s.starts_with("Public surface"))
        .expect("docs/ARCHITECTURE.md has a section 'Public surface'");
    let mut names = BTreeSet::new();
    let start = format!("`{krate}::");
    for line in section.lines().filter(|l| l.starts_with("- ")) {
        let head = line.split("`: ").next().unwrap_or("");
        for (at, _) in head.match_indices(&start) {
            let name: String = (head[at + start.len()..].chars())
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            names.insert(name);
        }
    }
    names
}

#[test]
fn the_public_surface_is_the_one_architecture_lists() {
    let architecture =
        std::fs::read_to_string(crate_dir("stiffid").join("../../docs/ARCHITECTURE.md")).unwrap();
    for name in CRATES {
        let lib = std::fs::read_to_string(src_of(name).join("lib.rs")).unwrap();
        let krate = name.replace('-', "_");
        let (public, listed) = (public_surface(&lib), listed_surface(&architecture, &krate));
        assert!(!public.is_empty(), "{name}");
        assert_eq!(
            public, listed,
            "{name}'s lib.rs (pub mod, pub use) against docs/ARCHITECTURE.md's 'Public surface'"
        );
    }
    let core =
        public_surface(&std::fs::read_to_string(src_of("stiffid-core").join("lib.rs")).unwrap());
    assert!(!core.contains("app") && core.contains("Setup"), "{core:?}");
    // The parsers themselves.
    let lib = "#![deny(x)]\npub mod a;\nmod hidden;\npub use x::{B, c::D};\n/// pub mod not_code;\npub fn e() {}\nimpl X {\n    pub fn inner() {}\n}\npub struct F;\n#[cfg(doctest)]\npub struct G;\npub use h as i;\n";
    assert_eq!(
        public_surface(lib),
        ["B", "D", "F", "a", "e", "i"].map(String::from).into()
    );
    let doc = "# A\n## Public surface\n\n- `stiffid::a`, `stiffid::B`: x `stiffid::no`\n- `stiffid_core::d`: z\n## Next\n- `stiffid::c`: y\n";
    assert_eq!(
        listed_surface(doc, "stiffid"),
        ["B", "a"].map(String::from).into()
    );
    assert_eq!(
        listed_surface(doc, "stiffid_core"),
        ["d"].map(String::from).into()
    );
}

/// Whether Rust source `text` declares a test: `#[test]` or a `proptest!` block.
fn declares_a_test(text: &str) -> bool {
    text.contains("#[test]") || text.contains("proptest!")
}

/// Every `.rs` file under `dir`, test modules included.
fn every_source(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            every_source(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// A crate whose unit tests are off (`[lib] test = false`, so `cargo test` compiles it once)
/// has no test under `src/`: one added there would never run. Its tests live in tests/it.
#[test]
fn a_crate_without_unit_tests_declares_none() {
    let crates = crate_dir("stiffid").join("..");
    let mut off = Vec::new();
    for entry in std::fs::read_dir(&crates).unwrap() {
        let dir = entry.unwrap().path();
        let Ok(manifest) = std::fs::read_to_string(dir.join("Cargo.toml")) else {
            continue;
        };
        let manifest: toml::Table = toml::from_str(&manifest).unwrap();
        let lib = manifest.get("lib").and_then(toml::Value::as_table);
        if lib
            .and_then(|l| l.get("test"))
            .and_then(toml::Value::as_bool)
            != Some(false)
        {
            continue;
        }
        let mut files = Vec::new();
        every_source(&dir.join("src"), &mut files);
        for file in files {
            let text = std::fs::read_to_string(&file).unwrap();
            assert!(
                !declares_a_test(&text),
                "{}: a test in a crate with `[lib] test = false` never runs; move it to crates/stiffid/tests/it",
                file.display()
            );
        }
        off.push(dir.file_name().unwrap().to_string_lossy().into_owned());
    }
    assert!(off.contains(&"stiffid-view".to_string()), "{off:?}");
    assert!(declares_a_test(
        "#[cfg(test)]\nmod t {\n    #[test]\n    fn a() {}\n}"
    ));
    assert!(declares_a_test("proptest! {\n    fn b(x in 0..3) {}\n}"));
    assert!(!declares_a_test("#[cfg(test)]\nmod t {}\n"));
}

/// Every `Document` type of the library (what a job writes), and every `Report` that serialises
/// to its document itself, names itself: its attributes hold serde's `tag = "kind"`, so its
/// JSON's first key is `kind` (docs/ARCHITECTURE.md, "Jobs and documents"); the schemas' test
/// checks the same of every schema `stiffid schema` lists.
#[test]
fn every_document_type_names_its_kind() {
    let mut missing = Vec::new();
    let mut found = 0;
    for c in CRATES {
        for (file, code) in library_files(c) {
            let lines: Vec<&str> = code.lines().collect();
            for (i, line) in lines.iter().enumerate() {
                let report = line.starts_with("pub struct Report");
                if !line.starts_with("pub struct Document") && !report {
                    continue;
                }
                let attributes: Vec<&&str> = (lines[..i].iter().rev())
                    .take_while(|l| {
                        // An attribute over several lines: its inner lines and its `)]`.
                        let inner = l.starts_with(' ') || l.starts_with(")]");
                        l.starts_with("#[") || l.starts_with("///") || inner
                    })
                    .collect();
                if report && !attributes.iter().any(|l| l.contains("Serialize")) {
                    continue;
                }
                found += 1;
                if !attributes.iter().any(|l| l.contains("tag = \"kind\"")) {
                    missing.push(format!("{c}/src/{}:{}", file.display(), i + 1));
                }
            }
        }
    }
    assert!(found >= 15, "{found} document types found");
    assert!(missing.is_empty(), "documents without a kind: {missing:?}");
}

/// The `pub` items of a library crate's files (outside their tests): every `pub` function (a
/// method too), type, trait, constant, static, module and `pub use` line (a `pub(crate)` or
/// `pub(super)` item is not public; a field is counted with its type).
fn public_items(name: &str) -> usize {
    let kinds = [
        "fn ", "struct ", "enum ", "trait ", "type ", "const ", "static ", "mod ", "use ",
    ];
    (stripped_library_files(name).iter())
        .flat_map(|(_, code)| code.lines().map(str::to_string).collect::<Vec<_>>())
        .filter(|l| {
            let rest = l.trim_start().strip_prefix("pub ");
            let rest = rest.map(|r| r.trim_start_matches("async ").trim_start_matches("unsafe "));
            rest.is_some_and(|r| kinds.iter().any(|k| r.starts_with(k)))
        })
        .count()
}

/// The public items of every library crate, as docs/ARCHITECTURE.md's table "Public items"
/// lists them (`| `crate` | count |`): a change of the surface changes the table with it.
#[test]
fn the_public_item_counts_are_the_ones_architecture_lists() {
    let architecture =
        std::fs::read_to_string(crate_dir("stiffid").join("../../docs/ARCHITECTURE.md")).unwrap();
    let listed: BTreeMap<String, usize> = (architecture.lines())
        .filter_map(|l| {
            let cells: Vec<&str> = l.split('|').map(str::trim).collect();
            let name = cells.get(1)?.strip_prefix('`')?.strip_suffix('`')?;
            let count = cells.get(2)?.parse().ok()?;
            CRATES.contains(&name).then(|| (name.to_string(), count))
        })
        .collect();
    let counted: BTreeMap<String, usize> = (CRATES.iter())
        .map(|c| (c.to_string(), public_items(c)))
        .collect();
    let total: usize = counted.values().sum();
    assert_eq!(
        counted, listed,
        "public items per crate (total {total}) against docs/ARCHITECTURE.md's table"
    );
    let listed_total = (architecture.lines()).find_map(|l| {
        l.strip_prefix("| all library crates | ")?
            .split(' ')
            .next()?
            .parse()
            .ok()
    });
    assert_eq!(listed_total, Some(total), "the table's total");
}

/// The places where a front end (`stiffid-cli`, `stiffid-py`) builds a job's document or a part
/// of one from its report (`Document::new(&report, ..)`, `Summary::new(&report)`, any `::new(`
/// or `::from(` of a type of a job's document module or of the documents' parts,
/// `app/document/`, the feasibility's `postures`, a scene from a report) instead of receiving it
/// from the job: none (every job's `run` returns its document, and a view of it or of a part
/// comes from the job's report).
const FRONT_END_DOCUMENTS: usize = 0;

/// How many documents or parts of one the line of code `line` builds: a `Document::new(`, a
/// `document::scene(`, a `NAME::new(` or `NAME::from(` of one of the `types` of the documents
/// ([`job_document_types`]), or a mention of the feasibility's `feasibility::postures` (its
/// call or its import).
fn builds(line: &str, types: &BTreeSet<String>) -> usize {
    // `word` in `line` as a whole word: neither a letter, a digit nor `_` before it, nor one
    // after it when `whole` (an opening parenthesis ends the call words).
    let calls = |word: &str, whole: bool| {
        let word_char = |c: char| c.is_alphanumeric() || c == '_';
        (line.match_indices(word))
            .filter(|(i, _)| !line[..*i].chars().next_back().is_some_and(word_char))
            .filter(|(i, _)| !whole || !line[*i + word.len()..].starts_with(word_char))
            .count()
    };
    let named = |name: &String| {
        // `Document::new(` is counted below for any type of that ending.
        let new = (!name.ends_with("Document")).then(|| calls(&format!("{name}::new("), false));
        new.unwrap_or(0) + calls(&format!("{name}::from("), false)
    };
    line.match_indices("Document::new(").count()
        + line.match_indices("document::scene(").count()
        + calls("feasibility::postures", true)
        + types.iter().map(named).sum::<usize>()
}

/// The types (structs and enums, public or not) of every job's document module,
/// `app/<job>/document.rs` and the files under `app/<job>/document/`, and of the documents'
/// parts, the files of `app/document/`.
fn job_document_types() -> BTreeSet<String> {
    let mut files = Vec::new();
    every_source(&src_of("stiffid").join("app/document"), &mut files);
    for job in std::fs::read_dir(src_of("stiffid").join("app")).unwrap() {
        let job = job.unwrap().path();
        if job.join("document.rs").is_file() {
            files.push(job.join("document.rs"));
        }
        if job.join("document").is_dir() {
            every_source(&job.join("document"), &mut files);
        }
    }
    let mut types = BTreeSet::new();
    for file in files {
        let code = strip(&std::fs::read_to_string(&file).unwrap());
        for word in ["struct ", "enum "] {
            for (i, _) in code.match_indices(word) {
                if code[..i].ends_with(|c: char| c.is_alphanumeric() || c == '_') {
                    continue;
                }
                let name: String = code[i + word.len()..]
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                types.extend((!name.is_empty()).then_some(name));
            }
        }
    }
    types
}

/// Each place in a front end's code where a document is built: `file:line`, and the files
/// scanned.
fn front_end_documents() -> (Vec<String>, Vec<PathBuf>) {
    let (mut found, mut scanned) = (Vec::new(), Vec::new());
    let types = job_document_types();
    for front in ["stiffid-cli", "stiffid-py"] {
        let mut files = Vec::new();
        every_source(&src_of(front), &mut files);
        files.sort();
        for file in files {
            let code = strip(&std::fs::read_to_string(&file).unwrap());
            for (n, line) in code.lines().enumerate() {
                let at = format!("{}:{}", file.display(), n + 1);
                found.extend(std::iter::repeat_n(at, builds(line, &types)));
            }
            scanned.push(file);
        }
    }
    (found, scanned)
}

#[test]
fn front_ends_build_no_documents() {
    // The scan sees a build in code and none in a comment, a view of a job's document by its
    // type's name (reproduce's `Summary`) but not a type of another name that ends like it, a
    // part of a document (`app/document/`'s, a job's document's) by `::new(` or `::from(`, and
    // the feasibility's `postures` called or imported, but not a name that starts like it.
    let types = job_document_types();
    for name in [
        "Document",
        "Summary",
        "Proposal",
        "Named",
        "Row",
        "Criteria",
        "CalibrationDoc",
        "CandidatesDoc",
        "Posture",
        "Checks",
        "Without",
    ] {
        assert!(types.contains(name), "{name} among {types:?}");
    }
    let sample = "let doc = Document::new(&report, setup); // Document::new(&report)\n\
                  let scene = job::document::scene(&report, setup)?;\n\
                  let summary = Summary::new(&report); let s = document::Summary::new(&r);\n\
                  let other = MySummary::new(); let text = \"Summary::new(\";\n\
                  let c = Criteria::from(e); let k = CandidatesDoc::from(v); // Checks::from(f)\n\
                  let w = document::Without::from(&r.without_pct); let m = MyCriteria::from(e);\n\
                  let d = CalibrationDoc::new(o, c); let t = String::from(\"Criteria::from(\");\n\
                  use stiffid::app::document::feasibility::postures;\n\
                  let p = feasibility::postures(&checks); let q = feasibility::postures_deg(&g);";
    let seen: usize = strip(sample).lines().map(|l| builds(l, &types)).sum();
    assert_eq!(seen, 10);
    let (found, scanned) = front_end_documents();
    // It reads both front ends, the command's plan report among them.
    for file in ["stiffid-cli/src/report/plan.rs", "stiffid-py/src/plan.rs"] {
        assert!(scanned.iter().any(|f| f.ends_with(file)), "{file}");
    }
    assert_eq!(
        found.len(),
        FRONT_END_DOCUMENTS,
        "a front end builds a document the job should return: {found:#?}"
    );
}

/// The fields of Rust source `code` written through a unit adapter of `app/document/units.rs`
/// (`serialize_with = "units::..."`, in a field's attributes, not in a comment): each one's line
/// (1-based, the adapter's) and its doc comment, its lines joined by a space (empty without one).
fn adapted_fields(code: &str) -> Vec<(usize, String)> {
    let lines: Vec<&str> = code.lines().map(str::trim).collect();
    let mut fields = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        if line.starts_with("//") || !line.contains("serialize_with = \"units::") {
            continue;
        }
        // Up over the field's attributes (an attribute over several lines: its `key = value`
        // lines and its `)]`), then its doc comment.
        let above = lines[..i].iter().rev().skip_while(|l| {
            let attribute = l.starts_with("#[") || l.starts_with(")]") || l.contains('=');
            attribute && !l.starts_with("//")
        });
        let mut doc: Vec<&str> = (above.map_while(|l| l.strip_prefix("///")))
            .map(str::trim)
            .collect();
        doc.reverse();
        fields.push((i + 1, doc.join(" ")));
    }
    fields
}

/// Every field the jobs write through a unit adapter holds one unit (SI) and is written in
/// another: its doc comment, which a Rust user reads and the document's schema describes the key
/// with, says both (`: m, written in mm.`, the convention of `app/document/units.rs`).
#[test]
fn every_field_written_through_a_unit_adapter_says_both_units() {
    let said = |doc: &str| doc.contains("written in");
    let (mut found, mut silent) = (0, Vec::new());
    for (file, code) in library_files("stiffid") {
        if !file.starts_with("app") {
            continue;
        }
        for (line, doc) in adapted_fields(&code) {
            found += 1;
            if !said(&doc) {
                silent.push(format!("stiffid/src/{}:{line}: {doc:?}", file.display()));
            }
        }
    }
    assert!(found >= 45, "{found} fields written through a unit adapter");
    assert!(
        silent.is_empty(),
        "say the unit a field holds and the one it is written in (`: m, written in mm.`): {silent:#?}"
    );
    // The scan finds a field's doc over its attributes (one over several lines among them), a
    // field without a doc, and no adapter named in a comment; a doc naming the written unit only
    // fails.
    let sample = "pub struct S {\n\
                  /// A length: m, written\n\
                  /// in mm.\n\
                  #[serde(rename = \"a_mm\", serialize_with = \"units::mm\")]\n\
                  pub a: f64,\n\
                  /// A length, mm (`serialize_with = \"units::mm\"`).\n\
                  #[cfg_attr(feature = \"schema\", schemars(with = \"Option<f64>\"))]\n\
                  #[serde(\n\
                      rename = \"b_mm\",\n\
                      serialize_with = \"units::mm_option\"\n\
                  )]\n\
                  pub b: Option<f64>,\n\
                  #[serde(serialize_with = \"units::plain3\")]\n\
                  pub c: Vector3<f64>,\n\
                  }\n";
    let fields = adapted_fields(sample);
    let docs: Vec<(usize, &str)> = fields.iter().map(|(l, d)| (*l, d.as_str())).collect();
    assert_eq!(
        docs,
        [
            (4, "A length: m, written in mm."),
            (10, "A length, mm (`serialize_with = \"units::mm\"`)."),
            (13, ""),
        ]
    );
    let silent: Vec<usize> = (fields.iter())
        .filter(|(_, d)| !said(d))
        .map(|(l, _)| *l)
        .collect();
    assert_eq!(silent, [10, 13]);
}

/// Every angle triple the library writes (CSV columns, documents, robot programs' A B C and W P R,
/// URDF and robot files) comes from `robot::file::rpy`, which gives the rotation back at any
/// pitch: nalgebra's `euler_angles()` misses it by degrees within 1e-6 deg of pitch +-90 (a
/// KUKA `B 90`, a tool pointing down a ROS `tool0`), so no library file calls it.
#[test]
fn angles_are_written_by_rpy_not_by_euler_angles() {
    let calls: Vec<String> = (CRATES.iter())
        .flat_map(|c| stripped_library_files(c))
        .filter(|(_, code)| code.contains(".euler_angles()"))
        .map(|(path, _)| path.display().to_string())
        .collect();
    assert!(calls.is_empty(), "{calls:?}");
}
