//! Scanning the text of a program (G-code or a controller's): its numbered lines and the numbers
//! in them.

use std::ops::Range;

/// The number at the start of `text[from..]` after blanks (line ends included): its value and
/// byte span.
pub(crate) fn number_at(text: &str, from: usize) -> Option<(f64, Range<usize>)> {
    let bytes = text.as_bytes();
    let mut start = from;
    while start < bytes.len() && matches!(bytes[start], b' ' | b'\t' | b'\n' | b'\r') {
        start += 1;
    }
    let mut end = start;
    if end < bytes.len() && matches!(bytes[end], b'+' | b'-') {
        end += 1;
    }
    let digits = |end: &mut usize| {
        let s = *end;
        while *end < bytes.len() && bytes[*end].is_ascii_digit() {
            *end += 1;
        }
        *end > s
    };
    let mut any = digits(&mut end);
    if end < bytes.len() && bytes[end] == b'.' {
        end += 1;
        any |= digits(&mut end);
    }
    if !any {
        return None;
    }
    if end < bytes.len() && matches!(bytes[end], b'e' | b'E') {
        let mut e = end + 1;
        if e < bytes.len() && matches!(bytes[e], b'+' | b'-') {
            e += 1;
        }
        if digits(&mut e) {
            end = e;
        }
    }
    let value: f64 = text[start..end].parse().ok()?;
    value.is_finite().then_some((value, start..end))
}

/// The 1-based line of each line start: `(line, start byte, the line without its end)`.
pub(crate) fn lines(text: &str) -> impl Iterator<Item = (u64, usize, &str)> {
    let mut start = 0;
    text.split_inclusive('\n').enumerate().map(move |(i, l)| {
        let s = start;
        start += l.len();
        (i as u64 + 1, s, l.trim_end_matches(['\n', '\r']))
    })
}

/// `items` in words: `a`, `a or b`, `a, b or c`.
pub(crate) fn or_list(items: &[String]) -> String {
    match items.split_last() {
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
        None => String::new(),
    }
}
