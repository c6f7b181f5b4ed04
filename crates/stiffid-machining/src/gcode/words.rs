//! The words of a block: read from a line, comments read for the header and operation names,
//! and what the subset refuses before any word is applied.

use super::{at, State};
use nalgebra::UnitQuaternion;
use std::ops::Range;
use stiffid_core::common::words::number;
use stiffid_core::Result;

/// A word: letter, value and span (bytes of the text).
pub(super) struct Word {
    pub(super) letter: char,
    pub(super) value: f64,
    pub(super) span: Range<usize>,
}

/// The words of one line (`start`: its first byte's in the text); comments are read for the
/// header and operation names. A byte-order mark opening the text is no word.
pub(super) fn words(line: u64, start: usize, l: &str, s: &mut State) -> Result<Vec<Word>> {
    let mut out = Vec::new();
    let opening = l.trim_start_matches(['\u{feff}', ' ', '\t']);
    if opening.starts_with('%') {
        // The tape's start or end (RS-274, LinuxCNC's manual "File Requirements"): the rest
        // of the line, a program name on some controls, is no block.
        return Ok(out);
    }
    if opening.starts_with('/') {
        return Err(at(line, "/: a block delete line: whether the controller runs it depends on its block delete switch, which the program does not say; remove the '/' (run it) or the line".into()));
    }
    if let Some(flow) = o_word_flow(opening) {
        return Err(at(line, format!("O-word '{flow}': subprograms, loops and conditions (LinuxCNC's O codes) are not followed; expand the program into one file of plain blocks first")));
    }
    let mut i = 0;
    while let Some(c) = l[i..].chars().next() {
        if c == '(' {
            let end = l[i..]
                .find(')')
                .map(|e| i + e)
                .ok_or_else(|| at(line, "comment without its closing ')'".into()))?;
            comment(line, &l[i + 1..end], s)?;
            i = end + 1;
            continue;
        }
        if c == ';' {
            comment(line, &l[i + 1..], s)?;
            break;
        }
        if c.is_whitespace() || c == '%' || (c == '\u{feff}' && start + i == 0) {
            i += c.len_utf8();
            continue;
        }
        let letter = c.to_ascii_uppercase();
        if c == '#' || c == '[' {
            return Err(at(line, format!("'{c}': parameters and expressions (#1 = 2.5, #<name>, [#1 * 2]) are not evaluated; have the post write numbers")));
        }
        if c == '/' {
            // A `/` within a block: controls that read it skip the words after it with their
            // block delete switch on; LinuxCNC reads block delete at a line's start only.
            return Err(at(line, "/ within the block: a block delete of the words after it on controls that read it there, an error on others (LinuxCNC), and whether they run depends on the block delete switch, which the program does not say; remove the '/' (run them) or the words".into()));
        }
        // `@` and `^`: LinuxCNC's polar distance and angle (module `polar`).
        if !(letter.is_ascii_alphabetic() || c == '@' || c == '^') {
            return Err(at(
                line,
                format!("'{c}': expected a word (a letter and a number)"),
            ));
        }
        let next = l[i + 1..].trim_start().chars().next();
        if let Some(c @ ('#' | '[')) = next {
            return Err(at(line, format!("'{c}': parameters and expressions (#1 = 2.5, #<name>, [#1 * 2]) are not evaluated; have the post write numbers")));
        }
        let (value, span) = crate::text::number_at(l, i + 1).ok_or_else(|| {
            at(
                line,
                format!("{letter}: expected a number after the letter"),
            )
        })?;
        let digits = &l[span.clone()];
        if digits.contains(['e', 'E']) {
            return Err(at(line, format!("{letter}{digits}: a number with an exponent is no G-code number (a controller reads {letter}{} and then a word E); write it out", &digits[..digits.find(['e', 'E']).unwrap_or(0)])));
        }
        out.push(Word {
            letter,
            value,
            span: start + i..start + span.end,
        });
        i = span.end;
    }
    Ok(out)
}

/// The keyword of an O-word that starts a subprogram, a call, a loop or a condition
/// (`O100 sub`, `o<probe> call`, `O1 if [..]`), if the line opens with one.
fn o_word_flow(opening: &str) -> Option<String> {
    let rest = opening.strip_prefix(['O', 'o'])?;
    let rest = match rest.strip_prefix('<') {
        Some(named) => &named[named.find('>')? + 1..],
        None => rest.trim_start_matches(|c: char| c.is_ascii_digit() || c == ' ' || c == '\t'),
    };
    let word: String = rest
        .trim_start()
        .chars()
        .take_while(char::is_ascii_alphabetic)
        .collect();
    const FLOW: [&str; 13] = [
        "sub",
        "endsub",
        "call",
        "return",
        "if",
        "elseif",
        "else",
        "endif",
        "while",
        "endwhile",
        "do",
        "repeat",
        "endrepeat",
    ];
    let w = word.to_ascii_lowercase();
    (FLOW.contains(&w.as_str()) || opening[1..].starts_with('<')).then(|| limits_short(opening))
}

fn limits_short(text: &str) -> String {
    stiffid_core::common::limits::short(text.trim())
}

pub(super) fn comment(line: u64, text: &str, s: &mut State) -> Result<()> {
    let t = text.trim();
    if let Some(name) = t.strip_prefix("operation:") {
        s.operation = Some(name.trim().into());
    }
    let Some(directive) = t.strip_prefix("stiffid:") else {
        if !t.is_empty() {
            s.line_comments.push(t.to_string());
        }
        return Ok(());
    };
    let (key, value) = directive
        .split_once('=')
        .ok_or_else(|| at(line, "stiffid header: expected 'key = value'".into()))?;
    match key.trim() {
        "tool_rpy_deg" => {
            let v: Vec<f64> = value
                .split_whitespace()
                .map(str::parse)
                .collect::<std::result::Result<_, _>>()
                .map_err(|_| at(line, "tool_rpy_deg: expected three numbers, deg".into()))?;
            if v.len() != 3
                || v.iter()
                    .any(|a| !stiffid_core::common::limits::ANGLE_DEG.contains(*a))
            {
                return Err(at(
                    line,
                    format!(
                        "tool_rpy_deg: expected three numbers within {}",
                        stiffid_core::common::limits::ANGLE_DEG
                    ),
                ));
            }
            s.tool = Some(UnitQuaternion::from_euler_angles(
                v[0].to_radians(),
                v[1].to_radians(),
                v[2].to_radians(),
            ));
        }
        "surface_mm" => {
            s.surface = match value.trim().parse::<f64>() {
                Ok(z) if z.is_finite() && z.abs() <= 1e5 => z * 1e-3,
                _ => return Err(at(line, "surface_mm: expected the part's surface, the Z (mm, part frame) a canned cycle drills into, within +-100000 mm".into())),
            };
        }
        "rotary" if value.trim().eq_ignore_ascii_case("abc") => {
            if let Some(l) = s.external.0.iter().find(|l| matches!(l, 'A' | 'B' | 'C')) {
                return Err(at(line, format!("rotary = abc: {l} drives an external axis (line {}); a letter turns the tool or drives an axis, not both", s.external.1)));
            }
            s.rotary = true;
        }
        "rotary" => {
            return Err(at(
                line,
                format!(
                    "rotary = {}: expected abc (A B C words turn the tool)",
                    stiffid_core::common::limits::short(value.trim())
                ),
            ))
        }
        "external" => {
            let letters: Vec<char> = value
                .split_whitespace()
                .map(|w| match w.to_ascii_uppercase().as_str() {
                    l @ ("U" | "V" | "W" | "A" | "B" | "C") => Ok(l.chars().next().unwrap_or('U')),
                    other => Err(at(line, format!("external: '{}' is no axis letter (expected U V W for linear axes, A B C for rotary ones, one per external axis of the cell in its order)", stiffid_core::common::limits::short(other)))),
                })
                .collect::<Result<_>>()?;
            if letters.is_empty() || letters.len() > stiffid_core::robot::external::MAX_AXES {
                return Err(at(line, format!("external: expected 1 to {} letters, one per external axis of the cell in its order", stiffid_core::robot::external::MAX_AXES)));
            }
            if let Some((i, l)) = letters.iter().enumerate().find(|(i, l)| letters[..*i].contains(l)) {
                return Err(at(line, format!("external: {l} given twice (letter {})", i + 1)));
            }
            if s.rotary && letters.iter().any(|l| matches!(l, 'A' | 'B' | 'C')) {
                return Err(at(line, "external: A, B and C turn the tool (rotary = abc): a letter turns the tool or drives an axis, not both".into()));
            }
            if !s.external.0.is_empty() {
                return Err(at(line, format!("external: the external axes are mapped already (line {})", s.external.1)));
            }
            s.e = vec![None; letters.len()];
            s.external = (letters, line);
        }
        other => {
            return Err(at(
                line,
                format!(
                    "stiffid header: unknown '{}' (expected tool_rpy_deg = R P Y, rotary = abc, external = LETTERS or surface_mm = Z)",
                    stiffid_core::common::limits::short(other)
                ),
            ))
        }
    }
    Ok(())
}

/// The largest feed rate `F` accepted (mm/min, or inch/min after `G20`).
pub(crate) const MAX_FEED: f64 = 1e6;

/// The largest spindle speed `S` accepted (rev/min), the process file's `spindle_rpm`'s.
const MAX_SPINDLE_RPM: f64 = 1e5;

/// What the subset refuses in the words of one block, before any is applied: a letter given twice
/// (`G` and `M` aside: several modal groups may share a block), a feed rate outside
/// `(0, MAX_FEED]`, a spindle speed outside `[0, MAX_SPINDLE_RPM]` (it is written into the robot
/// program's spindle calls, `{rpm}`), an `M` code not a whole number from 0 to 999 (it is written
/// into the robot program as an event or comment), a subprogram call or return (`M97`, `M98`, `M99`: the path would go where
/// this file does not say). `M2`/`M30` end the program: a motion after them is refused.
pub(super) fn check_words(line: u64, words: &[Word], s: &mut State) -> Result<()> {
    for (i, w) in words.iter().enumerate() {
        let again = words[..i].iter().any(|o| o.letter == w.letter);
        if again && !matches!(w.letter, 'G' | 'M') {
            return Err(at(line, format!("{} given twice in one block", w.letter)));
        }
        match w.letter {
            'F' if !(w.value > 0.0 && w.value <= MAX_FEED) => {
                return Err(at(
                    line,
                    format!(
                        "F{}: expected a feed rate in (0, {MAX_FEED}] (mm/min, inch/min after G20)",
                        number(w.value)
                    ),
                ));
            }
            'S' if !(0.0..=MAX_SPINDLE_RPM).contains(&w.value) => {
                return Err(at(
                    line,
                    format!(
                        "S{}: expected a spindle speed from 0 to {MAX_SPINDLE_RPM} rev/min",
                        number(w.value)
                    ),
                ));
            }
            'M' if !(w.value.fract() == 0.0 && (0.0..=999.0).contains(&w.value)) => {
                return Err(at(
                    line,
                    format!(
                        "M{}: expected an M code, a whole number from 0 to 999",
                        number(w.value)
                    ),
                ));
            }
            'M' if [97.0, 98.0, 99.0].contains(&w.value) => {
                return Err(at(
                    line,
                    format!("M{}: subprogram calls and returns are not followed; expand the program into one file first", w.value),
                ));
            }
            'M' if w.value == 2.0 || w.value == 30.0 => s.ended = Some(line),
            _ => {}
        }
    }
    Ok(())
}
