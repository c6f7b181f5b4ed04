//! Python's defaults are generated from the command's declaration of its options: the default
//! of every keyword of a job's Python function that names one of its command's options
//! (`level=`, `--level`; the pairs of [`FRONT_ENDS`]) is written into the function's PyO3
//! signature (`crates/stiffid-py/src/*.rs`) as the option's default, by
//!
//!     cargo test -p stiffid-cli --test it -- --ignored write_python_defaults
//!
//! and `python_defaults_are_the_commands` fails while a signature differs from what it writes
//! (as `crates/stiffid-py/tools/stubs.py --check` does for the document stubs).

use super::options_defined_once::{
    balanced, commands, default, options, repo, same_default, FRONT_ENDS,
};
use std::collections::BTreeMap;

/// A default of the command's as a Python literal in the style of the signature's `given`
/// (a text quoted, a number as it is, several values a tuple).
fn literal(clap: &str, given: &str) -> String {
    match (given.starts_with('"'), clap.contains(',')) {
        (true, _) => format!("\"{clap}\""),
        (false, true) => format!("({})", clap.replace(',', ", ")),
        (false, false) => clap.to_string(),
    }
}

/// The signature's parameters (`inner`, the text between its parentheses) with each keyword's
/// default that names an option of `cmd` (not one of `one_sided`) written as the option's.
fn generated_parameters(inner: &str, cmd: &clap::Command, one_sided: &[&str]) -> String {
    let opts: BTreeMap<String, &clap::Arg> = (options(cmd).into_iter())
        .map(|a| (a.get_long().unwrap().replace('-', "_"), a))
        .collect();
    let (mut out, mut depth, mut quoted, mut start) = (String::new(), 0, false, 0);
    let parameter = |p: &str, out: &mut String| {
        let rewritten = p.split_once('=').and_then(|(k, v)| {
            let (name, value) = (k.trim(), v.trim());
            let arg = opts.get(name).filter(|_| !one_sided.contains(&name))?;
            let clap = default(arg)?;
            (!same_default(Some(value), arg)).then(|| {
                let lead = &p[..p.len() - p.trim_start().len()];
                format!("{lead}{name}={}", literal(&clap, value))
            })
        });
        out.push_str(&rewritten.unwrap_or_else(|| p.to_string()));
    };
    for (i, c) in inner.char_indices() {
        match c {
            '"' => quoted = !quoted,
            '(' | '[' if !quoted => depth += 1,
            ')' | ']' if !quoted => depth -= 1,
            ',' if !quoted && depth == 0 => {
                parameter(&inner[start..i], &mut out);
                out.push(',');
                start = i + 1;
            }
            _ => {}
        }
    }
    parameter(&inner[start..], &mut out);
    out
}

/// A Python source's text with the defaults of its jobs' signatures generated from the
/// command's declaration ([`generated_parameters`]).
fn generated(text: &str, commands: &BTreeMap<String, clap::Command>) -> String {
    const OPEN: &str = "#[pyo3(signature = (";
    let (mut out, mut rest) = (String::new(), text);
    while let Some(at) = rest.find(OPEN) {
        out.push_str(&rest[..at + OPEN.len()]);
        rest = &rest[at + OPEN.len()..];
        let inner = balanced(rest);
        let name: String = (rest[inner.len()..].split("fn ").nth(1).unwrap_or_default())
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        let front = FRONT_ENDS.iter().find(|(_, function, _)| *function == name);
        match front {
            Some((command, _, one_sided)) => {
                let sided: Vec<&str> = one_sided.iter().map(|(n, _)| *n).collect();
                out.push_str(&generated_parameters(inner, &commands[*command], &sided));
            }
            None => out.push_str(inner),
        }
        rest = &rest[inner.len()..];
    }
    out + rest
}

/// Every Python source file of the package with its text and the text generated from it.
fn sources() -> Vec<(std::path::PathBuf, String, String)> {
    let commands: BTreeMap<String, clap::Command> = commands().into_iter().collect();
    let dir = repo().join("crates/stiffid-py/src");
    let mut files: Vec<_> = (std::fs::read_dir(dir).unwrap())
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "rs"))
        .collect();
    files.sort();
    (files.into_iter())
        .map(|p| {
            let text = std::fs::read_to_string(&p).unwrap();
            let want = generated(&text, &commands);
            (p, text, want)
        })
        .collect()
}

#[test]
fn python_defaults_are_the_commands() {
    let differ: Vec<String> = (sources().into_iter())
        .filter(|(_, text, want)| text != want)
        .map(|(p, _, _)| p.display().to_string())
        .collect();
    assert!(
        differ.is_empty(),
        "Python's defaults differ from the command's in {differ:?}: cargo test -p stiffid-cli --test it -- --ignored write_python_defaults"
    );
}

#[test]
fn the_generator_writes_a_changed_default_as_the_commands() {
    let commands: BTreeMap<String, clap::Command> = commands().into_iter().collect();
    let text = "#[pyo3(signature = (setup, *, level=0.9, frame=\"tool\", figures=false))]\npub fn compensate() {}";
    let want = "#[pyo3(signature = (setup, *, level=0.95, frame=\"base\", figures=false))]\npub fn compensate() {}";
    assert_eq!(generated(text, &commands), want);
}

#[test]
#[ignore = "writes crates/stiffid-py/src: run to regenerate Python's defaults"]
fn write_python_defaults() {
    for (path, text, want) in sources() {
        if text != want {
            std::fs::write(path, want).unwrap();
        }
    }
}
