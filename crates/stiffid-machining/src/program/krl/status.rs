//! KUKA's configuration data of a Cartesian target, status `S` and turn `T` (KUKA System
//! Software 8 operating and programming instructions for system integrators, "Status" and
//! "Turn"), from the posture ([`stiffid_core::robot::configuration`]):
//! - `S`: bit 0 set behind axis 1 (overhead area: the wrist centre's x in the A1 coordinate
//!   system negative), bit 1 set when `A3 >= phi` (the elbow in front, the usual posture), bit 2
//!   set when `A5 <= 0`;
//! - `T`: bit `k` set when axis `k+1` is negative.

use crate::program::cartesian::flags::{Branch, ConfigurationData};
use stiffid_core::robot::configuration::Configuration;

/// Status (its three low bits) and turn (six bits) (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StatusTurn {
    /// `S`.
    pub status: u8,
    /// `T`.
    pub turn: u8,
}

/// Where a part of `S` and `T` sits in a program and how it is written back.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StatusPart {
    /// The status, as a binary string `'B..'` or a decimal number.
    Status {
        /// Written as a binary string.
        binary: bool,
    },
    /// The turn, likewise.
    Turn {
        /// Written as a binary string.
        binary: bool,
    },
}

impl ConfigurationData for StatusTurn {
    type Part = StatusPart;
    const NAME: &'static str = "S and T";
    fn of(arm: &Configuration) -> Self {
        let status = u8::from(arm.behind())
            | u8::from(!arm.elbow_down()) << 1
            | u8::from(arm.q_deg[4] <= 0.0) << 2;
        let turn = (0..6).fold(0u8, |t, k| t | u8::from(arm.q_deg[k] < 0.0) << k);
        StatusTurn { status, turn }
    }
    fn branch(&self) -> Branch {
        let s = self.status;
        (s & 1 != 0, s & 2 == 0, s & 4 != 0)
    }
    fn text(&self) -> String {
        format!("S 'B{:03b}' T 'B{:06b}'", self.status, self.turn)
    }
    fn part(&self, part: StatusPart) -> String {
        match part {
            StatusPart::Status { binary: true } => format!("'B{:03b}'", self.status),
            StatusPart::Turn { binary: true } => format!("'B{:06b}'", self.turn),
            StatusPart::Status { .. } => self.status.to_string(),
            StatusPart::Turn { .. } => self.turn.to_string(),
        }
    }
}
