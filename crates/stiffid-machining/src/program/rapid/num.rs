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

/// The value of the expression `text` with the data `nums` (module docs), or why it has none.
pub(super) fn value(
    text: &str,
    nums: &dyn Fn(&str) -> Option<std::result::Result<f64, String>>,
) -> std::result::Result<f64, String> {
    let tokens = tokens(text)?;
    let mut at = 0;
    let v = sum(&tokens, &mut at, nums, 0)?;
    match at == tokens.len() && v.is_finite() {
        true => Ok(v),
        false => Err(format!(
            "'{}' is not arithmetic of numbers and num data stiffid reads",
            text.trim()
        )),
    }
}

/// A token: a number, a name (lower case) or an operator.
#[derive(Debug, Clone, PartialEq)]
enum Token {
    Number(f64),
    Name(String),
    Op(char),
}

/// The tokens of `text`.
fn tokens(text: &str) -> std::result::Result<Vec<Token>, String> {
    let mut out = Vec::new();
    let b = text.as_bytes();
    let mut i = 0;
    while i < b.len() {
        let c = b[i] as char;
        if c.is_ascii_whitespace() {
            i += 1;
        } else if "+-*/()".contains(c) {
            out.push(Token::Op(c));
            i += 1;
        } else if c.is_ascii_digit() || c == '.' {
            let (v, span) = crate::program::number_at(text, i)
                .ok_or_else(|| format!("'{}': not a number at '{}'", text.trim(), &text[i..]))?;
            out.push(Token::Number(v));
            i = span.end;
        } else if c.is_ascii_alphabetic() {
            let end = (text[i..].find(|c: char| !(c.is_ascii_alphanumeric() || c == '_')))
                .map_or(text.len(), |e| i + e);
            out.push(Token::Name(text[i..end].to_ascii_lowercase()));
            i = end;
        } else {
            return Err(format!(
                "'{}' holds '{c}', which stiffid does not evaluate",
                text.trim()
            ));
        }
    }
    Ok(out)
}

/// The most nested parentheses and signs read.
const DEPTH: usize = 32;

type Lookup<'a> = &'a dyn Fn(&str) -> Option<std::result::Result<f64, String>>;

fn sum(
    t: &[Token],
    at: &mut usize,
    nums: Lookup,
    depth: usize,
) -> std::result::Result<f64, String> {
    let mut v = product(t, at, nums, depth)?;
    while let Some(Token::Op(op @ ('+' | '-'))) = t.get(*at) {
        *at += 1;
        let w = product(t, at, nums, depth)?;
        v = if *op == '+' { v + w } else { v - w };
    }
    Ok(v)
}

fn product(
    t: &[Token],
    at: &mut usize,
    nums: Lookup,
    depth: usize,
) -> std::result::Result<f64, String> {
    let mut v = factor(t, at, nums, depth)?;
    while let Some(Token::Op(op @ ('*' | '/'))) = t.get(*at) {
        *at += 1;
        let w = factor(t, at, nums, depth)?;
        v = if *op == '*' { v * w } else { v / w };
    }
    Ok(v)
}

fn factor(
    t: &[Token],
    at: &mut usize,
    nums: Lookup,
    depth: usize,
) -> std::result::Result<f64, String> {
    if depth > DEPTH {
        return Err("an expression nested too deep".into());
    }
    let token = t.get(*at).cloned();
    *at += 1;
    match token {
        Some(Token::Number(v)) => Ok(v),
        Some(Token::Op('-')) => Ok(-factor(t, at, nums, depth + 1)?),
        Some(Token::Op('+')) => factor(t, at, nums, depth + 1),
        Some(Token::Op('(')) => {
            let v = sum(t, at, nums, depth + 1)?;
            match t.get(*at) {
                Some(Token::Op(')')) => {
                    *at += 1;
                    Ok(v)
                }
                _ => Err("an unclosed '('".into()),
            }
        }
        Some(Token::Name(n)) if matches!(t.get(*at), Some(Token::Op('('))) => {
            Err(format!("{n}(..), a function the controller computes"))
        }
        Some(Token::Name(n)) => match nums(&n) {
            Some(v) => v,
            None => Err(format!(
                "{n} is not a num declared with a value in this module or the task's"
            )),
        },
        _ => Err("an incomplete expression".into()),
    }
}

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

    /// The module's `num` data, each one a statement sets (`assignments` too) the run's.
    pub(super) fn finish(mut self, assignments: &[(String, u64)]) -> Nums {
        let setters = std::mem::take(&mut self.setters);
        set(
            &mut self.nums,
            &self.constants,
            assignments.iter().chain(&setters),
        );
        self.nums
    }
}
