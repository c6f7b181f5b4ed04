//! The data a task's modules share (*RAPID kernel*: scope rules): a module's global data is
//! seen by every module of the task, its `LOCAL` data by itself alone. One name declared global
//! in two modules with two values is ambiguous (the controller refuses to load the task, or, for
//! a `PERS`, holds one value of the two): a motion reading it is refused naming both modules.

use super::{first_word, Statement};
use std::collections::HashMap;

/// A module's data declarations by lower-case name: the value as written (blanks left out,
/// lower case), the line, and whether `LOCAL` (seen by its own module alone).
pub(super) type Values = HashMap<String, (String, u64, bool)>;

/// The data declarations of the module `code` (comments blanked), its `statements`.
pub(super) fn values(code: &str, statements: &[Statement]) -> Values {
    let mut out = Values::new();
    for s in statements {
        let body = &code[s.span.clone()];
        let lower = body.to_ascii_lowercase();
        let local = first_word(&lower) == "local";
        let words: Vec<&str> = (lower.split(|c: char| c.is_whitespace() || c == ':' || c == '='))
            .filter(|w| !w.is_empty())
            .skip_while(|w| matches!(*w, "local" | "task"))
            .collect();
        let ["const" | "var" | "pers", _, name, ..] = words.as_slice() else {
            continue;
        };
        let name = name.trim_end_matches(';');
        let name = name.split('{').next().unwrap_or(name).to_string();
        let value = lower.find(":=").map_or("", |eq| &lower[eq + 2..]);
        let value: String = value.chars().filter(|c| !c.is_whitespace()).collect();
        out.entry(name).or_insert((value, s.line, local));
    }
    out
}

/// The names two modules of the task declare global with two values, each with why a motion
/// cannot read it: `own` the module's, each of `others` a backup module's file name and its
/// declarations. A name the module itself declares `LOCAL` hides the others' and is its own; a
/// `PERS` declared without a value takes the one declared with it.
pub(super) fn ambiguous(own: &Values, others: &[(&str, Values)]) -> HashMap<String, String> {
    let mut first: HashMap<&str, (&str, &str, u64)> = HashMap::new();
    for (name, (value, line, local)) in own {
        if !local && !value.is_empty() {
            first.insert(name, ("this module", value, *line));
        }
    }
    let mut out = HashMap::new();
    for (file, values) in others {
        for (name, (value, line, local)) in values {
            if *local || value.is_empty() || own.get(name).is_some_and(|o| o.2) {
                continue;
            }
            match first.get(name.as_str()) {
                None => _ = first.insert(name, (file, value, *line)),
                Some((_, v, _)) if v == value => {}
                Some((f, _, l)) => {
                    let why = format!("{name} is declared in {f} (line {l}) and in {file} (line {line}) with two values: the task shares one datum of a name, and the controller refuses a task declaring it twice (or holds one value of a PERS); give the task's modules one declaration, or declare it LOCAL in this module");
                    out.entry(name.clone()).or_insert(why);
                }
            }
        }
    }
    out
}
