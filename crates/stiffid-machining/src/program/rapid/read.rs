//! A RAPID module read statement by statement (module docs of [`super`]): every motion of every
//! routine, each where it is (inside `IF`, `WHILE`, `FOR`, `TEST`, an error handler, any `PROC`),
//! in the order of the text. A motion names its own tool, work object and speed, so what it
//! moves with is the same on every path; what a statement sets for the motions after it,
//! `ConfJ`/`ConfL \Off` (configuration monitoring), is followed through the branches and loops
//! ([`crate::program::paths`]) and is the caller's at a routine's start.

use super::{declarations, first_word, flow, is_header, motion, no_motion, statements};
use super::{well_formed, without_comments, Statement};
use crate::program::controller::Read;
use crate::program::paths::{Join, Kind, Paths};
use crate::program::{at, Context, JointTarget};
use stiffid_core::Result;

/// Configuration monitoring in force for joint (0) and linear (1) motions: off (`\Off`), on, or
/// why the file does not say.
#[derive(Debug, Clone, PartialEq)]
struct Conf([std::result::Result<bool, String>; 2]);

impl Join for Conf {
    fn join(&mut self, other: &Self, (word, line): (&str, u64)) {
        for k in 0..2 {
            if self.0[k] != other.0[k] && self.0[k].is_ok() {
                let name = ["ConfJ", "ConfL"][k];
                self.0[k] = match &other.0[k] {
                    Err(why) => Err(why.clone()),
                    Ok(_) => Err(format!("{name} \\Off is in force on one path through {word} (line {line}) only: the controller holds this motion to its confdata on one path and not on the other; set {name} alike on every path, or before {word}")),
                };
            }
        }
    }
    fn agrees(&self, other: &Self) -> bool {
        self == other
    }
}

/// Every target of `text`, in the order of its motions (module docs), the program's external
/// axes (`eax_a` to the last one any target gives a value, not `9E9`) and the motions left as
/// found ([`Context::leave_refused`]).
///
/// # Errors
/// [`stiffid_core::Error::Program`] naming the line of a motion outside the subset, of a motion
/// whose configuration monitoring depends on the path (unless left as found), of a jump in a
/// module that switches configuration monitoring, or of a module without motions.
pub(crate) fn targets(text: &str, context: &Context) -> Result<Read> {
    let code = without_comments(text);
    let statements = statements(&code);
    let data = super::backup::merge(declarations(&code, &statements)?, (text, &code), context)?;
    let switches_conf = statements.iter().find(|s| {
        matches!(
            first_word(&code[s.span.clone()]).as_str(),
            "confj" | "confl"
        )
    });
    // The words that start a statement: a routine called by the module is among them.
    let called: std::collections::HashSet<String> = (statements.iter())
        .map(|s| first_word(&code[s.span.clone()]))
        .collect();
    let mut out = Vec::new();
    let mut left = Vec::new();
    let mut routines: Vec<(String, u64)> = Vec::new();
    let mut flow = flow::Flow::default();
    let mut paths: Paths<Conf> = Paths::default();
    let mut conf = Conf([Ok(false), Ok(false)]);
    // The first motion of the routine being read.
    let mut first_motion: Option<u64> = None;
    for s in &statements {
        let body = &code[s.span.clone()];
        let first = first_word(body);
        well_formed(s.line, &body.trim_start()[..first.len()])?;
        if let Some(name) = routine(body) {
            check_jumps(&flow, &routines, first_motion.take(), switches_conf)?;
            routines.push((name, s.line));
            flow.routine();
            paths.clear();
            conf = entry(
                switches_conf.filter(|_| called.contains(&name_of(&routines))),
                s.line,
            );
            continue;
        }
        flow.statement(&first, is_header(body), s.line);
        if is_header(body) {
            branches(&first, s.line, &mut paths, &mut conf);
        }
        if first == "if" && !is_header(body) {
            if let Some((name, line, _)) = flow::in_compact_if(body, s.line, flow::is_jump) {
                let jump = format!("IF (line {}) {}", s.line, name.to_uppercase());
                flow.jump(&jump, line);
            }
            // A compact IF's motion: read where it is, a branch of one statement.
            if let Some((name, line, at)) = flow::in_compact_if(body, s.line, flow::is_motion) {
                let inner = Statement {
                    line,
                    span: s.span.start + at..s.span.end,
                };
                let name = name.to_ascii_lowercase();
                match moves(&inner, &code, &name, &data, &conf) {
                    Ok(found) => {
                        first_motion.get_or_insert(line);
                        out.extend(found);
                    }
                    Err(e) => context.leave(&mut left, e)?,
                }
            }
            continue;
        }
        let rest = body.trim_start()[first.len()..].trim_start();
        if rest.starts_with([':', '.', '{']) {
            // An assignment (`name := ..`, `name.x := ..`, `name{i} := ..`): no motion.
            continue;
        }
        if let Some(k) = ["confj", "confl"].iter().position(|c| *c == first) {
            conf.0[k] = Ok(rest.to_ascii_lowercase().starts_with("\\off"));
        }
        let found = match moves(s, &code, &first, &data, &conf) {
            Ok(found) => found,
            Err(e) => {
                context.leave(&mut left, e)?;
                continue;
            }
        };
        if !found.is_empty() {
            first_motion.get_or_insert(s.line);
        }
        out.extend(found);
    }
    check_jumps(&flow, &routines, first_motion, switches_conf)?;
    if out.is_empty() && left.is_empty() {
        return Err(at(1, no_motion(&routines)));
    }
    let n = out
        .iter()
        .filter_map(|t| t.external.iter().rposition(Option::is_some))
        .max()
        .map_or(0, |k| k + 1);
    let axes = (0..n).map(|k| format!("eax_{}", (b'a' + k as u8) as char));
    Ok(Read {
        targets: out,
        axes: axes.collect(),
        left,
        ..Read::default()
    })
}

/// The name of the routine a statement opens (`PROC name()`, `FUNC type name()`, `TRAP name`).
fn routine(body: &str) -> Option<String> {
    let words: Vec<String> = body
        .split_whitespace()
        .take(3)
        .map(str::to_ascii_lowercase)
        .collect();
    let w: Vec<&str> = words
        .iter()
        .map(String::as_str)
        .skip_while(|w| matches!(*w, "local" | "task"))
        .collect();
    match w.as_slice() {
        ["proc" | "trap", name, ..] | ["func", _, name, ..] => {
            Some(name.split('(').next().unwrap_or(name).to_string())
        }
        _ => None,
    }
}

/// The name (lower case) of the last routine of `routines`.
fn name_of(routines: &[(String, u64)]) -> String {
    routines
        .last()
        .map_or(String::new(), |(n, _)| n.to_ascii_lowercase())
}

/// Configuration monitoring at the start of the routine on `line`: on (the controller's
/// default, as at the program's start) in a routine the module does not call or a module that
/// never switches it (`switches` `None`); else the caller's, which the module does not say.
fn entry(switches: Option<&Statement>, line: u64) -> Conf {
    match switches {
        None => Conf([Ok(false), Ok(false)]),
        Some(s) => {
            let why = format!("the module switches configuration monitoring (line {}), and at the start of the routine on line {line} it is in the state its caller leaves, which the module does not say; set ConfJ and ConfL at the routine's start", s.line);
            Conf([Err(why.clone()), Err(why)])
        }
    }
}

/// Follows a header statement `first` (lower case) on `line` that opens, divides or closes a
/// branch or loop.
fn branches(first: &str, line: u64, paths: &mut Paths<Conf>, conf: &mut Conf) {
    let kind = match first {
        "if" => Some(Kind::Branches),
        "test" => Some(Kind::Cases),
        "while" | "for" => Some(Kind::Loop),
        _ => None,
    };
    match (kind, first) {
        (Some(kind), _) => paths.open((&first.to_ascii_uppercase(), line), conf, kind, 0),
        (None, "elseif" | "case") => paths.branch(conf, false),
        (None, "else" | "default") => paths.branch(conf, true),
        (None, "endif" | "endtest" | "endwhile" | "endfor") => _ = paths.close(conf),
        _ => {}
    }
}

/// The targets of the statement `s` (`first` its instruction), with configuration monitoring
/// `conf` in force: a `MoveL`, `MoveC` or `MoveJ` with it off follows the arm's configuration.
///
/// # Errors
/// Those of [`motion`]; a Cartesian motion where the file does not say whether monitoring is on.
fn moves(
    s: &Statement,
    code: &str,
    first: &str,
    data: &super::Data,
    conf: &Conf,
) -> Result<Vec<JointTarget>> {
    let mut found = motion(s, code, first, data)?;
    let first = super::as_move(first);
    let linear = matches!(first, "movel" | "movec");
    if found.is_empty() || !(linear || first == "movej") {
        return Ok(found);
    }
    match &conf.0[usize::from(linear)] {
        Err(why) => Err(at(s.line, why.clone())),
        Ok(false) => Ok(found),
        Ok(true) => {
            // Configuration monitoring off: the motion keeps the arm's configuration from the
            // posture before it, whatever its confdata says.
            for c in found.iter_mut().filter_map(|t| t.cartesian.as_deref_mut()) {
                c.follows = true;
            }
            Ok(found)
        }
    }
}

/// Refuses a jump of the routine just read (its motions from `first`) in a module that switches
/// configuration monitoring: after a jump the state in force is not the file's.
fn check_jumps(
    flow: &flow::Flow,
    routines: &[(String, u64)],
    first: Option<u64>,
    switches: Option<&Statement>,
) -> Result<()> {
    match (first, switches, routines.last()) {
        (Some(line), Some(_), Some((name, _))) => flow.check_jumps(&format!("PROC {name}"), line),
        _ => Ok(()),
    }
}
