//! The check of a calibrated robot on another day (`calibrate --update`): each check reading's
//! error with the calibrated robot as it is (the tracker registered on the check readings, the
//! setup's measuring points) against the calibration's held-out error bound, and the verdict
//! whether the robot drifted beyond it.
//!
//! The bound is the split conformal quantile at the level of the calibration's held-out error
//! lengths (the calibrated robot file's `[held_out]`, [`stiffid_core::robot::HeldOut::quantile`]): a
//! reading of the undrifted robot lies beyond it with probability at most `1 - level`. The count
//! of the `n` check readings beyond it is then at most binomial `(n, 1 - level)`, and the robot
//! drifted when the count reaches the smallest `k` with `P(X >= k) <= `[`SIGNIFICANCE`] (a
//! one-sided binomial test: a false alarm in at most 1 % of checks of an undrifted robot).
//!
//! The bound is never below what the tracker's noise alone makes of a reading's error length:
//! `sigma sqrt(q_3(level))`, `sigma` the setup's noise per coordinate and `q_3` the chi-square
//! quantile with three degrees of freedom (2.80 `sigma` at 95 %). A calibration fitted to readings
//! far more precise than the check's (simulated, noise-free) would otherwise call a robot drifted
//! by nanometres.

use crate::app::document::{mm, units};
use serde::Serialize;
use stiffid_core::common::error::JobOption;
use stiffid_core::common::warning::{Warning, WarningKind};
use stiffid_core::{Error, Result, Robot};
use stiffid_metrology::calibration::drift::{allowed, noise_length};
use stiffid_metrology::calibration::validation::Validation;

/// The false-alarm rate of the drift verdict on an undrifted robot.
pub const SIGNIFICANCE: f64 = 0.01;

/// The check of a calibrated robot (module docs), as the calibration's document writes it
/// ([`super::document::Document::check`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[cfg_attr(
    feature = "schema",
    schemars(
        rename = "CheckDocument",
        description = "The check in the calibration's document."
    )
)]
pub struct Check {
    /// The level of the bound (`--level`, default 0.95).
    pub level: f64,
    /// Where the calibration's held-out errors come from (`[held_out] source`): `validate` or
    /// `cross-validate`.
    pub source: String,
    /// The count of the calibration's held-out errors.
    pub held_out: usize,
    /// The bound on a reading's error length, the calibration's held-out errors' conformal quantile
    /// at `level`: m, written in mm.
    #[serde(rename = "bound_mm", serialize_with = "units::mm")]
    pub bound: f64,
    /// The check readings' count.
    pub readings: usize,
    /// The check readings whose error with the calibrated robot (before the update) lies beyond
    /// the bound.
    pub outside: usize,
    /// `outside` over `readings`.
    pub share_outside: f64,
    /// The most readings outside an undrifted robot explains (one-sided binomial test at 1 %).
    pub allowed: usize,
    /// Whether the robot drifted beyond its intervals: `outside` above `allowed`.
    pub drifted: bool,
    /// Each check reading: its posture, point, error length with the calibrated robot and whether
    /// it lies beyond the bound.
    pub errors: Vec<CheckedReading>,
}

/// One check reading.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct CheckedReading {
    /// The posture's label.
    pub posture: String,
    /// The measuring point (1-based), or the table reflector's number (`point_name`).
    pub point: usize,
    /// The point as the readings name it: `1`, `2`, ... a measuring point of the tool (`point`),
    /// `T1`, `T2`, ... a reflector on the positioner's table (numbered apart from the tool's).
    pub point_name: String,
    /// The error's length with the calibrated robot: m, written in mm.
    #[serde(rename = "error_mm", serialize_with = "units::mm")]
    pub error: f64,
    /// Beyond the bound.
    pub outside: bool,
}

/// The check of `errors` (the check readings' errors with the calibrated `robot`, read with
/// `noise` per coordinate, m; posture labels `labels`) at `level`; `None` when the robot carries
/// no held-out errors or too few for the level (the bound infinite).
pub(crate) fn check(
    robot: &Robot,
    (errors, labels): (&Validation, &[String]),
    level: f64,
    noise: f64,
) -> Option<Check> {
    let held = robot.held_out()?;
    let bound = held.quantile(level);
    if !bound.is_finite() {
        return None;
    }
    let bound = bound.max(noise_length(noise, level));
    let errors: Vec<CheckedReading> = (errors.errors.iter())
        .map(|e| CheckedReading {
            posture: labels.get(e.posture).cloned().unwrap_or_default(),
            point: e.point + 1,
            point_name: stiffid_core::io::readings::point_name(e.point, e.table),
            error: e.error.norm(),
            outside: e.error.norm() > bound,
        })
        .collect();
    let readings = errors.len();
    let outside = errors.iter().filter(|e| e.outside).count();
    let allowed = allowed(readings, 1.0 - level, SIGNIFICANCE);
    Some(Check {
        level,
        source: held.source.clone(),
        held_out: held.errors.len(),
        bound,
        readings,
        outside,
        share_outside: outside as f64 / readings.max(1) as f64,
        allowed,
        drifted: outside > allowed,
        errors,
    })
}

/// [`check`], or a warning ([`WarningKind::LeftOut`]) in `warnings` saying why there is none.
pub(crate) fn checked(
    robot: &Robot,
    errors: (&Validation, &[String]),
    (level, noise): (f64, f64),
    warnings: &mut Vec<Warning>,
) -> Option<Check> {
    let check = check(robot, errors, level, noise);
    if check.is_none() {
        warnings.push(Warning::new(
            WarningKind::LeftOut,
            "no check of the readings against the calibration's intervals: the robot file carries no [held_out] errors (calibrate with --validate or --cross-validate, Python validate= or cross_validate=True), or too few for the level",
        ));
    }
    check
}

impl Check {
    /// The check as a gate: a robot that drifted beyond its intervals fails it. The update's
    /// outputs stand (the command writes them, then exits with code 1).
    ///
    /// # Errors
    /// [`Error::Gate`] ([`JobOption::Update`]) when [`Check::drifted`].
    pub fn gate(&self) -> Result<()> {
        match self.drifted {
            false => Ok(()),
            true => Err(Error::Gate {
                option: JobOption::Update,
                message: format!(
                    "the robot drifted beyond its intervals: {} of {} check readings beyond {:.4} mm, an undrifted robot explains up to {}",
                    self.outside, self.readings, mm(self.bound), self.allowed
                ),
            }),
        }
    }
}
