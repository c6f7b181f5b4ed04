//! A `FOR` loop whose body reads its variable (`FOR I = 1 TO 5 STEP 2` .. `XP1.Z = XP0.Z - I*2`
//! .. `LIN XP1`, or `LIN XP[I]`), with bounds and step the files state (numbers, or numbers known
//! where the loop is: [`super::numbers`]), read as the controller runs it: its body once per
//! value of the variable, in order (KSS 8.x SI manual, "FOR": the variable takes the start value,
//! then each step, while it has not passed the end value). The limits are every language's
//! ([`MOST`] motions over every loop of the module, [`MOST_STEPS`] statements); `STEP 0` or a loop over
//! them is refused naming the `FOR` line; bounds the run gives leave the loop read once, its
//! variable the run's.

use crate::program::at;
use crate::program::paths::{MOST, MOST_STEPS};
use crate::program::points::holds_word;
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// A loop to unroll: its variable (upper case), its values, the index of its `ENDFOR` among
/// the lines, and how many motions and statements its body holds.
pub(super) struct Unrolled {
    pub var: String,
    pub values: Vec<f64>,
    pub end: usize,
    pub motions: usize,
    pub steps: usize,
}

/// The module's lines: number, first byte, text.
pub(super) type Lines<'a> = [(u64, usize, &'a str)];

/// The code of a line (without its comment).
fn code<'a>(lines: &Lines<'a>, k: usize) -> &'a str {
    lines[k].2.split(';').next().unwrap_or("")
}

/// The first word of line `k`, upper case.
fn first(lines: &Lines, k: usize) -> String {
    super::declare::words(code(lines, k))
        .into_iter()
        .next()
        .unwrap_or_default()
}

/// The loop that line `k` (before `to`) opens, to unroll (module docs); `None` for any other
/// line, or a loop read once (no motion reads its variable, bounds the run gives).
///
/// # Errors
/// Naming the `FOR` line: `STEP 0`, more values than [`MOST`], `done` (motions and statements
/// unrolled so far) past the limits.
pub(super) fn at_line(
    lines: &Lines,
    (k, to): (usize, usize),
    eval: super::branches::Eval,
    done: (usize, usize),
) -> Result<Option<Unrolled>> {
    if first(lines, k) != "FOR" {
        return Ok(None);
    }
    let (line, text) = (lines[k].0, code(lines, k).trim());
    let words = super::declare::words(text);
    let Some(var) = words.get(1).cloned() else {
        return Ok(None);
    };
    let mut depth = 0;
    let Some(end) = (k..to).find(|&j| {
        match first(lines, j).as_str() {
            "FOR" => depth += 1,
            "ENDFOR" => depth -= 1,
            _ => {}
        }
        depth == 0
    }) else {
        return Ok(None);
    };
    let motion = |j: &usize| {
        matches!(
            first(lines, *j).as_str(),
            "PTP" | "LIN" | "CIRC" | "SPTP" | "SLIN" | "SCIRC"
        )
    };
    let reads = (k + 1..end).any(|j| holds_word(code(lines, j), &var));
    let motions = (k + 1..end).filter(motion).count();
    if !reads || motions == 0 {
        return Ok(None);
    }
    let Some((a, b, step)) = bounds(text, eval) else {
        return Ok(None);
    };
    if step == 0.0 {
        return Err(at(
            line,
            format!("{}: STEP 0, a loop that never ends", short(text)),
        ));
    }
    let count = ((b - a) / step).floor() + 1.0;
    let steps = (end - k - 1) * count.max(0.0) as usize;
    if !count.is_finite()
        || count > MOST as f64
        || done.0 + motions * count.max(0.0) as usize > MOST
    {
        return Err(at(line, format!("{}: unrolled, the loops give more than {MOST} motions; stiffid reads a loop's motions once per value of its variable up to that: split the path", short(text))));
    }
    if done.1 + steps > MOST_STEPS {
        return Err(at(line, format!("{}: unrolled, the loops give more than {MOST_STEPS} statements to read; split the path", short(text))));
    }
    let values = (0..count.max(0.0) as usize)
        .map(|n| a + step * n as f64)
        .collect();
    Ok(Some(Unrolled {
        var,
        values,
        end,
        motions,
        steps,
    }))
}

/// The start, end and step of the `FOR` line `text` (`FOR I = a TO b STEP s`), where each is an
/// integer known here.
fn bounds(text: &str, eval: super::branches::Eval) -> Option<(f64, f64, f64)> {
    let upper = text.to_ascii_uppercase();
    let eq = upper.find('=')?;
    let to = word_at(&upper, "TO")?;
    let step = word_at(&upper, "STEP");
    let int = |t: &str| eval(t).ok().map(|v| v.0).filter(|v| v.fract() == 0.0);
    let a = int(&text[eq + 1..to])?;
    let b = int(&text[to + 2..step.unwrap_or(text.len())])?;
    let s = match step {
        Some(s) => int(&text[s + 4..])?,
        None => 1.0,
    };
    Some((a, b, s))
}

/// The byte of the whole word `word` in `upper`.
fn word_at(upper: &str, word: &str) -> Option<usize> {
    let part = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '$';
    upper
        .match_indices(word)
        .map(|(i, _)| i)
        .find(|&i| !upper[..i].ends_with(part) && !upper[i + word.len()..].starts_with(part))
}
