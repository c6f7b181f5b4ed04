//! A declared point visited by motions whose compensations differ, written as several points:
//! the first visit's values stay in the point's declaration; each other value is a new
//! declaration beside it (a copy of the declaration's lines with that value and a name the text
//! does not hold: `XP1_2`, `p10_2`), and the motions that take it name the copy. Every language
//! whose readers say where a point is declared and named ([`super::JointTarget::declared_at`],
//! [`super::JointTarget::named_at`]) is written so; a target without them (a literal, a
//! position of an LS `/POS`) keeps the refusal of two values in one place.

use super::{at, JointProgram};
use std::collections::BTreeMap;
use std::ops::Range;
use stiffid_core::Result;

/// One text to write: its span in the program's text, the target, the text, whether the
/// target's value changed there.
pub(super) type Edit = (Range<usize>, usize, String, bool);

/// A visit's texts in its point's declaration: span and text, in order.
type Texts = Vec<(Range<usize>, String)>;

/// Where a declared point is: its declaration (whole lines, bytes of the text), its name there,
/// and where the motion names it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Point {
    /// The declaration's bytes, from its first line's start to the end of its last line.
    pub declaration: Range<usize>,
    /// The name's bytes in the declaration.
    pub name: Range<usize>,
    /// The name's bytes at the motion, once the motion is read.
    pub reference: Option<Range<usize>>,
}

/// Splits the declared points whose visits take different values (module docs) in `edits`: the
/// later visits' edits in the declaration replaced by a copy of it and the motion's new name.
///
/// # Errors
/// [`stiffid_core::Error::Program`] naming the line of a visit whose point has no name the
/// controller takes beside it (every name up to the language's length taken).
pub(super) fn split(program: &JointProgram, edits: &mut Vec<Edit>) -> Result<()> {
    // Per declaration (its start), the visits in order and each one's texts in it.
    let mut visits: BTreeMap<usize, Vec<(usize, Texts)>> = BTreeMap::new();
    for (i, t) in program.targets.iter().enumerate() {
        let Some(p) = t.point.as_deref().filter(|p| p.reference.is_some()) else {
            continue;
        };
        let inside =
            |r: &Range<usize>| p.declaration.start <= r.start && r.end <= p.declaration.end;
        let mut texts: Texts = (edits.iter())
            .filter(|e| e.1 == i && inside(&e.0))
            .map(|e| (e.0.clone(), e.2.clone()))
            .collect();
        texts.sort_by_key(|(r, _)| r.start);
        visits
            .entry(p.declaration.start)
            .or_default()
            .push((i, texts));
    }
    let mut taken: Vec<String> = Vec::new();
    for list in visits.values() {
        let mut values: Vec<&Texts> = Vec::new();
        for (_, texts) in list {
            if !values.contains(&texts) {
                values.push(texts);
            }
        }
        if values.len() < 2 {
            continue;
        }
        let point = program.targets[list[0].0].point.as_deref().cloned();
        let Some(point) = point else { continue };
        let mut copies = String::new();
        let mut names = vec![String::new()];
        for texts in &values[1..] {
            let name = fresh(program, &point, &taken).ok_or_else(|| at(program.targets[list[0].0].line, format!("the point of line {} is visited with different compensations, and no name beside it is free to declare the second", program.targets[list[0].0].origin)))?;
            copies.push_str(&copy(&program.text, &point, texts, &name));
            taken.push(name.to_ascii_uppercase());
            names.push(name);
        }
        for (i, texts) in list {
            let k = values.iter().position(|v| v == &texts).unwrap_or(0);
            if k == 0 {
                continue;
            }
            edits.retain(|e| !(e.1 == *i && texts.iter().any(|(r, _)| *r == e.0)));
            let reference = program.targets[*i]
                .point
                .as_deref()
                .and_then(|p| p.reference.clone());
            if let Some(r) = reference {
                edits.push((r, *i, names[k].clone(), true));
            }
        }
        let end = point.declaration.end;
        edits.push((end..end, list[0].0, copies, true));
    }
    Ok(())
}

/// The declaration of `point` in `text` with the texts `texts` (absolute spans in it) written
/// and its name `name`.
fn copy(text: &str, point: &Point, texts: &[(Range<usize>, String)], name: &str) -> String {
    let mut all: Vec<(Range<usize>, &str)> =
        texts.iter().map(|(r, t)| (r.clone(), t.as_str())).collect();
    all.push((point.name.clone(), name));
    all.sort_by_key(|(r, _)| r.start);
    let (mut out, mut from) = (String::new(), point.declaration.start);
    for (r, t) in all {
        out.push_str(&text[from..r.start]);
        out.push_str(t);
        from = r.end;
    }
    out.push_str(&text[from..point.declaration.end]);
    match out.ends_with('\n') {
        true => out,
        // The last line of the text: the copy on a line of its own after it.
        false => format!("\n{out}"),
    }
}

/// A name for a copy of `point` the program's text does not hold as a word (any case) and no
/// other copy took (`taken`, upper case): the point's name and `_2`, `_3`.., shortened to the
/// language's longest name; `None` when none is free.
fn fresh(program: &JointProgram, point: &Point, taken: &[String]) -> Option<String> {
    let base = &program.text[point.name.clone()];
    let most = program.dialect.controller().max_name_length();
    (2..10_000).find_map(|k| {
        let suffix = format!("_{k}");
        let keep = most.checked_sub(suffix.len())?.min(base.len());
        let name = format!("{}{suffix}", &base[..keep]);
        let upper = name.to_ascii_uppercase();
        (!taken.contains(&upper) && !holds_word(&program.text, &name)).then_some(name)
    })
}

/// Whether `text` holds `word` (any case) as a whole word (letters, digits, `_` around it).
fn holds_word(text: &str, word: &str) -> bool {
    let (t, w) = (text.to_ascii_lowercase(), word.to_ascii_lowercase());
    let part = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '$';
    t.match_indices(&w).any(|(i, _)| {
        let before = t[..i].chars().next_back().is_none_or(|c| !part(c));
        let after = t[i + w.len()..].chars().next().is_none_or(|c| !part(c));
        before && after
    })
}
