//! LS's speed word: `mm/sec`, `cm/min`, `inch/min`, or a time in `sec` or `msec`
//! ([`crate::program::speed`]).

use crate::program::number_at;
use crate::program::speed::{duration, path, Speed};
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// The speed of the LS motion `letter` (`J`, `L`) whose speed word is `word` (`100mm/sec`).
///
/// # Errors
/// A literal speed or time outside its limits, naming the line.
pub(crate) fn speed(line: u64, letter: &str, word: &str) -> Result<Speed> {
    if letter == "J" {
        return Ok(Speed::Joint);
    }
    let Some((v, span)) = number_at(word, 0).filter(|(_, s)| s.start == 0) else {
        let why = match word.to_ascii_uppercase().starts_with("R[") || word.contains('[') {
            true => "the speed is held in a register on the controller",
            false => "a speed stiffid does not read",
        };
        return Ok(Speed::Unread(format!("{}: {why}", short(word))));
    };
    match word[span.end..].to_ascii_lowercase().as_str() {
        "mm/sec" => path(line, word, v),
        "cm/min" => path(line, word, v * 10.0 / 60.0),
        "inch/min" => path(line, word, v * 25.4 / 60.0),
        "sec" => duration(line, word, v),
        "msec" => duration(line, word, v * 1e-3),
        "deg/sec" => Ok(Speed::Unread(format!(
            "{word}: an orientation speed; the TCP's is the controller's"
        ))),
        _ => Ok(Speed::Unread(format!(
            "{}: a speed unit stiffid does not read (mm/sec, cm/min, inch/min, sec, msec)",
            short(word)
        ))),
    }
}
