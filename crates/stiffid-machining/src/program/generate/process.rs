//! The G-code's process words in a generated program: each written where the G-code has it
//! between the motions ([`place`]), as the setup's `[controller.io]` maps its event
//! ([`stiffid_core::setup::program_io`]) in the language's own form ([`ProcessForm`]), or, not
//! mapped, as a comment naming the words and their line, with one warning naming them all.
//! The G-code's comments on lines of their own (the CAM post's operation and tool comments,
//! [`Comment`]) are written as comments at their place too ([`place_comments`]), each
//! sanitised to what the language's comment takes ([`ProcessForm::comment_text`]).
//!
//! Each language's forms and their sources are in its folder (`process.rs`); every name written
//! is checked against the controller's longest name and reserved words.

use super::{number, Plan};
use crate::gcode::{Comment, ProcessWord};
use stiffid_core::setup::program_io::{Action, Argument, Io, Placeholder, ProcessEvent, Signal};
use stiffid_core::{Error, Result};

/// How a language writes process instructions.
#[derive(Debug, Clone, Copy)]
pub struct ProcessForm {
    /// A comment line: its text between these (KRL `; `, LS `! ` and ` ;`).
    pub comment: (&'static str, &'static str),
    /// The longest comment the pendant keeps, characters of its text; `None`: no limit.
    pub comment_length: Option<usize>,
    /// Characters a comment's text may not hold (besides anything outside printable ASCII),
    /// each written as a blank: LS's `;`, which ends its statement.
    pub comment_forbidden: &'static str,
    /// The indentation of a line of the program's body.
    pub indent: &'static str,
    /// A call of the routine `name` with `arguments` (numbers, as text), or why the language
    /// cannot write it.
    pub call: fn(name: &str, arguments: &[String]) -> std::result::Result<String, String>,
    /// A digital output set on or off, or why the language cannot write it.
    pub output: fn(signal: &Signal, on: bool) -> std::result::Result<String, String>,
    /// A wait of `seconds` (a G-code dwell, `G4`), a whole instruction.
    pub wait: fn(seconds: f64) -> String,
}

/// The process words of a program and where they go.
#[derive(Debug, Clone, Copy, Default)]
pub struct Process<'a> {
    /// The words, in path order.
    pub words: &'a [ProcessWord],
    /// For each word, the index of the target it is written before; the targets' count: after
    /// the last ([`place`]).
    pub before: &'a [usize],
    /// The setup's `[controller.io]`; `None`: no event mapped.
    pub io: Option<&'a Io>,
    /// The G-code's comments on lines of their own, in path order.
    pub comments: &'a [Comment],
    /// For each comment, the index of the target it is written before ([`place_comments`]).
    pub comments_before: &'a [usize],
}

impl ProcessForm {
    /// `text` as this language's comment takes it: every character outside printable ASCII
    /// (the controllers' files are ASCII or their code pages; a line break would end the
    /// comment) written as `?`, a forbidden one ([`ProcessForm::comment_forbidden`]) as a
    /// blank, at most [`ProcessForm::comment_length`] characters.
    pub(crate) fn comment_text(&self, text: &str) -> String {
        let mut out: String = (text.chars())
            .map(|c| match c {
                c if self.comment_forbidden.contains(c) => ' ',
                ' '..='~' => c,
                _ => '?',
            })
            .collect();
        if let Some(most) = self.comment_length {
            out.truncate(most);
        }
        out.trim_end().to_string()
    }

    /// A whole comment line of `text` ([`ProcessForm::comment_text`]).
    pub(crate) fn comment_line(&self, text: &str) -> String {
        let (open, close) = self.comment;
        format!("{}{open}{}{close}\n", self.indent, self.comment_text(text))
    }
}

/// Where each of `comments` goes among targets whose G-code lines are `lines` (as [`place`]
/// places a word of its line: before the first target of its line or a later one, else after
/// the path).
pub fn place_comments(comments: &[Comment], lines: &[Option<u64>]) -> Vec<usize> {
    let n = lines.len();
    let after_path = lines.iter().rposition(Option::is_some).map_or(n, |i| i + 1);
    (comments.iter())
        .map(|c| {
            (lines.iter())
                .position(|l| l.is_some_and(|l| l >= c.line))
                .unwrap_or(after_path)
        })
        .collect()
}

/// Where each of `words` goes among targets whose G-code lines are `lines` (`None`: a target of
/// no G-code line, the home posture): before the first target of its line or a later one (a
/// block's process words run before its motion), the program's end (`M2`, `M30`) after every
/// target, a word after the last motion before a home posture that follows it.
pub fn place(words: &[ProcessWord], lines: &[Option<u64>]) -> Vec<usize> {
    let n = lines.len();
    let after_path = lines.iter().rposition(Option::is_some).map_or(n, |i| i + 1);
    (words.iter())
        .map(|w| match w.event {
            Some(ProcessEvent::ProgramEnd) => n,
            _ => (lines.iter())
                .position(|l| l.is_some_and(|l| l >= w.line))
                .unwrap_or(after_path),
        })
        .collect()
}

/// Moves the place (`before`, [`place`]) of each of `words` that follows a path point (a
/// `G82`'s dwell at the hole's bottom, [`ProcessWord::point`]) to just after that point's
/// target: before the first target of a later point (`points`: each target's path point,
/// `None` for one of no G-code point, the home posture), else after the path's last target.
pub fn after_points(words: &[ProcessWord], points: &[Option<usize>], before: &mut [usize]) {
    let after_path = points
        .iter()
        .rposition(Option::is_some)
        .map_or(points.len(), |i| i + 1);
    for (w, at) in words.iter().zip(before.iter_mut()) {
        if let Some(i) = w.point {
            *at = (points.iter())
                .position(|p| p.is_some_and(|p| p > i))
                .unwrap_or(after_path);
        }
    }
}

/// The lines written before each target of `plan` (and, at the targets' count, after the last),
/// and the warning naming the words no event of `io` maps.
///
/// # Errors
/// [`Error::InvalidField`] (`controller.io.KEY`) for an action the language cannot write or a
/// name the controller does not take; [`Error::Program`] naming the G-code line of a word whose
/// action needs a value (`{rpm}`, `{tool}`) the program has not given.
pub(crate) fn inserted(
    plan: &Plan,
    form: &ProcessForm,
    process: &Process,
) -> Result<(Vec<String>, Option<String>)> {
    let n = plan.targets.len();
    // Each written line with its place (the target it goes before) and its G-code line.
    let mut placed: Vec<(usize, u64, String)> = Vec::new();
    let mut unmapped: Vec<(&str, &ProcessWord)> = Vec::new();
    for (w, &at) in process.words.iter().zip(process.before) {
        if let Some(dwell) = &w.dwell {
            let seconds = dwell.clone().map_err(|why| Error::Program {
                line: w.line,
                message: format!("{why}: a robot program written from it waits as long"),
            })?;
            placed.push((
                at.min(n),
                w.line,
                format!("{}{}\n", form.indent, (form.wait)(seconds)),
            ));
            continue;
        }
        let actions = w.event.and_then(|e| process.io.and_then(|io| io.get(e)));
        let Some(actions) = actions else {
            let key = w
                .event
                .map_or("other M words (no event)", ProcessEvent::key);
            unmapped.push((key, w));
            let text = format!("{} (line {})", w.words, w.line);
            placed.push((at.min(n), w.line, form.comment_line(&text)));
            continue;
        };
        for action in actions {
            let line = written(plan, form, w, action)?;
            placed.push((at.min(n), w.line, format!("{}{line}\n", form.indent)));
        }
    }
    for (c, &at) in process.comments.iter().zip(process.comments_before) {
        placed.push((at.min(n), c.line, form.comment_line(&c.text)));
    }
    // In the G-code's order at each place (a block's words in their order of execution).
    placed.sort_by_key(|(at, line, _)| (*at, *line));
    let mut lines = vec![String::new(); n + 1];
    for (at, _, text) in placed {
        lines[at] += &text;
    }
    Ok((lines, warning(&unmapped)))
}

/// One warning naming every word not mapped, grouped by event key.
fn warning(unmapped: &[(&str, &ProcessWord)]) -> Option<String> {
    if unmapped.is_empty() {
        return None;
    }
    let mut keys: Vec<&str> = unmapped.iter().map(|(k, _)| *k).collect();
    keys.dedup();
    let mut seen = Vec::new();
    let groups: Vec<String> = (keys.into_iter())
        .filter(|k| {
            let new = !seen.contains(k);
            seen.push(*k);
            new
        })
        .map(|key| {
            let words: Vec<String> = (unmapped.iter())
                .filter(|(k, _)| *k == key)
                .map(|(_, w)| format!("{} (line {})", w.words, w.line))
                .collect();
            format!("{key}: {}", words.join(", "))
        })
        .collect();
    Some(format!(
        "{} process word(s) of the G-code not mapped in the setup's [controller.io], written as comments where the G-code has them (map an event to a call or an output to run it): {}",
        unmapped.len(),
        groups.join("; ")
    ))
}

/// One action of a word in the language, names checked.
fn written(plan: &Plan, form: &ProcessForm, w: &ProcessWord, action: &Action) -> Result<String> {
    let key = w.event.map_or("", ProcessEvent::key);
    let refused = |message: String| Error::InvalidField {
        field: format!("controller.io.{key}"),
        message,
    };
    let line = match action {
        Action::Call { name, arguments } => {
            let values = (arguments.iter())
                .map(|a| value(w, a))
                .collect::<Result<Vec<String>>>()?;
            check_name(plan, name).and_then(|()| (form.call)(name, &values))
        }
        Action::Output { signal, on } => match signal {
            Signal::Name(name) => check_name(plan, name),
            Signal::Number(_) => Ok(()),
        }
        .and_then(|()| (form.output)(signal, *on)),
    };
    line.map_err(|why| refused(format!("{} (at {} on line {})", why, w.words, w.line)))
}

/// A name within the controller's longest and not one of its reserved words.
fn check_name(plan: &Plan, name: &str) -> std::result::Result<(), String> {
    let controller = plan.dialect.controller();
    let most = controller.max_name_length();
    if name.len() > most {
        return Err(format!(
            "{name}: {} takes names of at most {most} characters",
            controller.title()
        ));
    }
    if (controller.reserved_words().iter()).any(|r| r.eq_ignore_ascii_case(name)) {
        return Err(format!(
            "{name}: a reserved word of {} (or a name the program declares)",
            controller.title()
        ));
    }
    Ok(())
}

/// An argument's text: a number as the setup gives it, a placeholder the word's value.
fn value(w: &ProcessWord, a: &Argument) -> Result<String> {
    let missing = |what: &str| Error::Program {
        line: w.line,
        message: format!(
            "{}: the setup's [controller.io] passes {what}, and no such word is in force here",
            w.words
        ),
    };
    match a {
        Argument::Number(n) => Ok(n.clone()),
        Argument::Value(Placeholder::Rpm) => {
            (w.rpm.map(number)).ok_or_else(|| missing("{rpm}, the spindle speed S"))
        }
        Argument::Value(Placeholder::Tool) => {
            (w.tool.map(|t| t.to_string())).ok_or_else(|| missing("{tool}, the tool number T"))
        }
    }
}
