//! How a virtual joint deflects under its load: linearly (a spring), by a lost motion, or with a
//! compliance that changes with the load. Every law is linear in its one parameter, so its column
//! of the observation matrix is the spring's column with the load `t = J_s(p_f)^T W` replaced by
//! the law's response `g(t)`: `J_s(p_m)[0:3] g(t)`, and least squares fits it as any spring.
//!
//! - linear: `dq = c t` (the spring; `c` its compliance);
//! - lost motion: `dq = b s(t)`, a deflection of size `b` (rad, or m for a translation) in the
//!   direction of the load, the sign smoothed near zero: `s(t) = t / sqrt(t^2 + t0^2)`, `t0` the
//!   smoothing load (Nm, or N; [`DEFAULT_SMOOTHING`]): `s` is within 1% of `sign(t)` beyond
//!   `|t| = 7 t0` and passes through zero with slope `1 / t0` (backlash and the dead band of a
//!   gearbox, Ruderman and Bertram, "Two-state dynamic friction model with elasto-plasticity",
//!   2013, use the same smoothed sign);
//! - load-dependent compliance: with the drive's compliance `c0`, `dq = (c0 + c1 |t|) t`, so the
//!   parameter `c1` (rad/Nm^2) has the column of `|t| t`; `c1 < 0` is a joint that stiffens with
//!   the load, physical while `c0 + c1 |t| > 0` over the loads measured.
//!
//! Whether the data separate these from the springs is a question of the loads: with one load
//! level per posture, `s(t)` and `|t| t` differ from `t` only through how the load differs from
//! posture to posture, so they also absorb whatever else changes with the posture; with several
//! load levels in one posture (load steps) the load-deflection curve of that posture separates
//! them directly (its intercept is the lost motion, its curvature the load dependence).

/// The smoothing load `t0` of a lost motion, Nm (rotation) or N (translation).
pub const DEFAULT_SMOOTHING: f64 = 10.0;

/// How a virtual joint deflects under its load (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Law {
    /// `dq = c t`: a spring.
    #[default]
    Linear,
    /// `dq = b t / sqrt(t^2 + t0^2)`: a lost motion `b`, `smoothing` the load `t0` (Nm or N).
    LostMotion {
        /// `t0`, Nm (rotation) or N (translation), `> 0`.
        smoothing: f64,
    },
    /// `dq = c1 |t| t`: the load-dependent part of a compliance.
    LoadDependent,
}

impl Law {
    /// The response `g(t)` to the load `t` (Nm or N) whose multiple by the parameter is the
    /// deflection (module docs).
    #[inline(always)]
    pub(crate) fn response(self, t: f64) -> f64 {
        match self {
            Law::Linear => t,
            Law::LostMotion { smoothing } => t / t.hypot(smoothing),
            Law::LoadDependent => t.abs() * t,
        }
    }

    /// Whether it is a spring's.
    pub fn is_linear(self) -> bool {
        self == Law::Linear
    }
}
