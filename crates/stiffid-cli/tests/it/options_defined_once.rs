//! Each option is declared once, in the command's parser (`stiffid_cli::command`: its name,
//! value, help with its range and unit, default), and what repeats it elsewhere is checked
//! against that declaration so the three cannot drift:
//! - the reference's option tables (`docs/reference.md`, the first `| option | meaning |` table
//!   of each command's section): the same options in the same order, each row stating the
//!   option's default (`[default: X]`, `the default X`) and every range its help states (`A to
//!   B`, `A <= value <= B`);
//! - the Python keywords of the same jobs (their PyO3 signatures in `crates/stiffid-py/src`): a
//!   keyword and an option of the same name (`margin_deg`, `--margin-deg`) have the same default,
//!   and a name in one front end only is one of the differences listed here, each with why
//!   (the defaults are written there from the command's, `python_defaults`).

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

pub(crate) fn repo() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// Every visible subcommand by its path (`compensate`, `setups new`).
pub(crate) fn commands() -> Vec<(String, clap::Command)> {
    fn walk(prefix: &str, cmd: &clap::Command, out: &mut Vec<(String, clap::Command)>) {
        for sub in cmd.get_subcommands().filter(|s| !s.is_hide_set()) {
            let name = format!("{prefix}{}", sub.get_name());
            out.push((name.clone(), sub.clone()));
            walk(&format!("{name} "), sub, out);
        }
    }
    let mut out = Vec::new();
    walk("", &stiffid_cli::command(), &mut out);
    out
}

/// The visible options of `cmd` with a long name (positionals and `--help` left out).
pub(crate) fn options(cmd: &clap::Command) -> Vec<&clap::Arg> {
    (cmd.get_arguments())
        .filter(|a| !a.is_hide_set() && !a.is_positional())
        .filter(|a| a.get_long().is_some_and(|l| l != "help" && l != "version"))
        .collect()
}

/// The option's default as clap states it (`5`, `-180,180`), or `None`.
pub(crate) fn default(arg: &clap::Arg) -> Option<String> {
    let values: Vec<String> = (arg.get_default_values().iter())
        .map(|v| v.to_string_lossy().into_owned())
        .collect();
    match arg.get_action().takes_values() && !values.is_empty() {
        true => Some(values.join(",")),
        false => None,
    }
}

/// The help of `arg` as one line.
fn help(arg: &clap::Arg) -> String {
    let help = (arg.get_long_help().or(arg.get_help()))
        .map(|h| h.to_string())
        .unwrap_or_default();
    help.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// The reference's option rows of the section `### `stiffid NAME``: its first table headed
/// `| option | meaning |`, each row's option name (`margin-deg`) and its meaning.
fn reference_rows(reference: &str, name: &str) -> Option<Vec<(String, String)>> {
    let heading = format!("### `stiffid {name}`\n");
    let start = reference.find(&heading)? + heading.len();
    let rest = &reference[start..];
    let end = rest
        .find("\n## ")
        .into_iter()
        .chain(rest.find("\n### "))
        .min();
    let section = &rest[..end.unwrap_or(rest.len())];
    let Some(table) = section.find("| option | meaning |") else {
        return Some(Vec::new());
    };
    let rows = (section[table..].lines().skip(2))
        .take_while(|l| l.starts_with('|'))
        .filter_map(|l| l.trim_start_matches("| ").split_once(" | "))
        .flat_map(|(cell, meaning)| {
            // A row may name several options (`--tolerance-mm <L>`, `--tolerance-deg <A>`).
            let meaning = meaning.trim_end_matches(" |").to_string();
            (cell.split("`--").skip(1))
                .map(|l| {
                    l.chars()
                        .take_while(|c| c.is_alphanumeric() || *c == '-')
                        .collect()
                })
                .map(move |long: String| (long, meaning.clone()))
                .collect::<Vec<_>>()
        })
        .collect();
    Some(rows)
}

/// The numeric ranges a help states: `A to B` and `A <= value <= B`, as pairs of numbers.
fn ranges(text: &str) -> BTreeSet<(String, String)> {
    let words: Vec<&str> = text
        .split(|c: char| c.is_whitespace() || "()[],;:".contains(c))
        .filter(|w| !w.is_empty())
        .collect();
    let number = |w: &str| w.replace(' ', "").parse::<f64>().is_ok();
    let mut out = BTreeSet::new();
    for k in 1..words.len().saturating_sub(1) {
        let (a, b) = (words[k - 1], words[k + 1]);
        if words[k] == "to" && number(a) && number(b) {
            out.insert((a.to_string(), b.to_string()));
        }
        if words[k] == "value"
            && k >= 2
            && k + 2 < words.len()
            && words[k - 1] == "<="
            && words[k + 1] == "<="
        {
            out.insert((words[k - 2].to_string(), words[k + 2].to_string()));
        }
    }
    out
}

/// Whether the reference's `meaning` states the default `d` (`[default: 5]`, `the default 5`,
/// `(default `5`)`, `` `5` (default)``), or, without one, states no `[default: X]` unless the
/// option's help names `X` as what it falls back to.
fn states_default(meaning: &str, d: Option<&str>, help: &str) -> bool {
    match d {
        None => match meaning.split_once("[default: ") {
            None => true,
            Some((_, rest)) => {
                let x = rest.split(']').next().unwrap_or_default();
                help.contains("default") && help.contains(x)
            }
        },
        Some(d) => [
            format!("[default: {d}]"),
            format!("default {d}"),
            format!("default: {d}"),
            format!("default `{d}`"),
            format!("`{d}` (default"),
        ]
        .iter()
        .any(|f| meaning.contains(f.as_str())),
    }
}

#[test]
fn the_references_option_tables_name_each_option_with_its_default_and_ranges() {
    let reference = std::fs::read_to_string(repo().join("docs/reference.md")).unwrap();
    let mut drift = Vec::new();
    for (name, cmd) in commands() {
        let declared = options(&cmd);
        let Some(rows) = reference_rows(&reference, &name) else {
            drift.push(format!(
                "docs/reference.md: no section ### `stiffid {name}`"
            ));
            continue;
        };
        let names: Vec<&str> = rows.iter().map(|(n, _)| n.as_str()).collect();
        let longs: Vec<&str> = declared.iter().map(|a| a.get_long().unwrap()).collect();
        if names != longs {
            drift.push(format!(
                "stiffid {name}: the reference's options {names:?}, the command's {longs:?}"
            ));
            continue;
        }
        for (arg, (long, meaning)) in declared.iter().zip(&rows) {
            let d = default(arg);
            if !states_default(meaning, d.as_deref(), &help(arg)) {
                drift.push(format!(
                    "stiffid {name} --{long}: the reference does not state the default {d:?}"
                ));
            }
            // Every range the command states is the reference's (which may say more).
            let (stated, given) = (ranges(meaning), ranges(&help(arg)));
            if !given.is_subset(&stated) {
                drift.push(format!(
                    "stiffid {name} --{long}: the reference's ranges {stated:?}, the command's {given:?}"
                ));
            }
        }
    }
    assert!(
        drift.is_empty(),
        "docs/reference.md's option tables differ from the command's declarations:\n{}",
        drift.join("\n")
    );
}

/// A Python function's keywords with their defaults as written in its PyO3 signature
/// (`None` for a parameter without one), `*` and `**` left out.
type Signature = BTreeMap<String, Option<String>>;

/// Every `#[pyo3(signature = (...))]` of the Python package's sources, by function name (a name
/// given twice, such as two `from_file`, is left out).
fn python_signatures() -> BTreeMap<String, Signature> {
    let dir = repo().join("crates/stiffid-py/src");
    let mut found: BTreeMap<String, Vec<Signature>> = BTreeMap::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let text = std::fs::read_to_string(entry.unwrap().path()).unwrap();
        let mut rest = text.as_str();
        while let Some(at) = rest.find("#[pyo3(signature = (") {
            rest = &rest[at + "#[pyo3(signature = (".len()..];
            let inner = balanced(rest);
            let after = &rest[inner.len()..];
            let name = after.split("fn ").nth(1).unwrap();
            let name: String = name
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            found.entry(name).or_default().push(parameters(inner));
        }
    }
    (found.into_iter())
        .filter(|(_, v)| v.len() == 1)
        .map(|(k, mut v)| (k, v.remove(0)))
        .collect()
}

/// The text up to the `)` that closes the signature's tuple.
pub(crate) fn balanced(text: &str) -> &str {
    let (mut depth, mut quoted) = (0i32, false);
    for (i, c) in text.char_indices() {
        match c {
            '"' => quoted = !quoted,
            '(' | '[' if !quoted => depth += 1,
            ')' | ']' if !quoted && depth == 0 => return &text[..i],
            ')' | ']' if !quoted => depth -= 1,
            _ => {}
        }
    }
    text
}

/// The parameters of a signature's text, split at its top-level commas.
fn parameters(text: &str) -> Signature {
    let (mut out, mut current, mut depth, mut quoted) = (Signature::new(), String::new(), 0, false);
    for c in text.chars().chain([',']) {
        match c {
            '"' => quoted = !quoted,
            '(' | '[' if !quoted => depth += 1,
            ')' | ']' if !quoted => depth -= 1,
            ',' if !quoted && depth == 0 => {
                let p = std::mem::take(&mut current);
                let p = p.trim();
                if !p.is_empty() && !p.starts_with('*') {
                    match p.split_once('=') {
                        Some((k, v)) => out.insert(k.trim().into(), Some(v.trim().into())),
                        None => out.insert(p.into(), None),
                    };
                }
                continue;
            }
            _ => {}
        }
        current.push(c);
    }
    out
}

/// Whether a Python default and the option's agree: numbers equal as numbers (tuples element by
/// element against comma-separated values), texts equal, `false` for a switch, `None` for an
/// option without a default.
pub(crate) fn same_default(python: Option<&str>, option: &clap::Arg) -> bool {
    let clap = default(option);
    let switch = !option.get_action().takes_values();
    match (python, clap.as_deref()) {
        (None, _) => true,
        (Some("None"), None) => true,
        (Some("false"), None) => switch,
        (Some(p), Some(c)) => {
            let p = p.trim_matches(|ch| ch == '(' || ch == ')' || ch == '"');
            let numbers = |s: &str| -> Option<Vec<f64>> {
                s.split(',').map(|x| x.trim().parse::<f64>().ok()).collect()
            };
            match (numbers(p), numbers(c)) {
                (Some(a), Some(b)) => a == b,
                _ => p == c,
            }
        }
        _ => false,
    }
}

/// The Python function of each command, and the names that are in one front end only: the
/// keyword (or option, `--` spelt as `_`) and why.
/// A command, its Python function and the names in one front end only, each with why.
pub(crate) type FrontEnd = (
    &'static str,
    &'static str,
    &'static [(&'static str, &'static str)],
);

pub(crate) const FRONT_ENDS: &[FrontEnd] = &[
    (
        "compensate",
        "compensate",
        &[
            ("json", "the command's output form"),
            (
                "report",
                "the command's report directory; Python returns figures=True",
            ),
            ("out", "the CSV the command writes; Python returns arrays"),
            ("figures", "Python's figures as SVG strings"),
            (
                "output",
                "the command takes the language from --out's extension",
            ),
            (
                "program_name",
                "the command names the program after --out's stem",
            ),
            (
                "csv",
                "the program's CSV the command writes; Python returns arrays",
            ),
        ],
    ),
    (
        "place",
        "place",
        &[
            ("json", "the command's output form"),
            (
                "out",
                "the setup the command writes; Python returns setup_text",
            ),
        ],
    ),
    (
        "identify",
        "identify",
        &[
            ("json", "the command's output form"),
            (
                "out",
                "the stiffness file the command writes; Python returns the document",
            ),
            (
                "report",
                "the command's report directory; Python's figures(document)",
            ),
            ("data", "Python's measurements= (a file or arrays)"),
            ("measurements", "the command's --data"),
            ("q_deg", "Python's measurements as arrays"),
            ("wrench", "Python's measurements as arrays"),
            ("displacement_mm", "Python's measurements as arrays"),
            ("point", "Python's measurements as arrays"),
        ],
    ),
    (
        "validate",
        "validate",
        &[
            ("json", "the command's output form"),
            ("data", "Python's measurements= (a file or arrays)"),
            ("measurements", "the command's --data"),
            ("q_deg", "Python's measurements as arrays"),
            ("wrench", "Python's measurements as arrays"),
            ("displacement_mm", "Python's measurements as arrays"),
            ("point", "Python's measurements as arrays"),
            (
                "stiffness",
                "Python's stiffness_nm_per_rad= (numbers or a stiffness file)",
            ),
            ("stiffness_nm_per_rad", "the command's --stiffness"),
        ],
    ),
    (
        "predict",
        "predict",
        &[
            ("json", "the command's output form"),
            (
                "stiffness",
                "Python's stiffness_nm_per_rad= and its covariance as arrays",
            ),
            ("stiffness_nm_per_rad", "the command's --stiffness file"),
            (
                "compliance_covariance_rad2_per_nm2",
                "the command's --stiffness file",
            ),
        ],
    ),
    (
        "calibrate",
        "calibrate",
        &[
            ("json", "the command's output form"),
            (
                "report",
                "the command's report directory; Python's figures(document)",
            ),
            ("data", "Python's readings="),
            ("readings", "the command's --data"),
            (
                "update",
                "the command's --update [LIST]: Python's update=True and update_parameters",
            ),
            ("update_parameters", "the command's --update LIST"),
        ],
    ),
    (
        "calibrate-cell",
        "calibrate_cell",
        &[
            ("json", "the command's output form"),
            (
                "out",
                "the setup fragment the command writes; Python returns the document",
            ),
            ("data", "Python's readings="),
            ("readings", "the command's --data"),
        ],
    ),
    (
        "register",
        "register",
        &[
            ("json", "the command's output form"),
            (
                "out",
                "the file the command writes; Python returns the document",
            ),
            ("data", "Python's readings="),
            ("readings", "the command's --data"),
            (
                "postures",
                "refused in Python too: renamed count (its message)",
            ),
        ],
    ),
    (
        "simulate",
        "simulate",
        &[
            ("json", "the command's output form"),
            (
                "out",
                "the directory the command writes; Python returns the document",
            ),
            ("force", "the command's overwrite of --out"),
            ("postures", "Python's groups= (arrays)"),
            ("groups", "the command's --postures files"),
        ],
    ),
    (
        "reproduce",
        "reproduce",
        &[
            (
                "out",
                "the directory the command writes; Python returns the document",
            ),
            ("force", "the command's overwrite of --out"),
            ("figures", "Python's figures as SVG strings"),
            (
                "setup",
                "Python's None is the command's default, the paper's built-in setup",
            ),
        ],
    ),
    (
        "force",
        "process_force",
        &[("json", "the command's output form")],
    ),
    (
        "setups new",
        "setups_new",
        &[("package_paths", "the command's global --package-path")],
    ),
    (
        "select",
        "select",
        &[
            ("json", "the command's output form"),
            (
                "out",
                "the postures file the command writes; Python returns the document",
            ),
            ("report", "the command's plan directory; Python's plan(...)"),
            ("force", "the command's overwrite of --out"),
            ("setup", "a method of Python's Setup"),
            ("count", "Python's n="),
            ("n", "the command's --count"),
            ("for", "Python's purpose= (for is a Python keyword)"),
            ("purpose", "the command's --for"),
            (
                "global",
                "Python's method=\"global\" (global is a Python keyword)",
            ),
            ("start_random", "Python's start="),
            ("method", "the command's --global and --pool"),
            ("station", "Python's stations= (a list)"),
            ("stations", "the command's --station, repeated"),
        ],
    ),
    (
        "evaluate",
        "evaluate",
        &[
            ("json", "the command's output form"),
            ("setup", "a method of Python's Setup"),
            ("postures", "Python's postures_deg= (arrays)"),
            ("postures_deg", "the command's --postures file"),
            ("for", "Python's purpose= (for is a Python keyword)"),
            ("purpose", "the command's --for"),
        ],
    ),
    (
        "kinematics",
        "kinematics",
        &[
            ("json", "the command's output form"),
            ("setup", "a method of Python's Robot"),
            ("robot", "a method of Python's Robot"),
            ("tip", "Python's Robot.from_file(path, tip)"),
            (
                "point_mm",
                "Python's None is the command's default, the flange origin",
            ),
        ],
    ),
];

#[test]
fn python_keywords_and_the_commands_options_agree_on_names_and_defaults() {
    let signatures = python_signatures();
    let commands: BTreeMap<String, clap::Command> = commands().into_iter().collect();
    let mut drift = Vec::new();
    for (command, function, one_sided) in FRONT_ENDS {
        let cmd = &commands[*command];
        let Some(python) = signatures.get(*function) else {
            drift.push(format!("Python has no function {function}"));
            continue;
        };
        let opts: BTreeMap<String, &clap::Arg> = (options(cmd).into_iter())
            .map(|a| (a.get_long().unwrap().replace('-', "_"), a))
            .collect();
        let allowed: BTreeSet<&str> = one_sided.iter().map(|(n, _)| *n).collect();
        for (name, value) in python {
            let listed = allowed.contains(name.as_str());
            match opts.get(name) {
                // Listed on both sides: the same meaning spelt differently (None for the default).
                Some(arg) if listed && same_default(value.as_deref(), arg) => drift.push(format!(
                    "{command}: {name} agrees in both front ends: remove it from FRONT_ENDS"
                )),
                Some(_) if listed => {}
                Some(arg) if !same_default(value.as_deref(), arg) => drift.push(format!(
                    "{command}: Python's {name}={} but --{} defaults to {:?}",
                    value.as_deref().unwrap_or("(required)"),
                    arg.get_long().unwrap(),
                    default(arg)
                )),
                Some(_) => {}
                None if listed => {}
                None => drift.push(format!(
                    "{command}: Python's keyword {name} has no option --{}",
                    name.replace('_', "-")
                )),
            }
        }
        for name in opts
            .keys()
            .filter(|n| !python.contains_key(*n) && !allowed.contains(n.as_str()))
        {
            drift.push(format!(
                "{command}: the option --{} has no Python keyword {name}",
                name.replace('_', "-")
            ));
        }
        for name in allowed
            .iter()
            .filter(|n| !python.contains_key(**n) && !opts.contains_key(**n))
        {
            drift.push(format!(
                "{command}: {name} is in neither front end: remove it from FRONT_ENDS"
            ));
        }
    }
    assert!(
        drift.is_empty(),
        "the front ends disagree:\n{}",
        drift.join("\n")
    );
}
