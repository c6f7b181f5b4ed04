//! A `FOR` loop whose motions read its variable (`FOR i FROM 1 TO 3 DO MoveL pts{i}, ..;
//! ENDFOR`), with bounds and step the module states (numbers, or arithmetic of `num` data it
//! never sets, module `num`), read as the controller runs it: its statements once per value of
//! the variable, in order (*RAPID overview*: `FOR`; the variable takes `FROM`, then each step,
//! while it has not passed `TO`). At most [`MOST`] motions are read so; a `STEP 0`, a longer
//! loop, or bounds the run gives leave the variable the run's (bounds) or are refused naming the
//! `FOR` line.

use super::num::{value, Nums};
use super::{first_word, flow, Statement};
use crate::program::at;
use stiffid_core::Result;

pub(super) use crate::program::paths::{MOST, MOST_STEPS};

/// A statement to read: its index, and the loop variables' values in force (name lower case).
pub(super) type Step = (usize, Vec<(String, f64)>);

/// The statements of `code` in the order the reader takes them: each once, but the bodies of the
/// loops unrolled (module docs), with their variables' values; `nums` the module's `num` data.
///
/// # Errors
/// Naming a `FOR` line: `STEP 0`, or more than [`MOST`] motions unrolled.
pub(super) fn order(code: &str, statements: &[Statement], nums: &Nums) -> Result<Vec<Step>> {
    let mut out = Vec::with_capacity(statements.len());
    let mut motions = 0;
    steps(
        code,
        statements,
        (0, statements.len()),
        (nums, &[]),
        (&mut out, &mut motions),
    )?;
    Ok(out)
}

/// The steps of statements `from..to` with the loop values `outer`, into `out`.
fn steps(
    code: &str,
    statements: &[Statement],
    (from, to): (usize, usize),
    (nums, outer): (&Nums, &[(String, f64)]),
    (out, motions): (&mut Vec<Step>, &mut usize),
) -> Result<()> {
    let mut k = from;
    while k < to {
        let body = &code[statements[k].span.clone()];
        let Some((var, values, end)) = loop_of(code, statements, k, to, (nums, outer))? else {
            out.push((k, outer.to_vec()));
            k += 1;
            continue;
        };
        let inside = (k + 1..end)
            .filter(|&j| flow::is_motion(&first_word(&code[statements[j].span.clone()])))
            .count();
        *motions += inside * values.len();
        if *motions > MOST {
            let line = statements[k].line;
            return Err(at(line, format!("{}: unrolled, the loops give more than {MOST} motions; stiffid reads a loop's motions once per value of its variable up to that: split the path", body.trim())));
        }
        for v in values {
            if out.len() > MOST_STEPS {
                let line = statements[k].line;
                return Err(at(line, format!("{}: unrolled, the loops give more than {MOST_STEPS} statements to read; split the path", body.trim())));
            }
            let mut inner = outer.to_vec();
            inner.retain(|(n, _)| *n != var);
            inner.push((var.clone(), v));
            steps(
                code,
                statements,
                (k + 1, end),
                (nums, &inner),
                (out, motions),
            )?;
        }
        k = end + 1;
    }
    Ok(())
}

/// The loop opened by statement `k` (before `to`) that is unrolled: its variable (lower case),
/// its values and its `ENDFOR`; `None` for any other statement or a loop left as it is (no motion
/// reads its variable, or its bounds are the run's).
#[allow(clippy::type_complexity)]
fn loop_of(
    code: &str,
    statements: &[Statement],
    k: usize,
    to: usize,
    (nums, outer): (&Nums, &[(String, f64)]),
) -> Result<Option<(String, Vec<f64>, usize)>> {
    let s = &statements[k];
    let body = code[s.span.clone()].trim();
    let lower = body.to_ascii_lowercase();
    if first_word(&lower) != "for" {
        return Ok(None);
    }
    let words: Vec<&str> = lower.split_whitespace().collect();
    let Some(var) = words.get(1).map(|v| v.to_string()) else {
        return Ok(None);
    };
    let Some(end) = closing(code, statements, k, to) else {
        return Ok(None);
    };
    // Its motions read the variable, or an assignment does (`p := Offs(p0, 0, 0, i * 10);`,
    // module `assign`) in a loop that moves.
    let text = |j: usize| code[statements[j].span.clone()].to_ascii_lowercase();
    let moving = |j: &usize| flow::is_motion(&first_word(&text(*j)));
    let reads =
        (k + 1..end).any(|j| (moving(&j) || text(j).contains(":=")) && holds_word(&text(j), &var));
    if !reads || !(k + 1..end).any(|j| moving(&j)) {
        return Ok(None);
    }
    let part = |from: &str, until: &[&str]| -> Option<String> {
        let i = lower.find(from)? + from.len();
        let j = (until.iter()).filter_map(|u| lower[i..].find(u)).min()?;
        Some(lower[i..i + j].to_string())
    };
    let lookup = |n: &str| {
        (outer.iter().rev())
            .find(|(o, _)| o == n)
            .map(|(_, v)| Ok(*v))
            .or_else(|| nums.get(n).cloned())
    };
    let eval = |t: Option<String>| t.and_then(|t| value(&t, &lookup).ok());
    let from = eval(part(" from ", &[" to "]));
    let until = eval(part(" to ", &[" step ", " do"]));
    let step = match lower.contains(" step ") {
        true => eval(part(" step ", &[" do"])),
        false => Some(1.0),
    };
    let (Some(a), Some(b), Some(step)) = (from, until, step) else {
        return Ok(None);
    };
    if step == 0.0 {
        return Err(at(
            s.line,
            format!("{body}: STEP 0, a loop that never ends"),
        ));
    }
    let count = ((b - a) / step).floor() + 1.0;
    if !count.is_finite() || count > MOST as f64 {
        return Err(at(s.line, format!("{body}: more than {MOST} values of {var}; stiffid reads a loop's motions once per value up to that: split the path")));
    }
    let values = (0..count.max(0.0) as usize)
        .map(|n| a + step * n as f64)
        .collect();
    Ok(Some((var, values, end)))
}

/// The `ENDFOR` that closes the `FOR` of statement `k`, before `to`.
fn closing(code: &str, statements: &[Statement], k: usize, to: usize) -> Option<usize> {
    let mut depth = 0;
    for (j, s) in statements.iter().enumerate().take(to).skip(k) {
        match first_word(&code[s.span.clone()]).as_str() {
            "for" => depth += 1,
            "endfor" => {
                depth -= 1;
                if depth == 0 {
                    return Some(j);
                }
            }
            _ => {}
        }
    }
    None
}

/// Whether `text` (lower case) holds `word` as a whole word.
fn holds_word(text: &str, word: &str) -> bool {
    let part = |c: char| c.is_ascii_alphanumeric() || c == '_';
    text.match_indices(word).any(|(i, _)| {
        let before = text[..i].chars().next_back().is_none_or(|c| !part(c));
        let after = text[i + word.len()..]
            .chars()
            .next()
            .is_none_or(|c| !part(c));
        before && after
    })
}
