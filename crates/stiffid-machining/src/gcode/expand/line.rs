//! One line of a program read for its control: a LinuxCNC O-word (`O100 sub`, `o<name> call
//! [..]`, `O1 if [..]`), a FANUC/Haas statement (`IF [..] GOTO n`, `WHILE [..] DO m`, `END m`,
//! `GOTO n`, a program number `O1234`), or a block whose parameters and expressions are
//! replaced by their values (assignments `#1 = ..` taken out and applied after the line, as
//! LinuxCNC applies them).

use super::expr::{self, Cursor, Flavour, Param, Values};

/// What a line is.
pub(super) enum Stmt<'a> {
    /// A LinuxCNC O-word: its label (lower case, as written or computed), keyword (lower case)
    /// and the text after the keyword.
    OWord {
        label: String,
        keyword: String,
        rest: &'a str,
    },
    /// A FANUC program number `O1234` (`:1234`) opening a program of the file.
    Header(u32),
    /// `IF [..] GOTO n` or `IF [..] THEN ..`: the text after `IF`.
    If(&'a str),
    /// `WHILE [..] DO m`: the text after `WHILE`.
    While(&'a str),
    /// `DO m` alone.
    Do(&'a str),
    /// `END m`.
    End(&'a str),
    /// `GOTO n`.
    Goto(&'a str),
    /// Anything else: a block.
    Block,
}

/// The line's text without its comments (`( .. )`, `; ..`), for classifying.
pub(super) fn code(line: &str) -> String {
    let mut out = String::new();
    let mut depth = false;
    for c in line.trim_start_matches('\u{feff}').chars() {
        match c {
            '(' if !depth => depth = true,
            ')' if depth => depth = false,
            ';' if !depth => break,
            _ if !depth => out.push(c),
            _ => {}
        }
    }
    out
}

/// The sequence number `N..` opening `code`, and the text after it.
pub(super) fn sequence(code: &str) -> (Option<u32>, &str) {
    let t = code.trim_start();
    let Some(rest) = t.strip_prefix(['N', 'n']) else {
        return (None, t);
    };
    let digits = rest.len() - rest.trim_start_matches(|c: char| c.is_ascii_digit()).len();
    match rest[..digits].parse() {
        Ok(n) => (Some(n), rest[digits..].trim_start()),
        Err(_) => (None, t),
    }
}

const KEYWORDS: [&str; 15] = [
    "sub",
    "endsub",
    "call",
    "return",
    "if",
    "elseif",
    "else",
    "endif",
    "while",
    "endwhile",
    "do",
    "break",
    "continue",
    "repeat",
    "endrepeat",
];

/// What `code` (comments out) is; an O-word's computed label evaluated with `v`.
pub(super) fn classify<'a>(code: &'a str, v: &dyn Values, f: Flavour) -> Result<Stmt<'a>, String> {
    let (_, t) = sequence(code);
    let upper = t.to_ascii_uppercase();
    if let Some(rest) = t.strip_prefix(['O', 'o']) {
        return o_word(rest, v, f);
    }
    if let Some(n) = t.strip_prefix(':').and_then(|r| r.trim().parse().ok()) {
        return Ok(Stmt::Header(n));
    }
    let after = |k: &str| &t[k.len()..];
    for (k, make) in [
        ("IF", Stmt::If as fn(&'a str) -> Stmt<'a>),
        ("WHILE", Stmt::While),
        ("GOTO", Stmt::Goto),
        ("DO", Stmt::Do),
        ("END", Stmt::End),
    ] {
        let next = upper.strip_prefix(k).map(|r| r.chars().next());
        if next.is_some_and(|n| !n.is_some_and(|c| c.is_ascii_alphabetic())) {
            return Ok(make(after(k)));
        }
    }
    Ok(Stmt::Block)
}

/// An O-word's label and keyword (`rest`: after the `O`), or a FANUC program number.
fn o_word<'a>(rest: &'a str, v: &dyn Values, f: Flavour) -> Result<Stmt<'a>, String> {
    let (label, after) = match rest.trim_start().chars().next() {
        Some('<') => {
            let r = rest.trim_start();
            let end = r.find('>').ok_or("O<: the name's closing '>' missing")?;
            let name: String = r[1..end].chars().filter(|c| !c.is_whitespace()).collect();
            (name.to_ascii_lowercase(), &r[end + 1..])
        }
        Some('[') => {
            let mut c = Cursor::new(rest, 0);
            let n = expr::expression(&mut c, v, f)?;
            (label_of(n), &rest[c.at..])
        }
        _ => {
            let r = rest.trim_start();
            let digits = r.len() - r.trim_start_matches(|c: char| c.is_ascii_digit()).len();
            let n: u32 = r[..digits].parse().map_err(|_| {
                format!(
                    "O{}: expected a number, <name> or [expression] after O",
                    short(r)
                )
            })?;
            (n.to_string(), &r[digits..])
        }
    };
    let after = after.trim_start();
    let keyword: String = after
        .chars()
        .take_while(char::is_ascii_alphabetic)
        .collect::<String>()
        .to_ascii_lowercase();
    if KEYWORDS.contains(&keyword.as_str()) {
        return Ok(Stmt::OWord {
            label,
            rest: &after[keyword.len()..],
            keyword,
        });
    }
    match (label.parse::<u32>(), after.trim().is_empty()) {
        (Ok(n), true) => Ok(Stmt::Header(n)),
        _ => Err(format!(
            "O{label} {}: expected a program number alone (O1234) or an O-word's keyword ({})",
            short(after),
            KEYWORDS.join(" ")
        )),
    }
}

/// A computed label as LinuxCNC names it (a whole number).
pub(super) fn label_of(n: f64) -> String {
    if n.fract() == 0.0 && n.abs() < 1e15 {
        format!("{}", n as i64)
    } else {
        format!("{n}")
    }
}

fn short(text: &str) -> String {
    stiffid_core::common::limits::short(text.trim())
}

/// A block with its values: the text with each parameter, expression and function replaced by
/// its number and the assignments taken out, the assignments, and the block's words (letter,
/// value) for the calls it may make.
pub(super) struct Substituted {
    pub(super) text: String,
    pub(super) assignments: Vec<(Param, f64)>,
    pub(super) words: Vec<(char, f64)>,
}

/// `line` (comments kept) with its values (module docs).
pub(super) fn substitute(line: &str, v: &dyn Values, f: Flavour) -> Result<Substituted, String> {
    let mut out = Substituted {
        text: String::with_capacity(line.len()),
        assignments: Vec::new(),
        words: Vec::new(),
    };
    let mut c = Cursor::new(line, 0);
    while let Some(ch) = line[c.at..].chars().next() {
        match ch {
            '(' => {
                let end = line[c.at..].find(')').map_or(line.len(), |e| c.at + e + 1);
                out.text.push_str(&line[c.at..end]);
                c.at = end;
            }
            ';' => {
                out.text.push_str(&line[c.at..]);
                c.at = line.len();
            }
            '#' => {
                let p = expr::param(&mut c, v, f)?;
                if !c.eat('=') {
                    return Err(format!(
                        "{p}: a parameter alone, expected '{p} = value' or a word's value (X{p})"
                    ));
                }
                let mut value_cursor = Cursor::new(line, c.at);
                let value = expr::assigned(&mut value_cursor, v, f)?;
                c.at = value_cursor.at;
                out.assignments.push((p, value));
            }
            l if l.is_ascii_alphabetic() || l == '@' || l == '^' => {
                out.text.push(l);
                c.at += 1;
                let value =
                    word_value(&mut c, &mut out.text, v, f).map_err(|e| format!("{l}: {e}"))?;
                out.words.push((l.to_ascii_uppercase(), value));
            }
            other => {
                out.text.push(other);
                c.at += other.len_utf8();
            }
        }
    }
    Ok(out)
}

/// A word's value after its letter: a number as written (kept byte for byte), else a value
/// computed and written as a number.
fn word_value(
    c: &mut Cursor,
    text: &mut String,
    v: &dyn Values,
    f: Flavour,
) -> Result<f64, String> {
    let start = c.at;
    let literal = match c.peek() {
        Some(ch) if ch.is_ascii_digit() || ch == '.' => true,
        Some('+' | '-') => {
            let mut k = Cursor::new(c.text, c.at + 1);
            k.peek().is_some_and(|n| n.is_ascii_digit() || n == '.')
        }
        _ => false,
    };
    if literal && let Some((value, span)) = crate::text::number_at(c.text, start) {
        let digits = &c.text[span.clone()];
        let end = match digits.find(['e', 'E']) {
            Some(e) => span.start + e,
            None => span.end,
        };
        text.push_str(&c.text[start..end]);
        c.at = end;
        return Ok(c.text[span.start..end].parse().unwrap_or(value));
    }
    let value = expr::real_value(c, v, f)?;
    text.push_str(&format!("{value}"));
    Ok(value)
}
