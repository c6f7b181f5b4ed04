//! Where each language's program ends, so that a file cut off at a line boundary (a copy
//! interrupted, a backup truncated) is refused rather than read as a whole program with its last
//! motions missing: a KRL `.src` that opens with `DEF` ends with `END` (or a function's
//! `ENDFCT`), a RAPID module that opens with `MODULE` with `ENDMODULE`, an LS program that opens
//! with `/PROG` with `/END` (KUKA System Software 8, "DEF ... END"; ABB RAPID overview, "Module
//! declarations"; FANUC R-30iB ASCII program, `/PROG` ... `/END`). A text without the opening
//! word (a fragment) is read as before; INFORM jobs check their own `END` ([`super::inform`]).
//! Also refused here: a text whose lines end with a lone CR, which would read as one line.

use super::Dialect;
use crate::program::at;
use crate::text::lines;
use stiffid_core::Result;

/// The opening and closing words of a program of `dialect` and its comment marker; `None` for
/// a language without such a rule here.
fn words(dialect: Dialect) -> Option<(&'static str, &'static [&'static str], char)> {
    match dialect.controller().key() {
        "krl" => Some(("DEF", &["END", "ENDFCT"], ';')),
        "rapid" => Some(("MODULE", &["ENDMODULE"], '!')),
        "ls" => Some(("/PROG", &["/END"], '!')),
        _ => None,
    }
}

/// Refuses `text` in `dialect` whose lines end with a lone CR, or that opens a program and does
/// not close it (module docs).
///
/// # Errors
/// [`stiffid_core::Error::Program`] naming the last line and the word the program ends with.
pub(crate) fn check(text: &str, dialect: Dialect) -> Result<()> {
    if text.contains('\r') && !text.contains('\n') {
        return Err(at(1, "the lines end with a lone CR (a carriage return without a line feed, as classic Mac OS wrote them), so the file reads as one line: convert its line ends to LF or CR LF".into()));
    }
    let Some((open, close, comment)) = words(dialect) else {
        return Ok(());
    };
    let code = |l: &str| {
        let l = match dialect.controller().key() {
            "ls" => l.trim(),
            _ => l.split(comment).next().unwrap_or("").trim(),
        };
        l.to_string()
    };
    let code_lines = || {
        lines(text)
            .map(|(n, _, l)| (n, code(l)))
            .filter(|(_, l)| !l.is_empty())
    };
    if !code_lines().any(|(_, l)| starts_with_word(&l, open)) {
        return Ok(());
    }
    let last = code_lines().last();
    match last {
        Some((_, l)) if close.iter().any(|c| starts_with_word(&l, c)) => Ok(()),
        Some((n, l)) => Err(at(n, format!(
            "the program ends on '{}' without {}: a {} program that opens with {open} closes with {}, so the file is cut off (its last lines, and the motions in them, missing); give the whole file",
            stiffid_core::common::limits::short(&l),
            close.join(" or "),
            dialect.controller().title(),
            close[0]
        ))),
        None => Ok(()),
    }
}

/// Refuses a KRL program's data list `data` (its `.dat`, named `file` in messages: `the
/// program's .dat`, `my_path.dat`) that does not open with `DEFDAT` (not a data list: the
/// controller refuses it) or does not close with `ENDDAT` (KUKA System Software 8, "Data
/// lists"): cut off, its last declarations missing, and written back so the controller would
/// refuse it. Other languages: nothing.
///
/// # Errors
/// [`stiffid_core::Error::Program`] on line 1, naming the file and its first or last line.
pub(crate) fn check_data(data: &str, file: &str, dialect: Dialect) -> Result<()> {
    if dialect.controller().key() != "krl" {
        return Ok(());
    }
    let code_lines = || {
        (lines(data).map(|(n, _, l)| {
            let l = l.trim_start_matches('\u{feff}');
            (n, l.split(';').next().unwrap_or("").trim())
        }))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('&'))
    };
    let short = stiffid_core::common::limits::short;
    match code_lines().next() {
        Some((_, l)) if starts_with_word(l, "DEFDAT") => {}
        Some((n, l)) => return Err(at(1, format!(
            "{file} opens on its line {n} with '{}', not DEFDAT: a KRL data list opens with DEFDAT NAME and closes with ENDDAT (the controller refuses any other), so this is not the module's data list (another file, or one cut off before its start); give the module's .dat",
            short(l)
        ))),
        None => return Err(at(1, format!(
            "{file} holds no declaration, not even DEFDAT: a KRL data list opens with DEFDAT NAME and closes with ENDDAT; give the module's .dat"
        ))),
    }
    match code_lines().last() {
        Some((n, l)) if !starts_with_word(l, "ENDDAT") => Err(at(1, format!(
            "{file} ends on its line {n}, '{}', without ENDDAT: a KRL data list that opens with DEFDAT closes with ENDDAT, so the file is cut off (its last declarations missing); give the whole .dat",
            short(l)
        ))),
        _ => Ok(()),
    }
}

/// Whether `line` starts with the word `word` (any case), followed by nothing or a character
/// that is not part of a name.
fn starts_with_word(line: &str, word: &str) -> bool {
    let Some(head) = line.get(..word.len()) else {
        return false;
    };
    head.eq_ignore_ascii_case(word)
        && !line[word.len()..]
            .chars()
            .next()
            .is_some_and(|c| c.is_ascii_alphanumeric() || c == '_')
}
