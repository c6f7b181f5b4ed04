//! Claims of docs/ARCHITECTURE.md checked against the library's code: it reads no process state
//! but the worker threads' count (`common/threads.rs`); it lists folders only where both front
//! ends must follow one rule (core's `io/input.rs`: a backup's files, the data file beside a
//! program; `io/temporaries.rs`: an output's leftovers); a controller language's folder is named
//! outside it only by its registry line (the recipe for a new language).

use crate::layout::{stripped_library_files, CRATES};

/// The library files (`crate/path`) whose code, comments and strings blanked, holds `needle`.
fn holding(needle: &str) -> Vec<String> {
    (CRATES.iter())
        .flat_map(|c| {
            (stripped_library_files(c).into_iter())
                .filter(|(_, code)| code.contains(needle))
                .map(move |(path, _)| format!("{c}/{}", path.display()))
        })
        .collect()
}

#[test]
fn the_library_reads_no_environment_but_the_thread_count() {
    assert_eq!(holding("env::var"), ["stiffid-core/common/threads.rs"]);
    assert!(holding("env::set_var").is_empty());
}

#[test]
fn the_library_lists_folders_only_in_its_input_and_output_rules() {
    assert_eq!(
        holding("read_dir("),
        ["stiffid-core/io/input.rs", "stiffid-core/io/temporaries.rs"]
    );
}

/// Whether `code` names the module `name` as a path (`krl::`, not `xkrl::`).
fn names_module(code: &str, name: &str) -> bool {
    let path = format!("{name}::");
    code.match_indices(&path).any(|(at, _)| {
        let before = code[..at].chars().next_back();
        !before.is_some_and(|c| c.is_alphanumeric() || c == '_')
    })
}

#[test]
fn a_language_is_named_outside_its_folder_only_by_its_registry_line() {
    let languages = [
        ("krl", "Krl"),
        ("rapid", "Rapid"),
        ("ls", "FanucLs"),
        ("inform", "Inform"),
    ];
    let mut outside = Vec::new();
    for krate in CRATES {
        for (path, code) in stripped_library_files(krate) {
            let file = path.display().to_string();
            for (folder, variant) in languages {
                if file.starts_with(&format!("program/{folder}/")) {
                    continue;
                }
                let registry = format!("{variant} => {folder}::{variant},");
                let code = code.replace(&registry, "");
                if names_module(&code, folder) || code.contains(&format!("Dialect::{variant}")) {
                    outside.push(format!("{krate}/{file}: {folder}"));
                }
            }
        }
    }
    assert!(outside.is_empty(), "{outside:?}");
}

#[test]
fn a_module_path_is_told_from_a_longer_name() {
    assert!(names_module("use super::krl::Krl;", "krl"));
    assert!(names_module("krl::Krl", "krl"));
    assert!(!names_module("calls::x; Labels::y", "ls"));
}
