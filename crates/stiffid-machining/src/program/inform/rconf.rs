//! Yaskawa's manipulator type of a position in Cartesian form, `///RCONF l,m,n,o,p,q,..` (the
//! job data format of the DX100/NX100 offline-teaching interface, "RCONF": `l` 0 flip, 1 no
//! flip; `m` 0 upper arm, 1 lower arm; `n` 0 front, 1 rear; `o`, `p`, `q` 0 when the R, T and S
//! axes are under 180 deg, 1 when at or beyond it; the numbers after them unused), from the
//! posture ([`stiffid_core::robot::configuration`]) as Yaskawa defines each choice (its YMConnect
//! SDK, `FrontOrBack`, `UpperOrLower`, `FlipOrNoFlip`, `AxisAngle`): flip with the B axis at 0
//! deg or more, no flip below; front with the B axis's centre in front of the S axis, rear
//! behind it; upper arm with the elbow (L and U axes) under 180 deg, lower arm beyond; an axis
//! "under 180 deg" from -180 deg excluded to 180 deg included, "at or beyond" outside.

use crate::program::cartesian::flags::{Branch, ConfigurationData};
use stiffid_core::robot::configuration::Configuration;

/// `///RCONF`'s six meaningful numbers, each 0 or 1 (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Rconf(pub(crate) [u8; 6]);

impl Rconf {
    /// The numbers after `///RCONF` (`0,0,0,0,0,0,0,0`): the six first, each 0 or 1; the
    /// unused ones after them any whole numbers.
    ///
    /// # Errors
    /// What is wrong, in words.
    pub(crate) fn parse(text: &str) -> Result<Self, String> {
        let words: Vec<&str> = text.split(',').map(str::trim).collect();
        if words.len() < 6 {
            return Err(format!("///RCONF {}: expected at least six numbers l,m,n,o,p,q (flip, arm, front, R, T and S axes)", text.trim()));
        }
        let mut out = [0u8; 6];
        for (k, w) in words.iter().enumerate() {
            match (k < 6, w.parse::<u8>()) {
                (true, Ok(v @ (0 | 1))) => out[k] = v,
                (false, Ok(_)) => {}
                _ => {
                    return Err(format!(
                        "///RCONF {}: number {} is '{w}', expected {}",
                        text.trim(),
                        k + 1,
                        if k < 6 { "0 or 1" } else { "a whole number" }
                    ))
                }
            }
        }
        Ok(Rconf(out))
    }
}

/// Whether an axis at `q` deg is "at or beyond 180 deg" (module docs).
fn beyond_half_turn(q: f64) -> u8 {
    u8::from(!(q > -180.0 && q <= 180.0))
}

impl ConfigurationData for Rconf {
    /// Written whole, on its own line.
    type Part = ();
    const NAME: &'static str = "RCONF";
    fn of(arm: &Configuration) -> Self {
        let q = arm.q_deg;
        Rconf([
            u8::from(arm.wrist_negative()),
            u8::from(arm.elbow_down()),
            u8::from(arm.behind()),
            beyond_half_turn(q[3]),
            beyond_half_turn(q[5]),
            beyond_half_turn(q[0]),
        ])
    }
    fn branch(&self) -> Branch {
        let [flip, arm, rear, ..] = self.0;
        (rear == 1, arm == 1, flip == 1)
    }
    fn text(&self) -> String {
        let [l, m, n, o, p, q] = self.0;
        format!("RCONF {l},{m},{n},{o},{p},{q}")
    }
    fn part(&self, _part: ()) -> String {
        ConfigurationData::text(self)
    }
}
