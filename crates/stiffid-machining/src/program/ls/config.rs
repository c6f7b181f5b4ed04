//! FANUC's configuration data of a position in Cartesian representation, `CONFIG` (FANUC
//! R-30iA/R-30iB operator's manual, "Configuration"), from the posture
//! ([`stiffid_core::robot::configuration`]): `'W E S, t1, t4, t6'`, `F` (flip) when J5 > 0,
//! else `N`; `U` (up) with the elbow in front, else `D`; `T` (front) in front of axis 1, else
//! `B`; the turn numbers of J1, J4 and J6: `floor((q + 180 deg) / 360 deg)`.

use crate::program::cartesian::flags::{Branch, ConfigurationData};
use std::fmt;
use stiffid_core::robot::configuration::Configuration;

/// `CONFIG`'s text inside its quotes, as stiffid writes it: `N U T, 0, 0, 0` (module docs).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Config(String);

impl Config {
    /// `CONFIG`'s text (inside the quotes) as the data, or why not: a flip `F`/`N`, an elbow
    /// `U`/`D`, a side `T`/`B` (in any order, blanks or none between), then the three turn
    /// numbers of J1, J4 and J6 (absent ones 0).
    ///
    /// # Errors
    /// What the text lacks or has too many of, naming it.
    pub(crate) fn parse(text: &str) -> Result<Self, String> {
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
        for (k, w) in (turns.split(',').map(str::trim))
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
        Ok(Config(format!(
            "{flip} {elbow} {side}, {}, {}, {}",
            t[0], t[1], t[2]
        )))
    }

    /// The text inside the quotes.
    pub fn as_str(&self) -> &str {
        &self.0
    }
}

impl fmt::Display for Config {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl ConfigurationData for Config {
    /// Written whole, inside its quotes.
    type Part = ();
    const NAME: &'static str = "CONFIG";
    fn of(arm: &Configuration) -> Self {
        let turn = |q: f64| ((q + 180.0) / 360.0).floor() as i64;
        Config(format!(
            "{} {} {}, {}, {}, {}",
            if arm.q_deg[4] > 0.0 { 'F' } else { 'N' },
            if arm.elbow_down() { 'D' } else { 'U' },
            if arm.behind() { 'B' } else { 'T' },
            turn(arm.q_deg[0]),
            turn(arm.q_deg[3]),
            turn(arm.q_deg[5])
        ))
    }
    fn branch(&self) -> Branch {
        let f = &self.0;
        (f.contains('B'), f.contains('D'), f.starts_with('N'))
    }
    fn text(&self) -> String {
        format!("'{}'", self.0)
    }
    fn part(&self, _part: ()) -> String {
        self.0.clone()
    }
}
