//! The configuration data of a Cartesian target as each controller writes it
//! ([`stiffid_core::robot::configuration`] defines them from the posture).

use super::super::Dialect;
use stiffid_core::robot::configuration::Configuration;

/// A target's configuration data.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Flags {
    /// KUKA status (its three low bits) and turn (six bits).
    Kuka(u8, u8),
    /// ABB `confdata` `[cf1, cf4, cf6, cfx]`.
    Abb([i64; 4]),
    /// FANUC `CONFIG`, as [`Configuration::fanuc`] writes it: `N U T, 0, 0, 0`.
    Fanuc(String),
}

impl Flags {
    /// The data of the posture `arm` in `dialect` (its controller's
    /// [`crate::program::Controller::flags`]; KRL's for INFORM, which has no Cartesian targets
    /// here).
    pub fn of(dialect: Dialect, arm: &Configuration) -> Self {
        dialect.controller().flags(arm)
    }

    /// The shoulder, elbow and wrist the data name, as [`stiffid_core::robot::configuration`] reads
    /// them from a posture: the wrist centre behind axis 1, the elbow down, axis 5 negative
    /// (or zero, for KUKA and FANUC).
    pub fn branch(&self) -> (bool, bool, bool) {
        match self {
            Flags::Kuka(s, _) => (s & 1 != 0, s & 2 == 0, s & 4 != 0),
            Flags::Abb(c) => (c[3] & 4 != 0, c[3] & 2 != 0, c[3] & 1 != 0),
            Flags::Fanuc(f) => (f.contains('B'), f.contains('D'), f.starts_with('N')),
        }
    }

    /// As the program writes them, for messages.
    pub fn text(&self) -> String {
        match self {
            Flags::Kuka(s, t) => format!("S 'B{s:03b}' T 'B{t:06b}'"),
            Flags::Abb([a, b, c, d]) => format!("[{a},{b},{c},{d}]"),
            Flags::Fanuc(f) => format!("'{f}'"),
        }
    }

    /// FANUC's `CONFIG` text (inside the quotes) as the data, or why not: a flip `F`/`N`, an
    /// elbow `U`/`D`, a side `T`/`B` (in any order, blanks or none between), then the three
    /// turn numbers of J1, J4 and J6 (absent ones 0).
    pub fn fanuc(text: &str) -> Result<Self, String> {
        let (letters, turns) = text.split_once(',').unwrap_or((text, ""));
        let letters: String = letters.chars().filter(|c| !c.is_whitespace()).collect();
        let letters = letters.to_ascii_uppercase();
        let pick = |a: char, b: char| {
            match (letters.contains(a), letters.contains(b)) {
            (true, false) => Ok(a),
            (false, true) => Ok(b),
            _ => Err(format!(
                "CONFIG '{text}': expected one of {a} and {b} among its letters (flip F/N, elbow U/D, side T/B)"
            )),
        }
        };
        let (flip, elbow, side) = (pick('F', 'N')?, pick('U', 'D')?, pick('T', 'B')?);
        if letters.len() != 3 {
            return Err(format!(
                "CONFIG '{text}': expected three letters (flip F/N, elbow U/D, side T/B)"
            ));
        }
        let mut t = [0i64; 3];
        for (k, w) in turns
            .split(',')
            .map(str::trim)
            .filter(|w| !w.is_empty())
            .enumerate()
        {
            let slot = t.get_mut(k).ok_or_else(|| {
                format!("CONFIG '{text}': more than three turn numbers (J1, J4, J6)")
            })?;
            *slot = w
                .parse()
                .map_err(|_| format!("CONFIG '{text}': turn number '{w}' is not a whole number"))?;
        }
        Ok(Flags::Fanuc(format!(
            "{flip} {elbow} {side}, {}, {}, {}",
            t[0], t[1], t[2]
        )))
    }
}

/// Where a part of the data sits and how it is written back.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// KUKA status, as a binary string `'B..'` or a decimal number.
    Status {
        /// Written as a binary string.
        binary: bool,
    },
    /// KUKA turn, likewise.
    Turn {
        /// Written as a binary string.
        binary: bool,
    },
    /// ABB `confdata` member `k` (0: cf1, 1: cf4, 2: cf6, 3: cfx).
    Abb(usize),
    /// FANUC `CONFIG`'s text inside its quotes.
    Fanuc,
}

impl Part {
    /// The text of this part of `flags`.
    pub fn text(self, flags: &Flags) -> String {
        match (self, flags) {
            (Part::Status { binary: true }, Flags::Kuka(s, _)) => format!("'B{s:03b}'"),
            (Part::Turn { binary: true }, Flags::Kuka(_, t)) => format!("'B{t:06b}'"),
            (Part::Status { .. }, Flags::Kuka(s, _)) => s.to_string(),
            (Part::Turn { .. }, Flags::Kuka(_, t)) => t.to_string(),
            (Part::Abb(k), Flags::Abb(c)) => c[k].to_string(),
            (_, Flags::Fanuc(f)) => f.clone(),
            (_, other) => other.text(),
        }
    }
}
