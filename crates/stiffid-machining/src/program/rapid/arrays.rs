//! RAPID arrays of targets declared with their values (`CONST robtarget pts{3} := [[..],[..],
//! [..]];`, also `jointtarget`, and two-dimensional: `pts{2,3} := [[[..],[..],[..]],[..]]`):
//! each element a target of its own (`pts{2}`, `pts{1,3}`), its numbers in
//! the array's declaration (*RAPID kernel*: arrays, aggregates). An element is written back in
//! place; two visits of one element compensated apart are refused naming both lines (an element
//! is not copied under another name).

use super::{arguments, cartesian, Declared, Statement};
use crate::program::cartesian::literal;

/// The elements of the array `name` of `kind` (`robtarget`, `jointtarget`) declared by the
/// statement `s` of `code`, its value after the `:=` at byte `eq` of the statement, into
/// `declared` as `name{1}`, `name{2}`..; the name alone refused (a motion moves to an element).
pub(super) fn declare(
    (name, kind): (&str, &str),
    (code, s, eq): (&str, &Statement, usize),
    declared: &mut Declared,
) {
    let from = s.span.start + eq + 2;
    let line = s.line;
    let parsed = literal::parse(code, from).and_then(|(node, end)| {
        let open = from + code[from..].find('[')?;
        Some((node.list()?.len(), open, end))
    });
    let Some((n, open, end)) = parsed else {
        let why = format!("{name} is an array of {kind}s (line {line}) whose value is not a literal: declare its elements with their values");
        declared.insert(name.to_string(), Err(why));
        return;
    };
    let inner = &code[open + 1..end - 1];
    let element = |at: usize| match kind {
        "robtarget" => cartesian::robtarget(line, code, at),
        _ => super::literal(line, code, at),
    };
    for (k, r) in arguments::top_level(inner).into_iter().enumerate() {
        let at = open + 1 + r.start;
        let item = inner[r.clone()].trim_start();
        // A row of a two-dimensional array (`pts{2,3}`): a list of targets.
        if item.starts_with("[[[") {
            let lead = inner[r.clone()].len() - item.len();
            let item = item.trim_end();
            let row_open = at + lead;
            let Some(row) = item.strip_prefix('[').and_then(|i| i.strip_suffix(']')) else {
                continue;
            };
            for (m, e) in arguments::top_level(row).into_iter().enumerate() {
                let t = element(row_open + 1 + e.start);
                let key = format!("{name}{{{},{}}}", k + 1, m + 1);
                declared.insert(key, t.map_err(|e| e.to_string()));
            }
            continue;
        }
        declared.insert(
            format!("{name}{{{}}}", k + 1),
            element(at).map_err(|e| e.to_string()),
        );
    }
    let why = format!("{name} is an array of {kind}s (line {line}): a motion moves to one of its elements, {name}{{1}} to {name}{{{n}}}");
    declared.insert(name.to_string(), Err(why));
}

/// The key of the element `text` (`pts{2}`, `pts{i + 1}`) of an array, its index the value of
/// the expression between the braces (`index`, the `num` data the module states), or why it has
/// none: an index that is not a whole number from 1, or that the run gives.
pub(super) fn element(
    text: &str,
    index: &dyn Fn(&str) -> std::result::Result<f64, String>,
) -> std::result::Result<String, String> {
    let (name, rest) = text.split_once('{').unwrap_or((text, ""));
    let Some(expr) = rest.strip_suffix('}') else {
        return Err(format!("{text}: expected an element name{{index}}"));
    };
    let mut at = Vec::new();
    for r in arguments::top_level(expr) {
        let v = index(&expr[r]).map_err(|why| format!("{text}: its index {why}"))?;
        if v.fract() != 0.0 || !(1.0..=1e9).contains(&v) {
            return Err(format!(
                "{text}: its index is {v}, not a whole number from 1"
            ));
        }
        at.push((v as u64).to_string());
    }
    Ok(format!(
        "{}{{{}}}",
        name.trim().to_ascii_lowercase(),
        at.join(",")
    ))
}
