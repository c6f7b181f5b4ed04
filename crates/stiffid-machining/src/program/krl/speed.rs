//! KRL's path speed: `$VEL.CP` and `BAS(#CP_PARAMS)` in force from their line, `WITH $VEL..`
//! on a motion for it alone ([`crate::program::speed`]).

use crate::program::speed::{literal, path, Speed};
use stiffid_core::common::limits::short;
use stiffid_core::Result;

/// The KRL path speed in force while a program is read line by line (module docs).
#[derive(Debug, Clone)]
pub(crate) struct Krl {
    pub(super) in_force: Speed,
}

impl Default for Krl {
    fn default() -> Self {
        Self::new()
    }
}

impl Krl {
    /// Before any line: no speed set.
    pub(crate) fn new() -> Self {
        let why = "no $VEL.CP set before it in the program: its speed is the controller's";
        Krl {
            in_force: Speed::Unread(why.into()),
        }
    }

    /// A speed the program does not state, for the reason `why`.
    pub(crate) fn unread(why: String) -> Self {
        Krl {
            in_force: Speed::Unread(why),
        }
    }

    /// Reads the line `code` (its comment removed) if it sets the path speed; whether it did.
    ///
    /// # Errors
    /// A literal speed outside (0, 10] m/s, naming the line.
    pub(crate) fn set(&mut self, line: u64, code: &str) -> Result<bool> {
        let c = compact(code);
        // The value as written: after the `=` or the `,`, up to a closing `)`.
        let value = |after: char| {
            let v = code.split_once(after).map_or("", |(_, v)| v.trim());
            v.strip_suffix(')').unwrap_or(v).trim()
        };
        let speed = if c.starts_with("$VEL.CP=") {
            krl_value(line, "$VEL.CP", value('='))?
        } else if c.starts_with("BAS(#CP_PARAMS,") {
            krl_value(line, "BAS(#CP_PARAMS)", value(','))?
        } else if c.starts_with("$VEL=") {
            Speed::Unread(format!(
                "line {line} sets $VEL as a whole, which stiffid does not read: set $VEL.CP"
            ))
        } else if ["BAS(#INITMOV", "BAS(#VEL_CP", "BAS(#CP_DAT"]
            .iter()
            .any(|b| c.starts_with(b))
        {
            Speed::Unread(format!("line {line} sets the path speed by {}, to the controller's value: set $VEL.CP after it", short(code.trim())))
        } else {
            return Ok(false);
        };
        self.in_force = speed;
        Ok(true)
    }

    /// The speed of the motion `first` (`PTP`, `LIN`, ..) on the line `code`: its own
    /// `WITH $VEL..`, else the one in force.
    ///
    /// # Errors
    /// A literal speed outside (0, 10] m/s, naming the line.
    pub(crate) fn motion(&self, line: u64, first: &str, code: &str) -> Result<Speed> {
        if matches!(first, "PTP" | "SPTP") {
            return Ok(Speed::Joint);
        }
        let c = compact(code);
        let own = c.split_once("WITH").map(|(_, w)| w).and_then(|w| {
            let v = (w.split_once("$VEL.CP=").map(|(_, v)| v))
                .or_else(|| w.split_once("$VEL=SVEL_CP(").map(|(_, v)| v))?;
            Some(v.split([',', ')']).next().unwrap_or(v))
        });
        match own {
            Some(v) => krl_value(line, "WITH $VEL", v),
            None => Ok(self.in_force.clone()),
        }
    }
}

/// A KRL speed `value` (m/s) set on `line` by `what`: a literal, checked, or unread.
fn krl_value(line: u64, what: &str, value: &str) -> Result<Speed> {
    match literal(value) {
        Some(v) => path(line, &format!("{what} = {value} m/s"), v * 1e3),
        None => Ok(Speed::Unread(format!(
            "line {line} sets {what} to '{}', which stiffid does not evaluate",
            short(value)
        ))),
    }
}

/// `text` without blanks, upper case: a KRL statement's words as the controller reads them.
fn compact(text: &str) -> String {
    let kept = text.chars().filter(|c| !c.is_whitespace());
    kept.collect::<String>().to_ascii_uppercase()
}
