//! Geometric and elastostatic calibration of the robot from one tracker campaign.
//!
//! The unloaded position of a measuring point differs from the nominal model's by the robot's
//! geometric errors (link lengths, twists, joint offsets, base and tool) and by its deflection
//! under its own weight. This module models both as one parameter vector and fits it to the
//! tracker's readings:
//!
//! - [`error_model`]: the parameters ([`Parameter`]: name, kind, unit, nominal) of a complete
//!   error model of every chain stiffid reads (DH, modified DH, URDF, with its axis map), the
//!   predicted reflector positions and their identification Jacobian (analytic, from the joint
//!   screws), with the column scaling; [`model`]: the error model of a setup, as `calibrate` fits it.
//! - [`identifiability`]: which parameters the readings determine, by QR with column pivoting on
//!   the column-scaled Jacobian: the rank, the condition number, the parameters merged and into
//!   which, the correlations above 0.9.
//! - [`gravity`]: the joint deflection under the robot's own weight, with known masses (the
//!   compliances unknown) or lumped (compliance times mass moment).
//! - [`motions`]: the orders of a carrier's error motions, chosen by cross-validation.
//! - [`fit`]: Levenberg-Marquardt over the identifiable parameters, standard deviations, the
//!   noise-ratio model check.
//! - `spread`: the uncertainty of the predictions over the robot's joint limits, from the fit's
//!   covariance.
//! - [`validation`]: the held-out position error of readings not fitted.
//! - [`intervals`]: prediction intervals of the position error from the held-out errors of
//!   leave-one-posture-out (jackknife+), and their coverage.
//! - [`robot_file`]: the calibrated robot, as a robot TOML file and as a URDF.
//!
//! Equations and sources: docs/model.md, section "Calibration".

mod acceptance;
#[cfg(test)]
mod acceptance_tests;
pub mod drift;
#[cfg(test)]
mod drift_tests;
pub mod error_model;
pub mod fit;
pub mod gravity;
pub mod identifiability;
pub mod intervals;
pub mod judgement;
pub mod maps;
pub mod motions;
mod reflections;
pub mod robot_file;
pub(crate) mod spread;
pub mod track_notes;
pub mod validation;

pub use error_model::{
    AxisPart, Component, ErrorModel, Estimate, Geometry, Kind, Parameter, Target,
};

use error_model::MeasuredIn;
use stiffid_core::{Result, Setup};

/// The error model of `setup` for readings in `measured_in`; with [`gravity::Gravity::Masses`] the
/// setup's tool (`[tool] mass_kg`, `centre_of_mass_mm`) joins link 6 ([`gravity::with_tool`]).
///
/// # Errors
/// [`stiffid_core::Error::InvalidField`] (`gravity`) for [`gravity::Gravity::Masses`] with a robot without masses; those
/// of [`ErrorModel::new`] and [`gravity::Terms::of`].
pub fn model(
    setup: &Setup,
    measured_in: MeasuredIn,
    geometry: Geometry,
    gravity: gravity::Gravity,
) -> Result<ErrorModel> {
    let robot = setup.robot();
    let nominal = setup.nominal_compliance().unwrap_or_default();
    let weighed = gravity::with_tool(robot, setup.payload().map(|p| p.body()));
    let g = gravity::Terms::of(&weighed, gravity, setup.springs(), nominal)?;
    ErrorModel::new(
        robot,
        &setup.tool().measuring_points,
        measured_in,
        geometry,
        g,
    )
}

#[cfg(test)]
mod reflections_tests;
#[cfg(test)]
mod spread_tests;
