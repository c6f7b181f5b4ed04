//! The fast path of the measurement reader: a piece of text whose lines are plain (no quote, no
//! carriage return but before a line feed, no byte-order mark) and valid is split at its commas
//! and line feeds directly, without the `csv` crate; anything else (a quote anywhere, a row in
//! error, text that is not UTF-8) sends the whole piece to the `csv` path, which gives the same
//! rows for plain text (tests) and is the one source of errors.

use super::{Layout, Parsed};

/// Puts the rows of `text` (whose first line is line `first` of the file) into `parsed` (cleared
/// first), as the `csv` path would; `false` (and `parsed` unusable) unless every line is plain and
/// every row valid.
pub fn parse(layout: &Layout, text: &[u8], first: u64, parsed: &mut Parsed) -> bool {
    parse_plain(layout, text, first, parsed).is_some()
}

fn parse_plain(layout: &Layout, text: &[u8], first: u64, parsed: &mut Parsed) -> Option<()> {
    let text = std::str::from_utf8(text).ok()?;
    if text.contains('"') {
        return None;
    }
    let carriage_returns = text.contains('\r');
    let expected = layout.fields();
    parsed.rows.clear();
    parsed.labels.clear();
    parsed.error = None;
    let mut fields: Vec<&str> = Vec::with_capacity(expected);
    for (i, line) in text.split('\n').enumerate() {
        let line = line.strip_suffix('\r').unwrap_or(line);
        if (carriage_returns && line.contains('\r')) || line.starts_with('\u{feff}') {
            return None;
        }
        split(line, &mut fields);
        if line.trim_ascii_start().starts_with('#') {
            // A comment, unless it holds a row (`commented_row`) or is not at the line's start.
            if fields.len() == expected || !line.starts_with('#') {
                return None;
            }
            continue;
        }
        if line.is_empty() {
            continue;
        }
        if fields.len() != expected {
            return None;
        }
        let label = fields[layout.columns.posture].trim();
        if label.is_empty() {
            return None;
        }
        let at = |c, p| layout.at(0, c, p);
        let measurement = layout.measurement(|f| fields[f], 0, at).ok()?;
        parsed.labels.push_str(label);
        let end = parsed.labels.len();
        parsed.rows.push((measurement, first + i as u64, end));
    }
    Some(())
}

/// The comma-separated fields of `line`, into `fields` (cleared first).
fn split<'a>(line: &'a str, fields: &mut Vec<&'a str>) {
    fields.clear();
    let mut start = 0;
    for (i, b) in line.bytes().enumerate() {
        if b == b',' {
            fields.push(&line[start..i]);
            start = i + 1;
        }
    }
    fields.push(&line[start..]);
}
