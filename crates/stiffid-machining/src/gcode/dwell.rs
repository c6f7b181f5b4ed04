//! A dwell, `G4 P..`, kept in path order among the process words ([`ProcessWord::dwell`]) so
//! that a robot program written from the path waits where the G-code does (KRL `WAIT SEC`,
//! RAPID `WaitTime`, LS `WAIT`, INFORM `TIMER`).
//!
//! Its time is the controller's reading of `P` ([`GcodeDialect`], the setup's `[controller]
//! dialect`): seconds on LinuxCNC (its manual, "G4 Dwell") and grbl (1.1, "G4 P: dwell in
//! seconds"); milliseconds on FANUC (Series 0i/30i, "Dwell (G04)": P without a decimal point,
//! in the least increment of 1 ms); on Haas seconds with a decimal point and milliseconds without
//! (Haas mill operator's manual, "G04 Dwell": `G04 P10.` 10 s, `G04 P10` 10 ms). Where the setup
//! does not say, `P0` is no time on every controller and any other `P` is not known: a program
//! written from the path refuses it naming the line. FANUC and Haas also take the time as `X`
//! (`G04 X1.5`: seconds with a decimal point; without one the last digit is 1/1000, the least
//! input increment: `X1500` 1.5 s); the `X` is then no axis word. LinuxCNC and grbl read an `X`
//! beside `G4` as a move, so there, and where the setup names no dialect, the block is refused
//! (module `block`). A `G82`'s `P` (the dwell at the hole's bottom) is read as `G4 P` is.

use super::process::ProcessWord;
use super::words::Word;
use super::{GcodeDialect, State};

/// A dwell's time as a block gives it: seconds or why not known, and its words as written.
pub(super) type Given = (Result<f64, String>, String);

/// The words of a block on `line` (spans in `text`) without a `G4`'s `X` where the setup's
/// dialect reads it as the dwell's time (FANUC, Haas: module docs), and that time; the words as
/// they are otherwise.
///
/// # Errors
/// [`Error::Program`](stiffid_core::Error::Program) for a `G4` with both `X` and `P`.
pub(super) fn time_in_x(
    line: u64,
    words: Vec<Word>,
    text: &str,
    dialect: Option<GcodeDialect>,
) -> stiffid_core::Result<(Vec<Word>, Option<Given>)> {
    let reads_x = matches!(dialect, Some(GcodeDialect::Fanuc | GcodeDialect::Haas));
    let g4 = words.iter().any(|w| w.letter == 'G' && w.value == 4.0);
    let Some(x) = words
        .iter()
        .position(|w| w.letter == 'X')
        .filter(|_| g4 && reads_x)
    else {
        return Ok((words, None));
    };
    if words.iter().any(|w| w.letter == 'P') {
        return Err(super::at(
            line,
            "G4 with both X and P: one dwell time, as X (seconds) or P".into(),
        ));
    }
    let mut words = words;
    let w = words.remove(x);
    let written = text.get(w.span.clone()).unwrap_or("X");
    let seconds = match written.contains('.') {
        _ if w.value < 0.0 || !w.value.is_finite() => {
            Err(format!("G4 {written}: a dwell time is not negative"))
        }
        true => Ok(w.value),
        false => Ok(w.value * 1e-3),
    };
    Ok((words, Some((seconds, format!("G4 {written}")))))
}

/// Keeps the dwell of a block (`words`, spans in `text`; `x` its time given as `X`,
/// [`time_in_x`]) on `line` in `s.process`, if it has `G4` (module docs).
pub(super) fn gather(line: u64, (words, text): (&[Word], &str), x: Option<Given>, s: &mut State) {
    if !words.iter().any(|w| w.letter == 'G' && w.value == 4.0) {
        return;
    }
    let p = words.iter().rev().find(|w| w.letter == 'P');
    let (dwell, written) = match (x, p) {
        (Some(given), _) => given,
        (None, None) => (Err("G4 without P: no dwell time".into()), "G4".to_string()),
        (None, Some(w)) => {
            let written = text.get(w.span.clone()).unwrap_or("P");
            let point = written.contains('.');
            (
                seconds(w.value, point, ("G4", s.machine.dialect)),
                format!("G4 {written}"),
            )
        }
    };
    push(line, (dwell, written), None, s);
}

/// The dwell of a `G82` on `line` at the hole's bottom, the path point `point`: its `P` as
/// written (`text`), read as `G4 P` is ([`seconds`]); none for `P0`.
pub(super) fn at_bottom(line: u64, (p, text): (f64, &str), point: usize, s: &mut State) {
    if p == 0.0 {
        return;
    }
    let seconds = seconds(p, text.contains('.'), ("G82", s.machine.dialect));
    push(line, (seconds, format!("G82 {text}")), Some(point), s);
}

fn push(line: u64, (dwell, words): Given, point: Option<usize>, s: &mut State) {
    s.process.push(ProcessWord {
        line,
        event: None,
        words,
        rpm: s.rpm,
        tool: s.selected,
        dwell: Some(dwell),
        point,
    });
}

/// The dwell `P` (`point`: written with a decimal point) in seconds on `dialect` (module docs).
fn seconds(
    p: f64,
    point: bool,
    (code, dialect): (&str, Option<GcodeDialect>),
) -> Result<f64, String> {
    if p < 0.0 || !p.is_finite() {
        return Err(format!("{code} P{p}: a dwell time is not negative"));
    }
    match dialect {
        _ if p == 0.0 => Ok(0.0),
        Some(GcodeDialect::LinuxCnc | GcodeDialect::Grbl) => Ok(p),
        Some(GcodeDialect::Fanuc) if point => Err(format!("{code} P{p}: FANUC takes P in milliseconds without a decimal point (an alarm with one); write {code} P{}", (p * 1e3).round())),
        Some(GcodeDialect::Fanuc) => Ok(p * 1e-3),
        Some(GcodeDialect::Haas) => Ok(if point { p } else { p * 1e-3 }),
        None => Err(format!("{code} P{p}: LinuxCNC and grbl dwell P seconds, FANUC P milliseconds (Haas: seconds with a decimal point, milliseconds without); state which controller runs the program, [controller] dialect = \"linuxcnc\", \"fanuc\", \"haas\" or \"grbl\" in the setup")),
    }
}
