//! What a group of postures is designed for (`select` and `evaluate` `--for`): the stiffness
//! identification, the robot's calibration, or both; and the calibration design of a setup that
//! the last two score groups with ([`crate::design::observability`]).

use super::calibrate;
use crate::design::observability::{CalibrationCriterion, CalibrationDesign};
use crate::design::{random_group, CalibrationGoal, Criterion, Goal};
use crate::metrology::calibration::error_model::MeasuredIn;
use crate::metrology::calibration::gravity::Gravity;
use crate::metrology::calibration::Geometry;
use crate::{Error, Result, Setup};

/// What a group is designed for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Purpose {
    /// The stiffness identification (the design criteria of [`crate::design::criteria`]).
    #[default]
    Stiffness,
    /// The geometric and elastostatic calibration (the criteria of
    /// [`crate::design::observability`]).
    Calibration,
    /// Both: the weighted sum of the two log-criteria ([`Goal`]).
    Both,
}

impl crate::common::choice::Choice for Purpose {
    const FIELD: &'static str = "for";
    const ALL: &'static [Self] = &[Purpose::Stiffness, Purpose::Calibration, Purpose::Both];
    fn name(self) -> &'static str {
        match self {
            Purpose::Stiffness => "stiffness",
            Purpose::Calibration => "calibration",
            Purpose::Both => "both",
        }
    }
    fn help(self) -> &'static str {
        match self {
            Purpose::Stiffness => "The stiffness identification (the default)",
            Purpose::Calibration => "The geometric and elastostatic calibration",
            Purpose::Both => "Both: the weighted sum of the two log-criteria",
        }
    }
}

crate::common::choice::by_name!(Purpose);

/// Reference postures of a calibration design: a seeded Latin-hypercube campaign over the
/// setup's bounds that fixes the kept parameters and the gravity terms' scaling.
pub const REFERENCE_POSTURES: usize = 60;

/// The seed of the reference postures (fixed, so that `select` and `evaluate` score a group on
/// the same design whatever the search's seed).
pub const REFERENCE_SEED: u64 = 1;

/// The calibration a group is designed for, and how the two designs combine.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CalibrationOptions {
    /// The calibration criterion (default [`CalibrationCriterion::TestPose`]).
    pub criterion: CalibrationCriterion,
    /// The joint errors the calibration fits (default [`Geometry::Full`], as `calibrate`).
    pub geometry: Geometry,
    /// The gravity terms it fits (default [`Gravity::None`], as `calibrate`).
    pub gravity: Gravity,
    /// With [`Purpose::Both`], the weight `w` of the calibration's log-criterion, in `(0, 1)`
    /// (default 0.5: each design's relative improvement counts the same).
    pub weight: f64,
}

impl Default for CalibrationOptions {
    fn default() -> Self {
        Self {
            criterion: CalibrationCriterion::default(),
            geometry: Geometry::Full,
            gravity: Gravity::None,
            weight: 0.5,
        }
    }
}

/// The calibration design of `setup`: the error model `calibrate` fits (readings in the tracker
/// frame, the setup's measuring points, `options`' geometry and gravity), the characteristic
/// length (1 m without one, as `calibrate`), [`REFERENCE_POSTURES`] reference postures
/// ([`random_group`] of [`REFERENCE_SEED`], within the bounds and the cell), the setup's test postures (the
/// machining region; the reference postures without them) and the setup's noise per coordinate.
///
/// # Errors
/// [`Error::InvalidField`] (`weight`) outside `(0, 1)`; those of [`calibrate::model`] and
/// [`CalibrationDesign::new`].
pub fn design(setup: &Setup, options: &CalibrationOptions) -> Result<CalibrationDesign> {
    if !(options.weight > 0.0 && options.weight < 1.0) {
        return Err(Error::InvalidField {
            field: "weight".into(),
            message: format!("expected a number between 0 and 1, got {}", options.weight),
        });
    }
    let model = calibrate::model(
        setup,
        MeasuredIn::Tracker,
        options.geometry,
        options.gravity,
    )?;
    let reference = random_group(setup, REFERENCE_POSTURES, REFERENCE_SEED);
    let test = match setup.test_postures() {
        [] => reference.as_slice(),
        t => t,
    };
    CalibrationDesign::new(
        model,
        setup.characteristic_length().unwrap_or(1.0),
        &reference,
        test,
        setup.noise().reading_sd(),
    )
}

/// The search goal of `purpose` with the stiffness criterion `criterion` and the calibration
/// design `design` (required unless [`Purpose::Stiffness`]).
pub fn goal<'a>(
    purpose: Purpose,
    criterion: Criterion,
    design: Option<&'a CalibrationDesign>,
    options: &CalibrationOptions,
) -> Goal<'a> {
    let calibration = match purpose {
        Purpose::Stiffness => None,
        Purpose::Calibration => Some(1.0),
        Purpose::Both => Some(options.weight),
    }
    .and_then(|weight| {
        design.map(|design| CalibrationGoal {
            design,
            criterion: options.criterion,
            weight,
        })
    });
    Goal {
        stiffness: criterion,
        calibration,
    }
}
