//! Arithmetic a program states (`+`, `-`, `*`, `/`, parentheses) of numbers and data whose
//! values the caller knows: RAPID's `num` data (`rapid::num`), KRL's members of points
//! (`krl::assign`). Anything else (a function, `DIV`, `MOD`) is the run's.

/// The value of the expression `text` with the data `nums` (module docs), or why it has none.
pub(crate) fn value(
    text: &str,
    nums: &dyn Fn(&str) -> Option<std::result::Result<f64, String>>,
) -> std::result::Result<f64, String> {
    let tokens = tokens(text)?;
    let mut at = 0;
    let v = sum(&tokens, &mut at, nums, 0)?;
    match at == tokens.len() && v.is_finite() {
        true => Ok(v),
        false => Err(format!(
            "'{}' is not arithmetic of numbers and data stiffid reads",
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
