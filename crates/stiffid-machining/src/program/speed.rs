//! A robot program's programmed speeds: how the controller moves to each target at 100 %
//! override, as the program states it.
//!
//! - A joint motion (KRL `PTP`, `SPTP`; RAPID `MoveJ`, `MoveAbsJ`; LS `J`; INFORM `MOVJ`) moves
//!   the axes at a share of their own largest speeds, which the controller plans: it has no TCP
//!   speed ([`Speed::Joint`]); the arm may change configuration along it.
//! - A linear motion (KRL `LIN`, `SLIN`; RAPID `MoveL`; LS `L`; INFORM `MOVL`) moves the TCP
//!   along a line at a path speed ([`Speed::Path`]) or in a time ([`Speed::Duration`]):
//!   - KRL: `$VEL.CP = v` (m/s) or `BAS(#CP_PARAMS, v)` (the inline forms' `Vel= v m/s`) on a
//!     line before the motion, in force until the next; `WITH $VEL.CP = v` or
//!     `WITH $VEL = SVEL_CP(v, ..)` on the motion, for it alone;
//!   - RAPID: the speed argument, a predefined `speeddata` (`v5` to `v7000`, mm/s), one
//!     declared in the module (`CONST speeddata vcut := [25, 500, 5000, 1000];`, its first
//!     member `v_tcp`, mm/s) or a literal `[25, 500, 5000, 1000]`; the switch `\V:=` (mm/s)
//!     replaces it, `\T:=` (s) gives the time;
//!   - LS: `mm/sec`, `cm/min`, `inch/min`, or the time `sec`, `msec`;
//!   - INFORM: `V=` (mm/s).
//!
//!   Any other form (a variable, a register, an orientation speed `deg/sec` or `VR=`, RAPID
//!   `vmax`, KRL `BAS(#INITMOV)` or an expression, no speed set before the first linear motion)
//!   is [`Speed::Unread`]: stiffid does not evaluate it, and says why.
//!
//! Each language's reader sits in its controller's folder (`krl::speed`, `rapid::speed`,
//! `ls::speed`, `inform::speed`); this module holds what they share: the [`Speed`] they give and
//! the limits they check.
//!
//! Overrides (KRL `$OV_PRO`, RAPID `VelSet`, the pendant's) and the controller's own slowing
//! down (corners, acceleration) are not read: a move is taken at its programmed speed, the
//! fastest the program lets it go.

use super::{at, number_at, JointProgram};
use stiffid_core::common::words::number;
use stiffid_core::Result;

/// The largest path speed read, mm/s (10 m/s: beyond every industrial arm's).
pub(crate) const MAX_PATH_SPEED_MM_S: f64 = 10_000.0;

/// The longest duration of one move read, s.
pub(crate) const MAX_DURATION_S: f64 = 3_600.0;

/// How the program moves to a target (module docs).
#[derive(Debug, Clone, PartialEq)]
pub enum Speed {
    /// A joint motion: the axes at a share of their largest speeds, no TCP speed.
    Joint,
    /// A linear motion at this TCP path speed, m/s.
    Path(f64),
    /// A linear motion that takes this time, s (RAPID `\T`, LS `sec`).
    Duration(f64),
    /// A linear motion whose speed the program gives in a form stiffid does not read: why.
    Unread(String),
}

impl JointProgram {
    /// Whether each target is reached by a joint motion ([`Speed::Joint`]), where the arm may
    /// change configuration; one per target.
    pub(crate) fn joint_moves(&self) -> Vec<bool> {
        self.targets
            .iter()
            .map(|t| t.speed == Speed::Joint)
            .collect()
    }
}

/// A path speed of `mm_s` (mm/s) stated on `line` by `what`, checked against its limits.
pub(super) fn path(line: u64, what: &str, mm_s: f64) -> Result<Speed> {
    // A speed given in m/s and converted may have left the numbers (1e308 m/s).
    let speed = match mm_s.is_finite() {
        true => format!("{} mm/s", number(mm_s)),
        false => "more than any number of mm/s".into(),
    };
    match mm_s > 0.0 && mm_s <= MAX_PATH_SPEED_MM_S {
        true => Ok(Speed::Path(mm_s * 1e-3)),
        false => Err(at(
            line,
            format!(
                "{what}: a path speed of {speed}; expected one in (0, {MAX_PATH_SPEED_MM_S}] mm/s"
            ),
        )),
    }
}

/// A move's time of `s` (s) stated on `line` by `what`, checked against its limits.
pub(super) fn duration(line: u64, what: &str, s: f64) -> Result<Speed> {
    match s > 0.0 && s <= MAX_DURATION_S {
        true => Ok(Speed::Duration(s)),
        false => Err(at(
            line,
            format!(
                "{what}: a move of {} s; expected a time in (0, {MAX_DURATION_S}] s",
                number(s)
            ),
        )),
    }
}

/// The number `text` is, whole (blanks around it aside), or `None` (a name, an expression).
pub(super) fn literal(text: &str) -> Option<f64> {
    let (v, span) = number_at(text, 0)?;
    text[span.end..].trim().is_empty().then_some(v)
}
