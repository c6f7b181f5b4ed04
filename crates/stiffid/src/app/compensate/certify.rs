//! Certified programs: every target of a written robot program carries its error bound as a
//! comment naming the value in mm (the CSV carries it as its `bound_mm` column).
//!
//! - KUKA KRL: `; bound 0.0123 mm at 95%` at the end of the motion's line;
//! - ABB RAPID: `! bound 0.0123 mm at 95%` at the end of the line that ends the motion
//!   instruction (its `;`);
//! - Yaskawa INFORM: a comment line `'bound 0.0123 mm at 95%` before the motion's line (INFORM
//!   comments are lines of their own);
//! - FANUC LS: the position's comment in `/POS`, `P[i:"0.0123 mm"]` (a position comment is at
//!   most 16 characters on the pendant; a position that already has one keeps it, and a position
//!   visited twice takes the larger bound).
//!
//! A program compensated again takes the new bounds in the place of the ones an earlier
//! compensation wrote (a bound comment of its form), never beside them.

use std::collections::HashMap;
use stiffid_machining::program::{BoundComment, Dialect};

/// The comment of a bound `bound` (m) at `level`.
fn words(bound: f64, level: f64) -> String {
    match bound.is_finite() {
        true => format!("bound {:.4} mm at {}%", bound * 1e3, level * 100.0),
        false => format!(
            "bound infinite at {}% (needs {} held-out values)",
            level * 100.0,
            stiffid_core::model::prediction::held_out_needed(level)
        ),
    }
}

/// The LS position comment of a bound (m): `0.0123 mm`.
fn ls_words(bound: f64) -> String {
    match bound.is_finite() {
        true => format!("{:.4} mm", bound * 1e3),
        false => "inf mm".into(),
    }
}

/// `text` (a program in `dialect`) with the bound of the target on each of `lines` (1-based:
/// the motion instructions' lines, with their bounds, m) as a comment (module docs).
pub fn at_lines(dialect: Dialect, text: &str, lines: &[(u64, f64)], level: f64) -> String {
    let mut by_line: HashMap<u64, f64> = HashMap::new();
    for &(line, bound) in lines {
        let b = by_line.entry(line).or_insert(bound);
        *b = b.max(bound);
    }
    match dialect.controller().bound_comment() {
        BoundComment::PositionComment => ls(text, &by_line),
        BoundComment::LineBefore { marker } => inform(text, &by_line, level, marker),
        BoundComment::EndOfLine { marker, statement } => {
            let mut out = String::with_capacity(text.len() + 40 * lines.len());
            let mut pending: Option<f64> = None;
            for (i, line) in text.split_inclusive('\n').enumerate() {
                if let Some(b) = by_line.get(&(i as u64 + 1)) {
                    pending = Some(pending.map_or(*b, |p| p.max(*b)));
                }
                let body = line.trim_end_matches(['\n', '\r']);
                let code = body.split(marker).next().unwrap_or("");
                let ends = statement.is_none_or(|end| code.contains(end));
                match pending.filter(|_| ends) {
                    Some(b) => {
                        out.push_str(without_bound(body, marker));
                        out.push_str(&format!(" {marker} {}", words(b, level)));
                        out.push_str(&line[body.len()..]);
                        pending = None;
                    }
                    None => out.push_str(line),
                }
            }
            out
        }
    }
}

/// `lines` (line numbers of the program read, `read`, with their bounds) as the lines of
/// `written` they are: `written` holds `read`'s lines, some edited in place, with whole lines
/// inserted (a point of another file declared anew in the program: an INFORM variable's copy in
/// `//POS`), so a line after an insertion is further down.
pub fn moved(read: &str, written: &str, lines: &[(u64, f64)]) -> Vec<(u64, f64)> {
    let r: Vec<&str> = read.split('\n').collect();
    let w: Vec<&str> = written.split('\n').collect();
    let extra = w.len().saturating_sub(r.len());
    if extra == 0 {
        return lines.to_vec();
    }
    let mut at = Vec::with_capacity(r.len());
    let mut j = 0;
    for (i, line) in r.iter().enumerate() {
        if w.get(j) != Some(line) {
            // Inserted lines end where this line and the next follow each other again.
            let follows =
                |k: &usize| w[*k] == *line && r.get(i + 1).is_none_or(|n| w.get(k + 1) == Some(n));
            if let Some(k) = (j + 1..w.len().min(j + extra + 1)).find(follows) {
                j = k;
            }
        }
        at.push(j as u64 + 1);
        j += 1;
    }
    let place = |l: u64| (l.checked_sub(1)).and_then(|k| at.get(k as usize)).copied();
    lines
        .iter()
        .map(|&(l, b)| (place(l).unwrap_or(l), b))
        .collect()
}

/// `texts` (the files of a generated program, in call order) with the bounds (m) of its targets,
/// in path order, as comments: each motion line, in file order, takes the next bound (`None`: a
/// move of no bound, the home posture's, without a comment).
pub fn generated(
    dialect: Dialect,
    texts: &[String],
    bounds: &[Option<f64>],
    level: f64,
) -> Vec<String> {
    let mut next = bounds.iter().copied();
    texts
        .iter()
        .map(|text| {
            let lines: Vec<(u64, f64)> = (dialect.controller().motion_lines(text).into_iter())
                .filter_map(|line| next.next().flatten().map(|b| (line, b)))
                .collect();
            at_lines(dialect, text, &lines, level)
        })
        .collect()
}

/// Whether `comment` (after its marker and blanks) is a bound [`words`] wrote: a program
/// compensated again takes the new bound in its place.
fn is_bound(comment: &str) -> bool {
    let c = comment.trim();
    c.starts_with("bound ")
        && (c.ends_with('%')
            || c.ends_with(" held-out values)")
            || c.ends_with("(too few held-out values)"))
}

/// `body` (a KRL or RAPID line) without the bound comment an earlier compensation put at its end.
fn without_bound(body: &str, marker: char) -> &str {
    match body.rfind(&format!(" {marker} bound ")) {
        Some(at) if is_bound(&body[at + 3..]) => &body[..at],
        _ => body,
    }
}

/// Whether an LS position comment is a bound [`ls_words`] wrote (`0.0123 mm`, `inf mm`).
fn is_ls_bound(comment: &str) -> bool {
    comment
        .strip_suffix(" mm")
        .is_some_and(|v| v.parse::<f64>().is_ok())
}

/// An INFORM job with a comment line naming the bound before each motion line of `by_line`,
/// indented as the motion.
fn inform(text: &str, by_line: &HashMap<u64, f64>, level: f64, marker: char) -> String {
    let mut out = String::with_capacity(text.len() + 40 * by_line.len());
    for (i, line) in text.split_inclusive('\n').enumerate() {
        let old = line.trim_start().strip_prefix(marker).is_some_and(is_bound);
        if old && by_line.contains_key(&(i as u64 + 2)) {
            continue;
        }
        if let Some(b) = by_line.get(&(i as u64 + 1)) {
            let indent = &line[..line.len() - line.trim_start().len()];
            let end = if line.ends_with("\r\n") { "\r\n" } else { "\n" };
            out.push_str(&format!("{indent}{marker}{}{end}", words(*b, level)));
        }
        out.push_str(line);
    }
    out
}

/// An LS program with the bound of the position of each motion line of `by_line` (and of its
/// continuation lines: a `C` motion's end) as the position's comment in `/POS`.
fn ls(text: &str, by_line: &HashMap<u64, f64>) -> String {
    let mut positions: HashMap<String, f64> = HashMap::new();
    // The bound of the motion on the line, for its continuation lines too (a `C` motion's end).
    let mut motion: Option<f64> = None;
    for (i, line) in text.lines().enumerate() {
        let continued = line.trim_start().starts_with(':');
        motion = by_line
            .get(&(i as u64 + 1))
            .copied()
            .or(motion.filter(|_| continued));
        let Some(b) = motion else {
            continue;
        };
        let Some(index) = line
            .split_once("P[")
            .and_then(|(_, r)| r.split([']', ':']).next())
        else {
            continue;
        };
        let p = positions.entry(index.trim().to_string()).or_insert(b);
        *p = p.max(b);
    }
    let mut out = String::with_capacity(text.len() + 16 * positions.len());
    let mut in_pos = false;
    for line in text.split_inclusive('\n') {
        let t = line.trim_start();
        if t.starts_with('/') {
            in_pos = t.starts_with("/POS");
        }
        let index = (t.strip_prefix("P["))
            .and_then(|r| r.split_once("]{"))
            .map(|(i, _)| i.split_once(':').unwrap_or((i, "")))
            .filter(|(_, c)| {
                c.is_empty()
                    || c.strip_prefix('"')
                        .and_then(|c| c.strip_suffix('"'))
                        .is_some_and(is_ls_bound)
            })
            .map(|(i, _)| i.trim().to_string());
        match (
            in_pos,
            index.and_then(|i| positions.get(&i).map(|b| (i, *b))),
        ) {
            (true, Some((i, b))) => {
                let lead = &line[..line.len() - t.len()];
                let rest = &t[t.find("]{").unwrap_or(0) + 1..];
                out.push_str(&format!("{lead}P[{i}:\"{}\"]{rest}", ls_words(b)));
            }
            _ => out.push_str(line),
        }
    }
    out
}
