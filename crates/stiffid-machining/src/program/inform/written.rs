//! A job written back with positions the job did not hold (the copies of position variables,
//! [`super::variables`]): the new positions numbered on from the job's own without a gap (a
//! motion whose copy is not written keeps its variable, so its number is free), the motions
//! that name them renamed with them, and the first count of `///NPOS` (the robot's positions)
//! the positions `//POS` now holds, as the controller counts them when it loads the job.

use crate::program::lines;
use std::collections::BTreeSet;

/// `written`, the job `read` written back, with its new robot positions numbered without a gap
/// and `///NPOS` counting them (module docs); as it is when it holds no new position.
pub(super) fn finish(read: &str, written: String) -> String {
    let before = robot_positions(read);
    let after = robot_positions(&written);
    let new: Vec<u64> = after.difference(&before).copied().collect();
    if new.is_empty() {
        return written;
    }
    let first = before.iter().next_back().map_or(0, |l| l + 1);
    let mut out = written;
    for (next, old) in (first..).zip(new) {
        if old != next {
            out = renamed(&out, old, next);
        }
    }
    let count = robot_positions(&out).len();
    npos(&out, count)
}

/// The numbers of the robot positions (`C00012=..`) of `//POS` in `text`.
fn robot_positions(text: &str) -> BTreeSet<u64> {
    let mut in_pos = false;
    let mut out = BTreeSet::new();
    for (_, _, l) in lines(text) {
        let t = l.trim();
        if let Some(section) = t.strip_prefix("//").filter(|s| !s.starts_with('/')) {
            in_pos = section.starts_with("POS");
            continue;
        }
        let name = t.split_once('=').map_or("", |(n, _)| n.trim());
        let number = name.strip_prefix('C').and_then(|d| d.parse::<u64>().ok());
        if let (true, Some(n)) = (in_pos, number) {
            out.insert(n);
        }
    }
    out
}

/// `text` with the robot position `C{old:05}` named `C{new:05}` wherever it is a whole word.
fn renamed(text: &str, old: u64, new: u64) -> String {
    let (from, to) = (format!("C{old:05}"), format!("C{new:05}"));
    let part = |c: Option<char>| c.is_some_and(|c| c.is_ascii_alphanumeric() || c == '_');
    let mut out = String::with_capacity(text.len());
    let mut at = 0;
    for (i, _) in text.match_indices(&from) {
        let before = text[..i].chars().next_back();
        let after = text[i + from.len()..].chars().next();
        if part(before) || part(after) {
            continue;
        }
        out.push_str(&text[at..i]);
        out.push_str(&to);
        at = i + from.len();
    }
    out.push_str(&text[at..]);
    out
}

/// `text` with the first count of its `///NPOS` line `count`.
fn npos(text: &str, count: usize) -> String {
    let Some((_, start, l)) = lines(text).find(|(_, _, l)| l.trim_start().starts_with("///NPOS"))
    else {
        return text.to_string();
    };
    let Some(open) = l.find("NPOS").map(|i| i + 4) else {
        return text.to_string();
    };
    let rest = &l[open..];
    let skip = rest.len() - rest.trim_start().len();
    let first = rest.trim_start();
    let end = first.find(',').unwrap_or(first.len());
    let span = start + open + skip..start + open + skip + end;
    format!("{}{count}{}", &text[..span.start], &text[span.end..])
}
