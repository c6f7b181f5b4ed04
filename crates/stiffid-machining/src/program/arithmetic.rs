//! Arithmetic a program states (`+`, `-`, `*`, `/`, parentheses) of numbers and data whose
//! values the caller knows: RAPID's `num` data (`rapid::num`), KRL's members of points
//! (`krl::assign`) and numeric data (`krl::numbers`). Anything else (a function, `DIV`, `MOD`)
//! is the run's. KRL types its numbers: a literal without a decimal point or exponent and `INT`
//! data are `INT`, and `INT / INT` divides as integers, truncating (KSS 8.x SI manual,
//! "Arithmetic operators": `3/2` is 1); [`value_krl`] follows that.

/// The value of the expression `text` with the data `nums` (module docs), or why it has none.
pub(crate) fn value(
    text: &str,
    nums: &dyn Fn(&str) -> Option<std::result::Result<f64, String>>,
) -> std::result::Result<f64, String> {
    let typed = |n: &str| nums(n).map(|r| r.map(|v| (v, false)));
    evaluate(text, &typed, false).map(|(v, _)| v)
}

/// The value of the KRL expression `text` and whether it is an `INT` (module docs), with the
/// data `nums` (each value and whether it is an `INT`), or why it has none.
pub(crate) fn value_krl(text: &str, nums: Lookup) -> std::result::Result<(f64, bool), String> {
    evaluate(text, nums, true)
}

/// [`value`] or [`value_krl`] (`krl`: integer literals are `INT`).
fn evaluate(text: &str, nums: Lookup, krl: bool) -> std::result::Result<(f64, bool), String> {
    let tokens = tokens(text, krl)?;
    let mut at = 0;
    let v = sum(&tokens, &mut at, nums, 0)?;
    match at == tokens.len() && v.0.is_finite() {
        true => Ok(v),
        false => Err(format!(
            "'{}' is not arithmetic of numbers and data stiffid reads",
            text.trim()
        )),
    }
}

/// A token: a number (and whether an `INT`), a name (lower case) or an operator.
#[derive(Debug, Clone, PartialEq)]
enum Token {
    Number(f64, bool),
    Name(String),
    Op(char),
}

/// The tokens of `text` (`krl`: a literal without `.` or exponent is an `INT`).
fn tokens(text: &str, krl: bool) -> std::result::Result<Vec<Token>, String> {
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
            let int = krl && !text[span.clone()].contains(['.', 'e', 'E']);
            out.push(Token::Number(v, int));
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

/// A value and whether it is an `INT`.
type Typed = (f64, bool);

/// The data an expression reads: by lower-case name, its value and whether it is an `INT`.
pub(crate) type Lookup<'a> = &'a dyn Fn(&str) -> Option<std::result::Result<Typed, String>>;

fn sum(
    t: &[Token],
    at: &mut usize,
    nums: Lookup,
    depth: usize,
) -> std::result::Result<Typed, String> {
    let mut v = product(t, at, nums, depth)?;
    while let Some(Token::Op(op @ ('+' | '-'))) = t.get(*at) {
        *at += 1;
        let w = product(t, at, nums, depth)?;
        v = (if *op == '+' { v.0 + w.0 } else { v.0 - w.0 }, v.1 && w.1);
    }
    Ok(v)
}

fn product(
    t: &[Token],
    at: &mut usize,
    nums: Lookup,
    depth: usize,
) -> std::result::Result<Typed, String> {
    let mut v = factor(t, at, nums, depth)?;
    while let Some(Token::Op(op @ ('*' | '/'))) = t.get(*at) {
        *at += 1;
        let w = factor(t, at, nums, depth)?;
        v = match (*op, v.1 && w.1) {
            ('*', int) => (v.0 * w.0, int),
            (_, true) if w.0 == 0.0 => return Err("a division of INTs by 0".into()),
            (_, true) => ((v.0 / w.0).trunc(), true),
            (_, false) => (v.0 / w.0, false),
        };
    }
    Ok(v)
}

fn factor(
    t: &[Token],
    at: &mut usize,
    nums: Lookup,
    depth: usize,
) -> std::result::Result<Typed, String> {
    if depth > DEPTH {
        return Err("an expression nested too deep".into());
    }
    let token = t.get(*at).cloned();
    *at += 1;
    match token {
        Some(Token::Number(v, int)) => Ok((v, int)),
        Some(Token::Op('-')) => factor(t, at, nums, depth + 1).map(|(v, int)| (-v, int)),
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
