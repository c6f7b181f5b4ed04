//! RAPID `num` data and arithmetic the module states (*RAPID kernel*: expressions): a `num`
//! declared with a value (`CONST num dz := 50;`, also `VAR`, `PERS`, `dnum`) that no statement
//! of the task sets (an assignment, `Incr`, `Decr`, `Add`, `Clear`, a read from the pendant or a
//! file, a procedure call it is passed to), and the arithmetic of numbers and such data (`+`,
//! `-`, `*`, `/`, parentheses): its value is the module's, which `Offs`, `RelTool` and an array's
//! index read. Anything else (a function, `DIV`, `MOD`, a datum the run sets) is the run's.

use std::collections::HashMap;

/// A module's `num` data by lower-case name: the value, or why the module does not state it.
pub(super) type Nums = HashMap<String, std::result::Result<f64, String>>;

/// The instructions whose first argument a `num` they set (lower case).
const SETTERS: &[&str] = &[
    "incr",
    "decr",
    "add",
    "clear",
    "tpreadnum",
    "tpreaddnum",
    "getdataval",
    "readnum",
    "readanybin",
    "readbin",
];

pub(super) use crate::program::arithmetic::value;

/// The `num` data a module sets as it runs (module docs): each one's name (lower case) and the
/// line, from its statements' text `body` on `line` (first word `first`, lower case).
pub(super) fn set_by(first: &str, body: &str, line: u64, out: &mut Vec<(String, u64)>) {
    let t = body.trim_start();
    let rest = t.get(first.len()..).unwrap_or("").trim_start();
    let rest = rest.trim_end().trim_end_matches(';');
    if SETTERS.contains(&first) {
        let arg = rest.split(',').next().unwrap_or("").trim();
        out.push((
            arg.split(['.', '{'])
                .next()
                .unwrap_or(arg)
                .to_ascii_lowercase(),
            line,
        ));
        return;
    }
    // A procedure call: each datum it is passed may be set through its parameter.
    if super::calls::called(body, first).is_some() {
        for a in super::arguments::top_level(rest) {
            let a = rest[a].trim();
            let a = a.rsplit(":=").next().unwrap_or(a).trim();
            if a.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') && !a.is_empty() {
                out.push((a.to_ascii_lowercase(), line));
            }
        }
    }
}

/// The value of the `num` `name` declared by the statement `body` on `line`, the data declared
/// before it `nums`; or why it has none.
pub(super) fn declared(
    name: &str,
    body: &str,
    line: u64,
    nums: &Nums,
) -> std::result::Result<f64, String> {
    let Some(eq) = body.find(":=").filter(|_| !name.contains('{')) else {
        return Err(format!(
            "num {name} is declared on line {line} without a value or as an array"
        ));
    };
    let expr = body[eq + 2..].trim_end().trim_end_matches(';');
    value(expr, &|n| nums.get(n).cloned()).map_err(|why| format!("num {name} (line {line}): {why}"))
}

/// `nums` with each datum that a statement of `set` (name, line) sets, but the `constants`, the
/// run's.
pub(super) fn set<'s>(
    nums: &mut Nums,
    constants: &[String],
    set: impl Iterator<Item = &'s (String, u64)>,
) {
    for (name, line) in set {
        if constants.contains(name) {
            continue;
        }
        if let Some(v) = nums.get_mut(name) {
            *v = Err(format!("num {name} is set on line {line}, so its value is the controller's as the module runs"));
        }
    }
}

/// The `num` data of a module as its statements are read: each one declared, the constants, and
/// the statements that set one.
#[derive(Debug, Default)]
pub(super) struct Reading {
    nums: Nums,
    constants: Vec<String>,
    setters: Vec<(String, u64)>,
}

impl Reading {
    /// The statement `body` on `line`, its words `words` (lower case, `LOCAL`/`TASK` skipped).
    pub(super) fn statement(&mut self, words: &[&str], body: &str, line: u64) {
        super::parameters::declare_nums(line, body, &mut self.nums);
        set_by(
            words.first().copied().unwrap_or(""),
            body,
            line,
            &mut self.setters,
        );
        if let ["const" | "var" | "pers", "num" | "dnum", name, ..] = words {
            let name = name.trim_end_matches(';');
            let value = declared(name, body, line, &self.nums);
            self.nums.insert(name.to_string(), value);
            if words[0] == "const" {
                self.constants.push(name.to_string());
            }
        }
    }

    /// The module's `num` data, each one a statement sets (`assignments` too) the run's; and
    /// those its routines set, followed along their paths (module `numflow`), of the module
    /// `code` (its `statements`).
    pub(super) fn finish(
        mut self,
        assignments: &[(String, u64)],
        (code, statements): (&str, &[super::Statement]),
    ) -> (Nums, super::numflow::Renum) {
        let setters = std::mem::take(&mut self.setters);
        let all: Vec<(String, u64)> = assignments.iter().chain(&setters).cloned().collect();
        let declared = (&self.nums, self.constants.as_slice());
        let followed = super::numflow::Renum::of((code, statements), declared, &all);
        set(&mut self.nums, &self.constants, all.iter());
        (self.nums, followed)
    }
}
