//! ABB's configuration data of a `robtarget`, `confdata` `[cf1, cf4, cf6, cfx]` (ABB Technical
//! reference manual RAPID Instructions, Functions and Data types, `confdata`), from the posture
//! ([`stiffid_core::robot::configuration`]): the quadrant of axes 1, 4 and 6
//! (`floor(q / 90 deg)`), and `cfx = 4 (behind axis 1) + 2 (wrist centre behind the lower arm)
//! + (axis 5 negative)`.

use crate::program::cartesian::flags::{Branch, ConfigurationData};
use stiffid_core::robot::configuration::Configuration;

/// `confdata` `[cf1, cf4, cf6, cfx]` (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ConfData(pub [i64; 4]);

impl ConfigurationData for ConfData {
    /// The member (0: cf1, 1: cf4, 2: cf6, 3: cfx).
    type Part = usize;
    const NAME: &'static str = "confdata";
    fn of(arm: &Configuration) -> Self {
        let quadrant = |q: f64| (q / 90.0).floor() as i64;
        let cfx = 4 * i64::from(arm.behind())
            + 2 * i64::from(arm.elbow_down())
            + i64::from(arm.wrist_negative());
        ConfData([
            quadrant(arm.q_deg[0]),
            quadrant(arm.q_deg[3]),
            quadrant(arm.q_deg[5]),
            cfx,
        ])
    }
    fn branch(&self) -> Branch {
        let c = self.0[3];
        (c & 4 != 0, c & 2 != 0, c & 1 != 0)
    }
    fn text(&self) -> String {
        let [a, b, c, d] = self.0;
        format!("[{a},{b},{c},{d}]")
    }
    fn part(&self, k: usize) -> String {
        self.0[k].to_string()
    }
}
