//! The order an LS program's `/MN` instructions run in (FANUC R-30iA/R-30iB HandlingTool
//! operator's manual, "Branching instructions", "FOR/ENDFOR", "IF/SELECT"): each instruction's
//! successors, so that what is in force at a motion (the frame numbers, the motion before it)
//! is found along every path that reaches it, as the controller may run them.
//!
//! - `LBL[i]` marks a place; `JMP LBL[i]` goes there; `IF .. ,JMP LBL[i]`, a `SELECT`'s cases
//!   (`SELECT R[1]=1,JMP LBL[1]`, `=2,JMP LBL[2]`), `WAIT .. TIMEOUT,LBL[i]` and any other
//!   instruction naming a label may go there or on; a `SELECT`'s `ELSE,JMP LBL[i]` goes there.
//! - `IF (..) THEN` runs on, or goes past its `ELSE` (or to its `ENDIF`); `ELSE` ends the first
//!   branch, going to its `ENDIF`.
//! - `FOR R[i]=a TO b` (or `DOWNTO b`; each bound a whole number, `R[j]` or `AR[j]`) runs its
//!   body or goes past its `ENDFOR`: its body at least once where both bounds are numbers that
//!   count through it, never where they count past it, either where a bound is a register's;
//!   `ENDFOR` goes back to the body's start or on. Any other form (`FOR R[1]=1 TO abc`) is refused
//!   naming the line: the controller does not load it.
//! - `END` and `ABORT` end the program: nothing follows.
//!
//! A label's number taken from a register (`JMP LBL[R[1]]`), a jump to a label the program does
//! not hold, a label held twice, and an `IF .. THEN`, `ELSE`, `ENDIF`, `FOR` or `ENDFOR` without
//! its other part are refused naming the line: the order the controller runs is not the file's to
//! say then. A German program's keywords are read as their English twins
//! ([`super::statements::english`]).

use super::statements::english;
use crate::program::at;
use std::collections::HashMap;
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// What an instruction does to the order of the run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    /// Runs on.
    On,
    /// `LBL[n]`.
    Label(u32),
    /// A jump to a label, which may also run on (`conditional`).
    Jump { label: u32, conditional: bool },
    /// `END`, `ABORT`.
    End,
    /// `IF (..) THEN`.
    Then,
    /// A structured `ELSE`.
    Else,
    /// `ENDIF`.
    EndIf,
    /// `FOR`, with whether its body runs.
    For(Runs),
    /// `ENDFOR`.
    EndFor,
}

/// The program's order of run: each instruction's successors (an index of the instructions, or
/// their count: the program's end).
#[derive(Debug, Clone)]
pub(super) struct Graph {
    /// Per instruction, the ones that may run after it.
    pub next: Vec<Vec<usize>>,
    /// Per instruction, whether it ends the run (`END`, `ABORT`) or only jumps (`JMP`): no
    /// instruction after it in the file runs after it.
    pub stops: Vec<bool>,
}

/// The order of run of `instructions` (line and text, the `/MN` of [`super::instructions`]);
/// `motion` says which are motions (their options' labels are read with the motion).
///
/// # Errors
/// Naming the line (module docs).
pub(super) fn graph(instructions: &[(u64, String)], motion: &[bool]) -> Result<Graph> {
    let mut kinds = Vec::with_capacity(instructions.len());
    let mut labels: HashMap<u32, usize> = HashMap::new();
    for (k, (line, t)) in instructions.iter().enumerate() {
        let kind = match motion[k] {
            true => Kind::On,
            false => kind(*line, t)?,
        };
        if let Kind::Label(n) = kind
            && let Some(first) = labels.insert(n, k)
        {
            return Err(at(*line, format!("LBL[{n}]: the label is also on line {}; the controller jumps to one of them, which is not the file's to say: give each label one place", instructions[first].0)));
        }
        kinds.push(kind);
    }
    let n = instructions.len();
    let pairs = pairs(instructions, &kinds)?;
    let mut next = Vec::with_capacity(n);
    for (k, kind) in kinds.iter().enumerate() {
        let label = |l: u32| {
            labels.get(&l).copied().ok_or_else(|| {
                let (line, t) = &instructions[k];
                at(
                    *line,
                    format!("{}: no LBL[{l}] in the program to jump to", short(t.trim())),
                )
            })
        };
        next.push(match *kind {
            Kind::On | Kind::Label(_) | Kind::EndIf => vec![k + 1],
            Kind::Jump {
                label: l,
                conditional,
            } => match conditional {
                true => vec![k + 1, label(l)?],
                false => vec![label(l)?],
            },
            Kind::End => Vec::new(),
            Kind::Then => vec![k + 1, pairs[&k] + 1],
            Kind::Else => vec![pairs[&k]],
            Kind::For(Runs::Maybe) => vec![k + 1, pairs[&k] + 1],
            Kind::For(Runs::Always) => vec![k + 1],
            Kind::For(Runs::Never) => vec![pairs[&k] + 1],
            Kind::EndFor => vec![pairs[&k] + 1, k + 1],
        });
    }
    let stops = kinds
        .iter()
        .map(|k| {
            matches!(
                k,
                Kind::End
                    | Kind::Jump {
                        conditional: false,
                        ..
                    }
            )
        })
        .collect();
    Ok(Graph { next, stops })
}

/// Where each structured part goes: `IF .. THEN` to its `ELSE` (else its `ENDIF`), `ELSE` to
/// its `ENDIF`, `FOR` to its `ENDFOR` and `ENDFOR` to its `FOR`, by index.
fn pairs(instructions: &[(u64, String)], kinds: &[Kind]) -> Result<HashMap<usize, usize>> {
    let mut out = HashMap::new();
    // The open `IF .. THEN`s (index, its `ELSE` once read) and `FOR`s, innermost last.
    let mut open: Vec<(Kind, usize, Option<usize>)> = Vec::new();
    let unmatched = |k: usize, what: &str| {
        let (line, t) = &instructions[k];
        at(
            *line,
            format!(
                "{}: {what}; the order the controller runs would not be the file's to say",
                short(t.trim())
            ),
        )
    };
    for (k, kind) in kinds.iter().enumerate() {
        match kind {
            Kind::Then | Kind::For(_) => open.push((*kind, k, None)),
            Kind::Else => match open.last_mut() {
                Some((Kind::Then, _, e @ None)) => *e = Some(k),
                _ => return Err(unmatched(k, "an ELSE without its IF .. THEN")),
            },
            Kind::EndIf => match open.pop() {
                Some((Kind::Then, then, e)) => {
                    out.insert(then, e.unwrap_or(k));
                    if let Some(e) = e {
                        out.insert(e, k);
                    }
                }
                _ => return Err(unmatched(k, "an ENDIF without its IF .. THEN")),
            },
            Kind::EndFor => match open.pop() {
                Some((Kind::For(_), f, _)) => {
                    out.insert(f, k);
                    out.insert(k, f);
                }
                _ => return Err(unmatched(k, "an ENDFOR without its FOR")),
            },
            _ => {}
        }
    }
    match open.pop() {
        Some((Kind::For(_), k, _)) => Err(unmatched(k, "a FOR without its ENDFOR")),
        Some((_, k, _)) => Err(unmatched(k, "an IF .. THEN without its ENDIF")),
        None => Ok(out),
    }
}

/// What instruction `t` on `line` (not a motion) does to the order of the run (module docs).
fn kind(line: u64, t: &str) -> Result<Kind> {
    let upper = english(&t.trim().to_ascii_uppercase());
    let first = upper
        .split(|c: char| c.is_whitespace() || matches!(c, '[' | '(' | '=' | ','))
        .next()
        .unwrap_or("");
    let label = || label_number(line, t, &upper);
    Ok(match first {
        "LBL" => Kind::Label(label()?.unwrap_or(0)),
        "END" | "ABORT" => Kind::End,
        "IF" if upper.ends_with("THEN") => Kind::Then,
        "ELSE" if upper == "ELSE" => Kind::Else,
        "ENDIF" => Kind::EndIf,
        "FOR" => Kind::For(for_loop(line, t, &upper)?),
        "ENDFOR" => Kind::EndFor,
        _ => match label()? {
            None => Kind::On,
            Some(l) => Kind::Jump {
                label: l,
                conditional: !(first == "JMP" || first == "ELSE"),
            },
        },
    })
}

/// Whether a `FOR` loop's body runs: at least once, never (both bounds numbers), or as the
/// registers it counts with hold at run time.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Runs {
    Always,
    Never,
    Maybe,
}

/// The `FOR` instruction `t` (`upper`: upper case, English) on `line`, `FOR R[i]=a TO b` or
/// `FOR R[i]=a DOWNTO b`, each bound a whole number, `R[j]` or `AR[j]` (the forms the controller
/// loads): whether its body runs.
///
/// # Errors
/// Naming the line, any other form (`FOR R[1]=1 TO abc`).
fn for_loop(line: u64, t: &str, upper: &str) -> Result<Runs> {
    let refuse = || {
        at(line, format!("{}: expected FOR R[i]=a TO b (or DOWNTO b), each bound a whole number, R[j] or AR[j], as the controller loads it", short(t.trim())))
    };
    let rest = upper
        .trim()
        .strip_prefix("FOR")
        .ok_or_else(refuse)?
        .trim_start();
    let (counter, rest) = rest.split_once('=').ok_or_else(refuse)?;
    if !register(counter.trim(), false) {
        return Err(refuse());
    }
    let words: Vec<&str> = rest.split_whitespace().collect();
    let at_word = words.iter().position(|w| *w == "TO" || *w == "DOWNTO");
    let Some(k) = at_word else {
        return Err(refuse());
    };
    let (from, to) = (words[..k].concat(), words[k + 1..].concat());
    if !(bound(&from) && bound(&to)) {
        return Err(refuse());
    }
    Ok(match (from.parse::<i64>(), to.parse::<i64>()) {
        (Ok(a), Ok(b)) if (words[k] == "TO") == (a <= b) || a == b => Runs::Always,
        (Ok(_), Ok(_)) => Runs::Never,
        _ => Runs::Maybe,
    })
}

/// Whether `w` is a `FOR` loop's bound: a whole number, `R[j]` or `AR[j]`.
fn bound(w: &str) -> bool {
    w.parse::<i64>().is_ok() || register(w, true)
}

/// Whether `w` is a register `R[j]` (`R[j:comment]`), or with `argument` an argument `AR[j]`.
fn register(w: &str, argument: bool) -> bool {
    let inner = match (w.strip_prefix("R["), w.strip_prefix("AR[")) {
        (Some(i), _) => i,
        (None, Some(i)) if argument => i,
        _ => return false,
    };
    let Some(inner) = inner.strip_suffix(']') else {
        return false;
    };
    let number = inner.split(':').next().unwrap_or("").trim();
    !number.is_empty() && number.chars().all(|c| c.is_ascii_digit())
}

/// The label instruction `t` (`upper`: in upper case, English) names, `LBL[n]` or
/// `LBL[n:comment]`; `None` when it names none.
///
/// # Errors
/// Naming the line, a label whose number is held in a register (`LBL[R[1]]`).
fn label_number(line: u64, t: &str, upper: &str) -> Result<Option<u32>> {
    let Some(at_label) = upper.find("LBL[") else {
        return Ok(None);
    };
    let inner = &upper[at_label + 4..];
    let number = inner.split([']', ':']).next().unwrap_or("").trim();
    match number.parse::<u32>() {
        Ok(n) => Ok(Some(n)),
        Err(_) => Err(at(line, format!("{}: the label is taken from a register at run time; the order the controller runs would not be the file's to say: jump to a label by its number", short(t.trim())))),
    }
}

impl Graph {
    /// Per instruction, whether some path from the program's start reaches it.
    pub(super) fn reached(&self) -> Vec<bool> {
        let n = self.next.len();
        let mut seen = vec![false; n + 1];
        let mut stack = vec![0];
        while let Some(k) = stack.pop() {
            if k > n || std::mem::replace(&mut seen[k], true) {
                continue;
            }
            if k < n {
                stack.extend(self.next[k].iter().copied());
            }
        }
        seen.truncate(n);
        seen
    }

    /// Per instruction, whether some path from it (after it) reaches an instruction `wanted`
    /// takes (a motion).
    pub(super) fn leads_to(&self, wanted: &[bool]) -> Vec<bool> {
        let n = self.next.len();
        let mut out = vec![false; n];
        loop {
            let mut changed = false;
            for k in (0..n).rev() {
                let v = (self.next[k].iter()).any(|&j| j < n && (wanted[j] || out[j]));
                if v && !out[k] {
                    out[k] = true;
                    changed = true;
                }
            }
            if !changed {
                return out;
            }
        }
    }

    /// Per instruction, whether some path from the start reaches it after an instruction
    /// `wanted` takes (a motion).
    pub(super) fn after(&self, wanted: &[bool]) -> Vec<bool> {
        let n = self.next.len();
        let mut out = vec![false; n];
        let mut stack: Vec<usize> = (0..n).filter(|&k| wanted[k]).collect();
        while let Some(k) = stack.pop() {
            for &j in &self.next[k] {
                if j < n && !std::mem::replace(&mut out[j], true) {
                    stack.push(j);
                }
            }
        }
        out
    }

    /// The state in force before each instruction: `start` at the first, and at every other
    /// the states the instructions before it on every path leave (`step`: the state after
    /// instruction `k` given the one before), joined where paths meet (`join`: the first
    /// joined with the second at instruction `k`; whether it changed). `None` where no path
    /// reaches the instruction.
    pub(super) fn states<S: Clone>(
        &self,
        start: S,
        step: impl Fn(usize, &S) -> S,
        join: impl Fn(&mut S, &S, usize) -> bool,
    ) -> Vec<Option<S>> {
        let n = self.next.len();
        let mut before: Vec<Option<S>> = vec![None; n];
        if n == 0 {
            return before;
        }
        before[0] = Some(start);
        let mut work = vec![0];
        while let Some(k) = work.pop() {
            let Some(s) = before[k].as_ref() else {
                continue;
            };
            let after = step(k, s);
            for &j in &self.next[k] {
                if j >= n {
                    continue;
                }
                let changed = match before[j].as_mut() {
                    Some(b) => join(b, &after, j),
                    None => {
                        before[j] = Some(after.clone());
                        true
                    }
                };
                if changed {
                    work.push(j);
                }
            }
        }
        before
    }
}

#[cfg(test)]
#[path = "flow_tests.rs"]
mod tests;
