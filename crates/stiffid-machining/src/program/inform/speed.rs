//! INFORM's speed tag: `V=` (mm/s) on a `MOVL` ([`crate::program::speed`]).

use crate::program::speed::{literal, path, Speed};
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// The speed of the INFORM motion `word` (`MOVJ`, `MOVL`) with its `tags` (`V=100.0`).
///
/// # Errors
/// A literal speed outside its limits, naming the line.
pub(crate) fn speed(line: u64, word: &str, tags: &[&str]) -> Result<Speed> {
    if word.eq_ignore_ascii_case("MOVJ") {
        return Ok(Speed::Joint);
    }
    let tag = |name: &str| {
        (tags.iter()).find_map(|t| {
            t.get(..name.len())
                .filter(|h| h.eq_ignore_ascii_case(name))
                .map(|_| &t[name.len()..])
        })
    };
    match (tag("V="), tag("VR="), tag("VE=")) {
        (Some(v), _, _) => match literal(v) {
            Some(mm_s) => path(line, &format!("V={v}"), mm_s),
            None => Ok(Speed::Unread(format!(
                "V={}: the speed is held in a variable on the controller",
                short(v)
            ))),
        },
        (None, Some(v), _) => Ok(Speed::Unread(format!(
            "VR={}: an orientation speed; the TCP's is the controller's",
            short(v)
        ))),
        (None, None, Some(v)) => Ok(Speed::Unread(format!(
            "VE={}: an external axis's speed; the TCP's is the controller's",
            short(v)
        ))),
        _ => Ok(Speed::Unread(
            "no V= tag: the speed is the controller's".into(),
        )),
    }
}
