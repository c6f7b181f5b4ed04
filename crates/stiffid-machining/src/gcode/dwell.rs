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
//! written from the path refuses it naming the line.

use super::process::ProcessWord;
use super::words::Word;
use super::{GcodeDialect, State};

/// Keeps the dwell of a block (`words`, spans in `text`) on `line` in `s.process`, if it has
/// `G4` (module docs).
pub(super) fn gather(line: u64, (words, text): (&[Word], &str), s: &mut State) {
    if !words.iter().any(|w| w.letter == 'G' && w.value == 4.0) {
        return;
    }
    let p = words.iter().rev().find(|w| w.letter == 'P');
    let (dwell, written) = match p {
        None => (Err("G4 without P: no dwell time".into()), "G4".to_string()),
        Some(w) => {
            let written = text.get(w.span.clone()).unwrap_or("P");
            let point = written.contains('.');
            (
                seconds(w.value, point, s.machine.dialect),
                format!("G4 {written}"),
            )
        }
    };
    s.process.push(ProcessWord {
        line,
        event: None,
        words: written,
        rpm: s.rpm,
        tool: s.selected,
        dwell: Some(dwell),
    });
}

/// The dwell `P` (`point`: written with a decimal point) in seconds on `dialect` (module docs).
fn seconds(p: f64, point: bool, dialect: Option<GcodeDialect>) -> Result<f64, String> {
    if p < 0.0 || !p.is_finite() {
        return Err(format!("G4 P{p}: a dwell time is not negative"));
    }
    match dialect {
        _ if p == 0.0 => Ok(0.0),
        Some(GcodeDialect::LinuxCnc | GcodeDialect::Grbl) => Ok(p),
        Some(GcodeDialect::Fanuc) if point => Err(format!("G4 P{p}: FANUC takes P in milliseconds without a decimal point (an alarm with one); write G4 P{}", (p * 1e3).round())),
        Some(GcodeDialect::Fanuc) => Ok(p * 1e-3),
        Some(GcodeDialect::Haas) => Ok(if point { p } else { p * 1e-3 }),
        None => Err(format!("G4 P{p}: LinuxCNC and grbl dwell P seconds, FANUC P milliseconds (Haas: seconds with a decimal point, milliseconds without); state which controller runs the program, [controller] dialect = \"linuxcnc\", \"fanuc\", \"haas\" or \"grbl\" in the setup")),
    }
}
