//! A declared point visited by motions whose compensations differ, written as several points:
//! the first visit's values stay in the point's declaration; each other value is a new
//! declaration beside it (a copy of the declaration's lines with that value and a name the text
//! does not hold: `XP1_2`, `p10_2`), and the motions that take it name the copy. Every language
//! whose readers say where a point is declared and named ([`super::JointTarget::declared_at`],
//! [`super::JointTarget::named_at`]) is written so; a target without them (a literal, a
//! position of an LS `/POS`) keeps the refusal of two values in one place. A point of another
//! file copied under another name than the motion gives it (an LS position register `PR[i]`,
//! copied as the program's `P[n]`) is renamed at the motion.

use super::{at, JointProgram};
use std::collections::BTreeMap;
use std::ops::Range;
use stiffid_core::Result;

/// One text to write: its span in the program's text, the target, the text, whether the
/// target's value changed there.
pub(super) type Edit = (Range<usize>, usize, String, bool);

/// A visit's texts in its point's declaration: span and text, in order.
type Texts = Vec<(Range<usize>, String)>;

/// A visit of a point: its target (`None`: a motion left as found) and its texts.
type Visit = (Option<usize>, Texts);

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
    /// For a point declared in another file of the controller (a module of its backup): that
    /// declaration, which the program declares again as its own (`declaration` is then the empty
    /// range where the program's copy goes, `name` the name's bytes in [`Foreign::text`]).
    pub foreign: Option<Box<Foreign>>,
}

/// A point declared in another file, as the program declares its own copy ([`Point::foreign`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Foreign {
    /// The copy's text (whole lines), its values as read.
    pub text: String,
    /// Where [`Foreign::text`]'s first byte was in its file, less what the copy adds before
    /// the values (a target's spans minus it are its spans in the text).
    pub at: usize,
    /// Whether the program computes the point as it runs (KRL's `XP2 = XP1 : {..}`): its copy is
    /// written and named by the motion even where the compensation leaves its values, since the
    /// run computes it from points the compensation may move.
    pub computed: bool,
}

/// Splits the declared points whose visits take different values (module docs) in `edits`: the
/// later visits' edits in the declaration replaced by a copy of it and the motion's new name.
///
/// # Errors
/// [`stiffid_core::Error::Program`] naming the line of a visit whose point has no name the
/// controller takes beside it (every name up to the language's length taken).
pub(super) fn split(program: &JointProgram, edits: &mut Vec<Edit>) -> Result<()> {
    let visits = visits(program, edits);
    let mut taken: Vec<String> = Vec::new();
    for (point, list) in visits.values() {
        let mut values: Vec<&Texts> = Vec::new();
        for (_, texts) in list {
            if !values.contains(&texts) {
                values.push(texts);
            }
        }
        // A point of another file: every value is a copy in the program, the first under the
        // point's own name (the program's declaration hides the other file's).
        let foreign = point.foreign.as_deref();
        let first = usize::from(foreign.is_none());
        let ours = |e: &Edit| list.iter().any(|v| v.0 == Some(e.1));
        // A text the copy already holds at its place changes nothing there.
        let same = |e: &Edit| {
            foreign.is_some_and(|f| {
                let at = e.0.start.checked_sub(f.at).zip(e.0.end.checked_sub(f.at));
                at.and_then(|(a, b)| f.text.get(a..b)) == Some(e.2.as_str())
            })
        };
        let computed = foreign.is_some_and(|f| f.computed);
        if foreign.is_some() && !computed && !edits.iter().any(|e| ours(e) && e.3 && !same(e)) {
            // Unchanged: the other file's declaration holds, nothing to write.
            edits.retain(|e| !ours(e));
            continue;
        }
        if values.len() <= first {
            continue;
        }
        let line = (list.iter().find_map(|v| v.0)).map_or(0, |i| program.targets[i].line);
        let mut copies = String::new();
        let mut names = vec![String::new()];
        for (k, texts) in values.iter().enumerate().skip(first) {
            let name = match (k, foreign) {
                (0, Some(f)) => f.text[point.name.clone()].to_string(),
                _ => fresh(program, point, &taken).ok_or_else(|| at(line, "the point of this motion is visited with different compensations, and no name beside it is free to declare the second".into()))?,
            };
            copies.push_str(&match foreign {
                None => copy(&program.text, point, texts, &name),
                Some(f) => {
                    let rebased: Texts = (texts.iter())
                        .map(|(r, t)| (r.start - f.at..r.end - f.at, t.clone()))
                        .collect();
                    let whole = Point {
                        declaration: 0..f.text.len(),
                        ..point.clone()
                    };
                    copy(&f.text, &whole, &rebased, &name)
                }
            });
            taken.push(name.to_ascii_uppercase());
            names.push(name);
        }
        if foreign.is_some() {
            names.remove(0);
        }
        // One motion statement run for several visits (a procedure read at each of its calls)
        // names one point: visits there that need two are refused.
        let mut named: BTreeMap<usize, (String, u64)> = BTreeMap::new();
        for (i, texts) in list {
            let k = values.iter().position(|v| v == &texts).unwrap_or(0);
            if let Some(i) = *i {
                let t = &program.targets[i];
                let reference = t.point.as_deref().and_then(|p| p.reference.clone());
                if let Some(r) = reference {
                    let name = names.get(k).cloned().unwrap_or_default();
                    match named.get(&r.start) {
                        Some((other, _)) if *other != name => {
                            return Err(at(t.line, two_values(program, i, &r)))
                        }
                        _ => _ = named.insert(r.start, (name, t.line)),
                    }
                }
            }
            let Some(i) = i.filter(|_| k > 0 || foreign.is_some()) else {
                continue;
            };
            edits.retain(|e| !(e.1 == i && texts.iter().any(|(r, _)| *r == e.0)));
            let reference = program.targets[i]
                .point
                .as_deref()
                .and_then(|p| p.reference.clone());
            // The copy of another file's point under another name (an LS position register's
            // copy, `P[n]` for `PR[i]`): the motion names the copy.
            let renamed = |r: &Range<usize>| program.text[r.clone()] != names[k];
            if let Some(r) = reference.filter(|r| k > 0 || (foreign.is_some() && renamed(r))) {
                edits.push((r, i, names[k].clone(), true));
            }
        }
        let end = point.declaration.end;
        let owner = list.iter().find_map(|v| v.0).unwrap_or(0);
        edits.push((end..end, owner, copies, true));
    }
    joined_insertions(edits);
    Ok(())
}

/// The visits of each declared point (by its declaration's start, and its place in another file):
/// the point, and its visits in order, each with its target (`None`: a motion left as found,
/// whose point stays as read) and its texts in the declaration.
fn visits(program: &JointProgram, edits: &[Edit]) -> BTreeMap<(usize, usize), (Point, Vec<Visit>)> {
    let mut visits: BTreeMap<(usize, usize), (Point, Vec<Visit>)> = BTreeMap::new();
    let key = |p: &Point| {
        (
            p.declaration.start,
            p.foreign.as_ref().map_or(usize::MAX, |f| f.at),
        )
    };
    for l in &program.left {
        if let Some(p) = l.point.as_ref().filter(|p| p.reference.is_some()) {
            let entry = visits.entry(key(p));
            entry
                .or_insert_with(|| (p.clone(), Vec::new()))
                .1
                .push((None, Vec::new()));
        }
    }
    for (i, t) in program.targets.iter().enumerate() {
        let Some(p) = t.point.as_deref().filter(|p| p.reference.is_some()) else {
            continue;
        };
        let inside = |r: &Range<usize>| {
            p.foreign.is_some() || (p.declaration.start <= r.start && r.end <= p.declaration.end)
        };
        let mut texts: Texts = (edits.iter())
            .filter(|e| e.1 == i && inside(&e.0))
            .map(|e| (e.0.clone(), e.2.clone()))
            .collect();
        texts.sort_by_key(|(r, _)| r.start);
        let entry = visits.entry(key(p));
        entry
            .or_insert_with(|| (p.clone(), Vec::new()))
            .1
            .push((Some(i), texts));
    }
    visits
}

/// Why the visit `i` of `program`, its point named at `reference` as another visit's is, cannot
/// take a value of its own: a procedure's motion run at two calls, or one name (an assignment's,
/// a loop's) for two values.
fn two_values(program: &JointProgram, i: usize, reference: &Range<usize>) -> String {
    match program.called_in(i) {
        Some(f) => format!("the motion of {f} is run at two calls of its procedure, whose compensations need two different points, and the motion names one: give each call its own procedure or point"),
        None => {
            let line = program.text[..reference.start].matches('\n').count() + 1;
            format!("the point named on line {line} is visited by motions whose compensations need two different points, and that line names one: give each motion its own point")
        }
    }
}

/// The insertions (empty spans) at one byte joined into one, in the order they came.
fn joined_insertions(edits: &mut Vec<Edit>) {
    let mut at: BTreeMap<usize, usize> = BTreeMap::new();
    let mut k = 0;
    while k < edits.len() {
        let e = &edits[k];
        if !e.0.is_empty() {
            k += 1;
            continue;
        }
        match at.get(&e.0.start) {
            Some(&first) => {
                let text = edits.remove(k).2;
                edits[first].2.push_str(&text);
            }
            None => {
                at.insert(e.0.start, k);
                k += 1;
            }
        }
    }
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
    let base = match &point.foreign {
        Some(f) => &f.text[point.name.clone()],
        None => &program.text[point.name.clone()],
    };
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
pub(crate) fn holds_word(text: &str, word: &str) -> bool {
    let (t, w) = (text.to_ascii_lowercase(), word.to_ascii_lowercase());
    let part = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '$';
    t.match_indices(&w).any(|(i, _)| {
        let before = t[..i].chars().next_back().is_none_or(|c| !part(c));
        let after = t[i + w.len()..].chars().next().is_none_or(|c| !part(c));
        before && after
    })
}
