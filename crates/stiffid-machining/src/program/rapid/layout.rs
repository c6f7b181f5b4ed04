//! A RAPID module's routines as the reader takes them (module `read`): which statements it reads
//! (every routine's, or a called procedure's and those of the module's routines it calls), the
//! routines the module calls, and where each statement sits among the motions (module `place`).

use super::calls::{self, routine};
use super::place::{places, Place, Seen};
use super::{first_word, flow, Statement};
use crate::program::rapid::called::Task;
use std::collections::{HashMap, HashSet};

/// A module's routines and statements, as read (module docs).
pub(super) struct Layout {
    /// Per statement, whether it is read.
    pub read: Vec<bool>,
    /// Per statement, where it sits among the motions.
    pub places: Vec<Place>,
    /// The module's routines (lower case).
    pub routines: HashSet<String>,
    /// The routines the module calls (lower case).
    pub called: HashSet<String>,
    /// The routines with parameters that the module calls (lower case): each read at each of
    /// its calls, with the call's arguments, not where it is.
    pub per_call: HashSet<String>,
}

impl Layout {
    /// The layout of the module `code` (its `statements`), the task's procedures in `task`;
    /// `entry` the procedure a call reads, its call's place, and whether it is read alone (a
    /// routine with parameters of a module read whole) or with the routines it calls (a
    /// procedure of another module); a routine with parameters it calls is read at that call.
    pub(super) fn of(
        code: &str,
        statements: &[Statement],
        task: &Task,
        entry: Option<(&str, Place, bool)>,
    ) -> Layout {
        let mut names: Vec<String> = Vec::new();
        let mut with_parameters: HashSet<usize> = HashSet::new();
        let mut seen = vec![Seen::default(); statements.len()];
        let mut open = false;
        for (k, s) in statements.iter().enumerate() {
            let body = &code[s.span.clone()];
            let first = first_word(body);
            if let Some(name) = routine(body) {
                if has_parameters(body) && calls::procedure(body).is_some() {
                    with_parameters.insert(names.len());
                }
                names.push(name.to_ascii_lowercase());
                open = true;
                continue;
            }
            if matches!(first.as_str(), "endproc" | "endfunc" | "endtrap") {
                open = false;
                continue;
            }
            seen[k].routine = open.then(|| names.len() - 1);
            seen[k].loop_step = match first.as_str() {
                "while" | "for" => 1,
                "endwhile" | "endfor" => -1,
                _ => 0,
            };
            seen[k].moving = flow::is_motion(&first)
                || (first == "if" && flow::in_compact_if(body, s.line, flow::is_motion).is_some());
        }
        let index: HashMap<&str, usize> = (names.iter().enumerate())
            .map(|(k, n)| (n.as_str(), k))
            .collect();
        for (k, s) in statements.iter().enumerate() {
            let body = &code[s.span.clone()];
            let first = first_word(body);
            let name = calls::called(body, &first).map(str::to_ascii_lowercase);
            let name = name.or_else(|| {
                (first == "if")
                    .then(|| calls::in_compact_if(body))
                    .flatten()
                    .map(|(w, _)| w.to_ascii_lowercase())
            });
            match name.as_deref() {
                Some(n) if index.contains_key(n) => seen[k].calls = Some(index[n]),
                Some(n) if n == "%" || task.procs.contains_key(n) => seen[k].moving = true,
                _ => {}
            }
        }
        moving_calls(&mut seen, names.len());
        let per_call: HashSet<usize> = (seen.iter().filter_map(|s| s.calls))
            .filter(|r| with_parameters.contains(r))
            .collect();
        let chosen = entry.map(|(name, _, alone)| {
            let mut set = match alone {
                true => index.get(name).copied().into_iter().collect(),
                false => reached(name, &index, &seen),
            };
            set.retain(|r| !per_call.contains(r) || Some(r) == index.get(name));
            set
        });
        let read = (seen.iter().enumerate())
            .map(|(k, s)| {
                let header = routine(&code[statements[k].span.clone()]);
                let r = header.map_or(s.routine, |h| {
                    index.get(h.to_ascii_lowercase().as_str()).copied()
                });
                match &chosen {
                    None => r.is_none_or(|r| !per_call.contains(&r)),
                    Some(set) => r.is_some_and(|r| set.contains(&r)),
                }
            })
            .collect();
        let at_entry: HashMap<usize, Place> = entry
            .and_then(|(name, place, _)| index.get(name).map(|&r| (r, place)))
            .into_iter()
            .collect();
        let called = (seen.iter().filter_map(|s| s.calls))
            .map(|r| names[r].clone())
            .collect();
        Layout {
            read,
            places: places(&seen, &at_entry),
            per_call: per_call.iter().map(|&r| names[r].clone()).collect(),
            routines: names.into_iter().collect(),
            called,
        }
    }
}

/// Whether the routine header `body` declares parameters (`PROC pick(robtarget p)`).
fn has_parameters(body: &str) -> bool {
    match (body.find('('), body.rfind(')')) {
        (Some(open), Some(close)) if open < close => !body[open + 1..close].trim().is_empty(),
        _ => false,
    }
}

/// Marks the calls of the module's routines that move (hold a motion, or call a procedure of the
/// task or a routine that moves) as moving.
fn moving_calls(seen: &mut [Seen], routines: usize) {
    let mut moves = vec![false; routines];
    loop {
        let mut changed = false;
        for s in seen.iter_mut() {
            if s.calls.is_some_and(|c| moves[c]) {
                s.moving = true;
            }
            if let Some(r) = s.routine.filter(|r| s.moving && !moves[*r]) {
                moves[r] = true;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
}

/// The routines (indices) `name` reaches: itself and those it calls, in turn.
fn reached(name: &str, index: &HashMap<&str, usize>, seen: &[Seen]) -> HashSet<usize> {
    let mut out = HashSet::new();
    let mut todo: Vec<usize> = index.get(name).copied().into_iter().collect();
    while let Some(r) = todo.pop() {
        if out.insert(r) {
            let calls = seen.iter().filter(|s| s.routine == Some(r));
            todo.extend(calls.filter_map(|s| s.calls));
        }
    }
    out
}

/// Refuses a routine of the module `code` (its `statements`) that another routine's header or
/// the module's end follows before its `ENDPROC` (`ENDFUNC`, `ENDTRAP`): the controller does not
/// load the module (*RAPID kernel*: routine declarations), and read on, the next routine's
/// motions would be read as this one's.
pub(super) fn routines_closed(code: &str, statements: &[Statement]) -> stiffid_core::Result<()> {
    let mut open: Option<(String, u64, &str)> = None;
    for s in statements {
        let body = &code[s.span.clone()];
        let first = first_word(body);
        let header = routine(body);
        let ends = first == "endmodule" || header.is_some();
        if let (Some((name, line, word)), true) = (&open, ends) {
            return Err(crate::program::at(*line, format!("the routine {name} has no {word} before line {}: the controller does not load the module; close it", s.line)));
        }
        match (header, first.as_str()) {
            (Some(name), _) => open = Some((name, s.line, closing(body))),
            (None, "endproc" | "endfunc" | "endtrap") => open = None,
            _ => {}
        }
    }
    match open {
        Some((name, line, word)) => Err(crate::program::at(line, format!("the routine {name} has no {word} before the file's end: the controller does not load the module; close it"))),
        None => Ok(()),
    }
}

/// The word that closes the routine whose header is `header` (`ENDPROC`, `ENDFUNC`, `ENDTRAP`).
fn closing(header: &str) -> &'static str {
    let words: Vec<String> = (header.split_whitespace().take(3))
        .map(str::to_ascii_lowercase)
        .collect();
    match words
        .iter()
        .find(|w| !matches!(w.as_str(), "local" | "task"))
        .map(String::as_str)
    {
        Some("func") => "ENDFUNC",
        Some("trap") => "ENDTRAP",
        _ => "ENDPROC",
    }
}
