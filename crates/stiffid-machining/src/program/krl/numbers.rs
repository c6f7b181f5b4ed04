//! The numbers a KRL program reads: `REAL`, `INT` and `BOOL` data declared with a value in the
//! `.src`, its `.dat`, `$config.dat` or another module's public data list (`DECL REAL
//! rHeight=12.5`, `DECL GLOBAL INT nParts=4`, `DECL CONST BOOL bPre=TRUE`; KSS 8.x SI manual,
//! "Data lists", "Simple data types"), and the expressions that read them: arithmetic
//! ([`crate::program::arithmetic::value_krl`]), comparisons (`==`, `<>`, `<`, `>`, `<=`, `>=`),
//! `NOT`, `AND`, `OR`, `EXOR` (a `BOOL` is 1 or 0). A number the program assigns is followed as
//! its points are ([`super::assign`]): known after an assignment on every path, the last run's
//! before one.

use crate::program::arithmetic::value_krl;
use stiffid_core::common::limits::short;

/// A value and whether it is an `INT` (a `BOOL` is an `INT` 1 or 0 here).
pub(super) type Typed = (f64, bool);

/// The value of the KRL expression `text` (module docs) with the data `nums` (by lower-case
/// name), or why it has none.
pub(super) fn evaluate(
    text: &str,
    nums: crate::program::arithmetic::Lookup,
) -> Result<Typed, String> {
    nested(text, nums, 0)
}

/// The most nested logical operators and parentheses read.
const DEPTH: usize = 32;

/// [`evaluate`] at `depth` nested operators.
fn nested(
    text: &str,
    nums: crate::program::arithmetic::Lookup,
    depth: usize,
) -> Result<Typed, String> {
    if depth > DEPTH {
        return Err("a condition nested too deep".into());
    }
    let t = outer(text.trim());
    let ops = |word: &str| split_word(t, word);
    for word in ["OR", "EXOR", "AND"] {
        let parts = ops(word);
        if parts.len() < 2 {
            continue;
        }
        if parts.iter().any(|p| comparison(p).is_some()) {
            return Err(format!("'{}' compares beside {word} without parentheses, and KRL compares last ((a == 1) {word} (b == 2) is meant): write the parentheses", short(t)));
        }
        let mut values = Vec::with_capacity(parts.len());
        for p in &parts {
            values.push(nested(p, nums, depth + 1)?.0 != 0.0);
        }
        let v = match word {
            "OR" => values.iter().any(|b| *b),
            "AND" => values.iter().all(|b| *b),
            _ => values.iter().filter(|b| **b).count() % 2 == 1,
        };
        return Ok((f64::from(u8::from(v)), true));
    }
    if let Some(rest) = strip_word(t, "NOT") {
        let v = nested(rest, nums, depth + 1)?.0 == 0.0;
        return Ok((f64::from(u8::from(v)), true));
    }
    if let Some((at, op)) = comparison(t) {
        let a = value_krl(&t[..at], nums)?.0;
        let b = value_krl(&t[at + op.len()..], nums)?.0;
        let v = match op {
            "==" => a == b,
            "<>" => a != b,
            "<=" => a <= b,
            ">=" => a >= b,
            "<" => a < b,
            _ => a > b,
        };
        return Ok((f64::from(u8::from(v)), true));
    }
    let logic = |n: &str| match n {
        "true" => Some(Ok((1.0, true))),
        "false" => Some(Ok((0.0, true))),
        _ => nums(n),
    };
    value_krl(t, &logic)
}

/// `text` without parentheses around all of it.
fn outer(text: &str) -> &str {
    let mut t = text.trim();
    for _ in 0..DEPTH {
        if !(t.starts_with('(') && t.ends_with(')') && closes_at_end(t)) {
            break;
        }
        t = t[1..t.len() - 1].trim();
    }
    t
}

/// Whether the `(` opening `text` closes at its last byte.
fn closes_at_end(text: &str) -> bool {
    let mut depth = 0i32;
    for (i, c) in text.char_indices() {
        depth += match c {
            '(' => 1,
            ')' => -1,
            _ => 0,
        };
        if depth == 0 {
            return i == text.len() - 1;
        }
    }
    false
}

/// The parts of `text` between the whole words `word` (any case) outside parentheses.
fn split_word<'a>(text: &'a str, word: &str) -> Vec<&'a str> {
    let upper = text.to_ascii_uppercase();
    let part = |c: u8| c.is_ascii_alphanumeric() || c == b'_' || c == b'$';
    let (b, mut depth, mut from, mut out) = (upper.as_bytes(), 0i32, 0, Vec::new());
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'(' => depth += 1,
            b')' => depth -= 1,
            _ if depth == 0
                && upper[i..].starts_with(word)
                && (i == 0 || !part(b[i - 1]))
                && b.get(i + word.len()).is_none_or(|c| !part(*c)) =>
            {
                out.push(&text[from..i]);
                from = i + word.len();
                i = from;
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    out.push(&text[from..]);
    out
}

/// `text` after its first word when that is `word` (any case).
fn strip_word<'a>(text: &'a str, word: &str) -> Option<&'a str> {
    let head = text.get(..word.len())?;
    let rest = &text[word.len()..];
    (head.eq_ignore_ascii_case(word) && rest.starts_with([' ', '\t', '('])).then_some(rest)
}

/// The first comparison of `text` outside parentheses: its byte and operator.
fn comparison(text: &str) -> Option<(usize, &'static str)> {
    let (b, mut depth) = (text.as_bytes(), 0i32);
    for i in 0..b.len() {
        match b[i] {
            b'(' => depth += 1,
            b')' => depth -= 1,
            _ if depth == 0 => {
                for op in ["==", "<>", "<=", ">=", "<", ">"] {
                    if text[i..].starts_with(op) {
                        return Some((i, op));
                    }
                }
            }
            _ => {}
        }
    }
    None
}
