//! What a group of postures is designed for (`select` and `evaluate` `--for`): the stiffness
//! identification, the robot's calibration, both, or the check of a calibrated robot; and the
//! calibration design of a setup that the last three score groups with
//! ([`stiffid_design::observability`]).

use stiffid_core::common::error::JobOption;
use stiffid_core::robot::external::AxisKind;
use stiffid_core::{Error, Result, Setup};
use stiffid_design::observability::{CalibrationCriterion, CalibrationDesign, Placed, TableDesign};
use stiffid_design::{random_group, CalibrationGoal, Criterion, Goal};
use stiffid_metrology::calibration::error_model::MeasuredIn;
use stiffid_metrology::calibration::gravity::Gravity;
use stiffid_metrology::calibration::{self, Geometry};

/// What a group is designed for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Purpose {
    /// The stiffness identification (the design criteria of [`stiffid_design::criteria`]).
    #[default]
    Stiffness,
    /// The geometric and elastostatic calibration (the criteria of
    /// [`stiffid_design::observability`]).
    Calibration,
    /// Both: the weighted sum of the two log-criteria ([`Goal`]).
    Both,
    /// The check of a calibrated robot (`calibrate --update`): the calibration design of what
    /// drifts between sessions, the joint offsets, the frame and the measuring points
    /// (`CalibrationOptions::of`), D-optimal by default, 10 postures by default.
    Check,
}

impl Purpose {
    /// Whether the group is designed for a calibration alone (no stiffness criterion).
    pub fn calibration_only(self) -> bool {
        matches!(self, Purpose::Calibration | Purpose::Check)
    }

    /// The size of a searched group when none is given: 10 for a check, 6 otherwise.
    pub fn default_postures(self) -> usize {
        match self {
            Purpose::Check => CHECK_POSTURES,
            _ => 6,
        }
    }
}

/// The default size of a check campaign (`select --for check`; within the search's 2 to 100
/// postures).
pub(crate) const CHECK_POSTURES: usize = 10;

impl stiffid_core::common::choice::Choice for Purpose {
    const FIELD: &'static str = "for";
    const ALL: &'static [Self] = &[
        Purpose::Stiffness,
        Purpose::Calibration,
        Purpose::Both,
        Purpose::Check,
    ];
    fn name(self) -> &'static str {
        match self {
            Purpose::Stiffness => "stiffness",
            Purpose::Calibration => "calibration",
            Purpose::Both => "both",
            Purpose::Check => "check",
        }
    }
    fn help(self) -> &'static str {
        match self {
            Purpose::Stiffness => "The stiffness identification (the default)",
            Purpose::Calibration => "The geometric and elastostatic calibration",
            Purpose::Both => "Both: the weighted sum of the two log-criteria",
            Purpose::Check => {
                "The check of a calibrated robot: its joint offsets, tracker and tool (calibrate --update)"
            }
        }
    }
}

stiffid_core::common::choice::by_name!(Purpose);

/// Reference postures of a calibration design: a seeded Latin-hypercube campaign over the
/// setup's bounds that fixes the kept parameters and the gravity terms' scaling.
pub(crate) const REFERENCE_POSTURES: usize = 60;

/// The seed of the reference postures (fixed, so that `select` and `evaluate` score a group on
/// the same design whatever the search's seed).
pub(crate) const REFERENCE_SEED: u64 = 1;

/// The calibration a group is designed for, and how the two designs combine.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CalibrationOptions {
    /// The calibration criterion; `None` for the default ([`CalibrationOptions::criterion`]).
    pub criterion: Option<CalibrationCriterion>,
    /// The joint errors the calibration fits; `None` for the default.
    pub geometry: Option<Geometry>,
    /// The gravity terms it fits; `None` for the default.
    pub gravity: Option<Gravity>,
    /// With [`Purpose::Both`] only, the weight `w` of the calibration's log-criterion, in
    /// `(0, 1)`; `None` for the default.
    pub weight: Option<f64>,
}

impl CalibrationOptions {
    /// The calibration criterion (default [`CalibrationCriterion::TestPose`]).
    pub fn criterion(&self) -> CalibrationCriterion {
        self.criterion.unwrap_or_default()
    }

    /// The joint errors the calibration fits (default [`Geometry::Full`], as `calibrate`).
    pub(crate) fn geometry(&self) -> Geometry {
        self.geometry.unwrap_or(Geometry::Full)
    }

    /// The gravity terms it fits (default [`Gravity::None`], as `calibrate`).
    pub(crate) fn gravity(&self) -> Gravity {
        self.gravity.unwrap_or(Gravity::None)
    }

    /// The weight of the calibration's log-criterion with [`Purpose::Both`] (default 0.5: each
    /// design's relative improvement counts the same).
    pub(crate) fn weight(&self) -> f64 {
        self.weight.unwrap_or(0.5)
    }

    /// The options of a design for `purpose`: for [`Purpose::Check`] the update's model (the
    /// joint offsets, no gravity terms) and, unless given, the D-optimal criterion (the
    /// determinant of the information of the offsets, the frame and the points); the options
    /// as given otherwise.
    pub(crate) fn of(self, purpose: Purpose) -> Self {
        match purpose {
            Purpose::Check => CalibrationOptions {
                criterion: Some(self.criterion.unwrap_or(CalibrationCriterion::DOptimality)),
                geometry: Some(Geometry::Offsets),
                gravity: Some(Gravity::None),
                ..self
            },
            _ => self,
        }
    }
}

/// Refuses calibration options that mean nothing for `purpose`: any of them for
/// [`Purpose::Stiffness`], the geometry and the gravity for [`Purpose::Check`] (fixed), the weight
/// unless [`Purpose::Both`]; and a weight outside `(0, 1)`.
///
/// # Errors
/// [`Error::InvalidOption`] naming the option ([`JobOption::CalibrationCriterion`],
/// [`JobOption::Geometry`], [`JobOption::Gravity`], [`JobOption::Weight`]).
pub fn check(purpose: Purpose, options: &CalibrationOptions) -> Result<()> {
    let refuse = |option: JobOption, message: &str| {
        Err(Error::InvalidOption {
            option,
            message: message.into(),
        })
    };
    if purpose == Purpose::Stiffness {
        let given = [
            (options.criterion.is_some(), JobOption::CalibrationCriterion),
            (options.geometry.is_some(), JobOption::Geometry),
            (options.gravity.is_some(), JobOption::Gravity),
        ];
        if let Some((_, option)) = given.into_iter().find(|(given, _)| *given) {
            return refuse(
                option,
                "a calibration option: only with for = calibration or both (the group is designed for the stiffness identification)",
            );
        }
    }
    if purpose == Purpose::Check {
        let given = [
            (options.geometry.is_some(), JobOption::Geometry),
            (options.gravity.is_some(), JobOption::Gravity),
        ];
        if let Some((_, option)) = given.into_iter().find(|(given, _)| *given) {
            return refuse(
                option,
                "not with for = check: a check campaign is designed for what calibrate --update refits (the joint offsets, the tracker and the tool)",
            );
        }
    }
    match options.weight {
        Some(_) if purpose != Purpose::Both => refuse(
            JobOption::Weight,
            "only with for = both: it weighs the calibration's criterion against the stiffness criterion",
        ),
        Some(w) if !(w > 0.0 && w < 1.0) => refuse(
            JobOption::Weight,
            &format!("expected a number between 0 and 1, got {}", stiffid_core::common::words::number(w)),
        ),
        _ => Ok(()),
    }
}

/// The calibration design of `setup`: the error model `calibrate` fits (readings in the tracker
/// frame, the setup's measuring points, `options`' geometry and gravity), the characteristic length
/// (1 m without one, as `calibrate`), 60 reference postures ([`random_group`]
/// of seed 1, within the bounds and the cell), the setup's test postures (the machining region; the
/// reference postures without them) and the setup's noise per coordinate.
///
/// # Errors
/// Those of [`calibration::model`] and [`CalibrationDesign::new`] (the options are checked
/// by [`check`]).
///
/// On a robot with a carrier (a track), the model has the track's parameters too (its direction and
/// its error motions of order 3, [`stiffid_metrology::calibration::ErrorModel::with_external`]; the
/// positioner's lines, which only reflectors on its table read, drop out as not identified), the
/// reference postures are dealt over 6 stations of the travel
/// ([`stiffid_core::robot::ExternalAxes::stations`]) and every test posture is read at each of
/// them. With reflectors on a positioner's table (`[workpiece] reflectors_mm`; reflectors on a
/// fixed part without a positioner change no design), the model has the positioner's lines and
/// offsets and the reflectors' coordinates too, and the table is read at 16 angles ([`table_grid`])
/// for reference, for the part's test points and as the readings a group is scored with until
/// `select` chooses its own ([`CalibrationDesign::new_with_table`]).
pub fn design(setup: &Setup, options: &CalibrationOptions) -> Result<CalibrationDesign> {
    let model = calibration::model(
        setup,
        MeasuredIn::Tracker,
        options.geometry(),
        options.gravity(),
    )?;
    let reference = random_group(setup, REFERENCE_POSTURES, REFERENCE_SEED);
    let test = match setup.test_postures() {
        [] => reference.as_slice(),
        t => t,
    };
    let (length, noise) = (
        setup.characteristic_length().unwrap_or(1.0),
        setup.noise().reading_sd(),
    );
    // Reflectors on a fixed part (no positioner) are fixed points of the cell: their readings
    // locate the part and separate none of the robot's parameters, nothing to design for.
    let reflectors = match setup.robot().external() {
        Some(a) if a.len() > a.carrier_len() => setup.table_reflectors(),
        _ => Vec::new(),
    };
    let Some(axes) =
        (setup.robot().external()).filter(|a| a.carrier_len() > 0 || !reflectors.is_empty())
    else {
        return CalibrationDesign::new(model, length, &reference, test, noise);
    };
    let orders: Vec<usize> = (axes.axes().iter())
        .map(|a| match a.kind {
            AxisKind::Linear => DESIGN_ORDER,
            AxisKind::Rotary => 0,
        })
        .collect();
    let model = model.with_external(&orders, reflectors.len())?;
    let stations = axes.stations(REFERENCE_STATIONS);
    let reference: Vec<Placed> = (reference.iter().enumerate())
        .map(|(i, q)| (*q, stations[i % stations.len()]))
        .collect();
    let test: Vec<Placed> = (stations.iter())
        .flat_map(|e| test.iter().map(move |q| (*q, *e)))
        .collect();
    if reflectors.is_empty() {
        return CalibrationDesign::new_placed(model, length, &reference, &test, noise);
    }
    let table = TableDesign {
        reflectors,
        reference: table_grid(axes, REFERENCE_TABLE_ANGLES, &stations[0]),
    };
    CalibrationDesign::new_with_table(model, length, &reference, &test, noise, &table)
}

/// How many positioner angles (about: a grid of the same count of values per axis) the table's
/// reflectors are read at in a calibration design's reference campaign.
pub(crate) const REFERENCE_TABLE_ANGLES: usize = 16;

pub use stiffid_design::selection::table::table_grid;

/// The order of a track's error motions a calibration design assumes (`calibrate` chooses its
/// own from the readings, `--error-motions`): a bow and a twist along the rail are of order 2
/// and 3.
pub(crate) const DESIGN_ORDER: usize = 3;

/// The stations of a track's travel the reference and test postures of a calibration design
/// are read at.
pub(crate) const REFERENCE_STATIONS: usize = 6;

/// The search goal of `purpose` with the stiffness criterion `criterion` and the calibration
/// design `design` (required unless [`Purpose::Stiffness`]).
pub(crate) fn goal<'a>(
    purpose: Purpose,
    criterion: Criterion,
    design: Option<&'a CalibrationDesign>,
    options: &CalibrationOptions,
) -> Goal<'a> {
    let calibration = match purpose {
        Purpose::Stiffness => None,
        Purpose::Calibration | Purpose::Check => Some(1.0),
        Purpose::Both => Some(options.weight()),
    }
    .and_then(|weight| {
        design.map(|design| CalibrationGoal {
            design,
            criterion: options.criterion(),
            weight,
        })
    });
    Goal {
        stiffness: criterion,
        calibration,
    }
}
