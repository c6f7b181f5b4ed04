//! The documented limits of every input (counts and physically meaningful ranges, in the units of
//! the files), the checks that apply them, the one box of axis angles ([`JointBox`]: joint limits
//! and posture bounds), and texts cut short for error messages (numbers: [`crate::common::words`]).
//!
//! Every number read from a robot, URDF or setup file is checked against one of these ranges when
//! the file is parsed, so an accepted file gives finite results: a stiffness of `1e-320` Nm/rad or
//! a link of `1e308` mm is an error naming the field and the value, not a NaN later on.

use crate::common::words::number;
use crate::{Error, Result};

pub(crate) mod joint_box;
pub use joint_box::{JointBox, Violation};

/// A closed interval `[min, max]` of accepted values, in the unit named by `unit`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// Smallest accepted value.
    pub min: f64,
    /// Largest accepted value.
    pub max: f64,
    /// Unit of both ends, as in the file's field names (`mm`, `deg`, `Nm/rad`, ...).
    pub unit: &'static str,
}

impl Range {
    /// The range `[min, max]` in `unit`.
    pub const fn new(min: f64, max: f64, unit: &'static str) -> Self {
        Self { min, max, unit }
    }

    /// Whether `v` is finite and within `[min, max]`.
    pub fn contains(&self, v: f64) -> bool {
        v.is_finite() && v >= self.min && v <= self.max
    }

    /// The problem of a column `name` whose `value` lies outside this range.
    pub fn outside(&self, name: &str, value: f64) -> crate::common::error::ColumnProblem {
        crate::common::error::ColumnProblem::Outside {
            name: name.into(),
            value,
            within: "the accepted range",
            lower: self.min,
            upper: self.max,
        }
    }
}

impl std::fmt::Display for Range {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "[{}, {}]", number(self.min), number(self.max))?;
        match self.unit {
            "" => Ok(()),
            unit => write!(f, " {unit}"),
        }
    }
}

/// Encoder pulses per degree (or per mm) of a controller's axis (`[controller] pulses_per_deg`,
/// `external_pulses`; an INFORM job's `'stiffid:` comments): from 1e-6 to 1e9.
pub(crate) const PULSES: Range = Range::new(1e-6, 1e9, "pulses per deg or mm");

/// An axis's largest speed in a robot, setup or URDF file (`max_speed_deg_s`, `max_speed_mm_s`):
/// above 0, at most 10 000 deg/s or mm/s (`check_speeds`).
pub(crate) const AXIS_SPEED: Range = Range::new(0.0, 1e4, "deg/s or mm/s");

/// Checks every largest speed of `values` (mm/s where `field` ends in `_mm_s`, else deg/s):
/// finite, above 0 and within [`AXIS_SPEED`]; the error names `field`, the value found and its
/// unit.
///
/// # Errors
/// [`Error::InvalidField`] for the first value that is not.
pub(crate) fn check_speeds(field: &str, values: &[f64]) -> Result<()> {
    let unit = match field.ends_with("_mm_s") {
        true => "mm/s",
        false => "deg/s",
    };
    check(
        field,
        values,
        &Range::new(AXIS_SPEED.min, AXIS_SPEED.max, unit),
    )?;
    match values.iter().position(|v| *v <= 0.0) {
        None => Ok(()),
        Some(i) => Err(Error::InvalidField {
            field: match values.len() {
                1 => field.to_string(),
                _ => format!("{field}[{}]", i + 1),
            },
            message: format!(
                "{} is not a speed: expected above 0, at most {} ({})",
                number(values[i]),
                number(AXIS_SPEED.max),
                match values.len() {
                    1 => "leave the field out for no limit",
                    _ => "inf for an axis without a limit, or leave the field out for none",
                }
            ),
        }),
    }
}

/// A capsule radius of a robot file's `[robot_geometry]`: 1 um to 10 m.
pub(crate) const BODY_RADIUS_MM: Range = Range::new(1e-3, 1e4, "mm");

/// Any length or position in a robot or setup file (link lengths, offsets, tool points, anchor):
/// at most 100 m from the origin.
pub const LENGTH_MM: Range = Range::new(-1e5, 1e5, "mm");

/// A direction's components in a robot or setup file (an external axis's `direction`, any
/// length, normalised when read): each within +-1e5, no unit.
pub(crate) const DIRECTION: Range = Range::new(-1e5, 1e5, "");

/// An external axis's value on the command line (`kinematics --external`): mm for a linear axis,
/// deg for a rotary one, before the axis's own travel is checked.
pub const EXTERNAL_VALUE: Range = Range::new(-1e5, 1e5, "mm or deg");

/// A link's mass in a robot file (`mass_kg`): 0 to 100 t.
pub(crate) const MASS_KG: Range = Range::new(0.0, 1e5, "kg");

/// A component of an inertia tensor (a robot file's `inertia_kg_m2`, a URDF's `<inertia>`, a
/// setup's `[tool] inertia_kg_m2`): at most 1e6 kg m^2 in magnitude (100 t at 100 m).
pub(crate) const INERTIA_KG_M2: Range = Range::new(-1e6, 1e6, "kg m^2");

/// [`LENGTH_MM`] in metres (URDF files).
pub(crate) const LENGTH_M: Range = Range::new(-100.0, 100.0, "m");

/// Any angle in a robot or setup file (DH angles, joint limits, bounds, postures, roll-pitch-yaw).
pub const ANGLE_DEG: Range = Range::new(-1e4, 1e4, "deg");

/// [`ANGLE_DEG`] in radians (URDF files).
pub const ANGLE_RAD: Range = Range::new(-175.0, 175.0, "rad");

/// Joint stiffness: from a soft hobby arm (1 Nm/rad) to far beyond the stiffest industrial joint
/// (about 1e7 Nm/rad). Outside it, compliances and deflections leave the range where the
/// identification's numbers mean anything.
pub const STIFFNESS_NM_PER_RAD: Range = Range::new(1.0, 1e10, "Nm/rad");

/// Translational stiffness of a virtual spring (a setup's `[model]`), N/mm.
pub const STIFFNESS_N_PER_MM: Range = Range::new(1e-3, 1e10, "N/mm");

/// Components of a spring's axis (any length; it is normalised), dimensionless.
pub(crate) const AXIS: Range = Range::new(-1e6, 1e6, "");

/// A tool's mass (`[tool] mass_kg`).
pub(crate) const TOOL_MASS_KG: Range = Range::new(1e-3, 1e4, "kg");

/// The relative standard deviation of the robot's and the tool's masses (`[masses] sd_pct`).
pub(crate) const MASS_SD_PERCENT: Range = Range::new(0.0, 100.0, "%");

/// How far each frame of the robot model may be from the true robot's, per coordinate
/// (`[robot_accuracy] frame_sd_mm` and `frame_sd_mrad`).
pub(crate) const FRAME_SD: Range = Range::new(0.0, 100.0, "");

/// The rope load of a setup.
pub(crate) const LOAD_N: Range = Range::new(1e-3, 1e7, "N");

/// Forces and moments on the command line, per component (measurement files: the magnitude limits
/// of 1e6 N and 1e6 Nm).
pub const WRENCH: Range = Range::new(-1e7, 1e7, "N or Nm");

/// The standard deviation of one coordinate of one tracker reading (`[noise] reading_sd_mm`).
pub(crate) const READING_SD_MM: Range = Range::new(1e-6, 1e2, "mm");

/// A calibration prior's nominal tolerance of the joints' length errors (`--tolerance-mm`).
pub const TOLERANCE_MM: Range = Range::new(1e-6, 1e3, "mm");

/// The bound on a calibration's gravity terms: the joint deflection each is held to at the
/// largest torque it meets (`--gravity-bound-mrad`).
pub const GRAVITY_BOUND_MRAD: Range = Range::new(1e-4, 100.0, "mrad");

/// A calibration prior's nominal tolerance of the joints' angle errors (`--tolerance-deg`).
pub const TOLERANCE_DEG: Range = Range::new(1e-6, 90.0, "deg");

/// The accepted margin a design keeps to every constraint of the cell (`[tracker]
/// registration_uncertainty_mm`, `select --margin-mm`): 0 to 1 m.
pub const MARGIN_MM: Range = Range::new(0.0, 1e3, "mm");

/// The old `[noise] variance_mm2`, the variance of one displacement coordinate.
pub(crate) const VARIANCE_MM2: Range = Range::new(1e-12, 1e4, "mm^2");

/// A noise level, as a multiple of the variance.
pub(crate) const LEVEL_MULTIPLE: Range = Range::new(1e-6, 1e6, "");

/// The characteristic length `L` of the dexterity index (Eq. 20).
pub const CHARACTERISTIC_LENGTH_MM: Range = Range::new(1.0, 1e5, "mm");

/// The predicted mean deviation rate a group is chosen to reach (`select --target-pct`, a
/// plan's `target_pct`), %.
pub const TARGET_PCT: Range = Range::new(1e-6, 1e4, "%");

/// An entry of a robot's axis map matrix.
pub(crate) const AXIS_MAP_ENTRY: Range = Range::new(-1e3, 1e3, "");

/// The largest 2-norm condition number of an axis map matrix: beyond it the map between axis and
/// kinematic angles loses more than half the digits.
pub(crate) const MAX_AXIS_MAP_COND: f64 = 1e8;

/// Largest input file accepted, bytes (256 MiB): room for a measurement file of 2 million rows
/// (1e6 rows take about 119 MB), and a bound on the memory one file (or `/dev/zero`) can take.
/// Both front ends read at most one byte more and hand the bytes to `crate::io::text`.
pub(crate) const MAX_INPUT_BYTES: u64 = 256 << 20;

/// Most noise levels of a setup (with [`MAX_RUNS`], a bound on a simulation's memory: levels x
/// runs results of one group at a time).
pub(crate) const MAX_LEVELS: usize = 20;

/// Most Monte Carlo runs per group and noise level (`--runs`).
pub const MAX_RUNS: u64 = 100_000;

/// Most identifications of one simulation, groups x noise levels x runs (each about 0.7 us of CPU
/// for six postures: 1e8 take about 40 s on two cores).
pub const MAX_SIMULATED_RUNS: u64 = 100_000_000;

/// Most resamples of the model comparison's bootstrap (`--bootstrap`): each redoes the whole
/// forward selection (about 25 ms of CPU on the FANUC data set: 2000 take about 25 s on two
/// cores).
pub const MAX_BOOTSTRAP: u64 = 2000;

/// Most local searches of a global search (`--starts`).
pub const MAX_STARTS: u64 = 10_000;

/// Most start groups of the start-group check of `stiffid reproduce` (`--trials`): two local
/// searches each (about 20 ms of CPU: 2000 take about 20 s on two cores).
pub const MAX_TRIALS: u64 = 2000;

/// Most postures a search chooses (`select --count`): 6 variables each, and SQP's memory grows with
/// their square.
pub const MAX_SEARCH_POSTURES: u64 = 100;

/// Most criterion evaluations of one local search (`--max-evals`).
pub const MAX_EVALS: u64 = 10_000_000;

/// The stopping tolerance of a local search on the change of `ln(criterion)` per SQP step
/// (`stiffid_design::SearchOptions::ftol`): 0 (stop on the budget or the step alone) to 1 (a
/// change of the criterion by a factor of e).
pub const FTOL: Range = Range::new(0.0, 1.0, "");

/// The stopping tolerance of a local search on the step of every angle
/// (`stiffid_design::SearchOptions::xtol`): 0 (stop on the budget or `ftol` alone) to 1 rad.
pub const XTOL_RAD: Range = Range::new(0.0, 1.0, "rad");

/// The forward finite-difference step of a local search
/// (`stiffid_design::SearchOptions::fd_step`): from 1e-12 rad (about 1e4 ulps of an angle of
/// order 1; below it rounding is the whole difference) to 0.01 rad (0.6 deg; beyond it the
/// difference no longer approximates the derivative).
pub const FD_STEP_RAD: Range = Range::new(1e-12, 1e-2, "rad");

/// Most exchange runs of a choice from a pool (`--restarts`, `stiffid_design::PoolOptions`),
/// and of the registration postures: each about 1.3 s of CPU for 60 postures of a pool of 10 000,
/// so 50 take about half a minute on two cores.
pub const MAX_POOL_RESTARTS: u64 = 50;

/// Most groups a choice from a pool enumerates
/// (`stiffid_design::PoolOptions::enumeration_limit`; about a minute of evaluations).
pub const MAX_ENUMERATION: u64 = 100_000_000;

/// The tolerances of inverse kinematics ([`crate::robot::ik::Options`]): of the position, m, and of the
/// rotation, rad; from 1e-15 (the rounding of a pose near 1 m) to 0.01.
pub const IK_TOLERANCE: Range = Range::new(1e-15, 1e-2, "m or rad");

/// Most steps per start of inverse kinematics ([`crate::robot::ik::Options::max_iterations`]).
pub const MAX_IK_ITERATIONS: u64 = 100_000;

/// Most seeded restarts of inverse kinematics ([`crate::robot::ik::Options::restarts`]).
pub const MAX_IK_RESTARTS: u64 = 10_000;

/// Most postures in one postures file.
pub const MAX_GROUP_POSTURES: usize = 10_000;

/// Most postures files of one `stiffid simulate`.
pub const MAX_GROUPS: usize = 100;

/// Most measuring points of a setup.
pub(crate) const MAX_MEASURING_POINTS: usize = 100;

/// Most reflectors on a positioner's table: a setup's `[workpiece] reflectors_mm`, a readings
/// file's `T1` ...
pub(crate) const MAX_TABLE_REFLECTORS: usize = 100;

/// Most parameters of a model in a stiffness file: the six drives and
/// [`MAX_VIRTUAL_SPRINGS`] virtual springs.
pub(crate) const MAX_PARAMETERS: usize = 6 + MAX_VIRTUAL_SPRINGS;

/// Most virtual springs a model may have.
pub const MAX_VIRTUAL_SPRINGS: usize = 64;

/// Most test postures of a setup.
pub(crate) const MAX_TEST_POSTURES: usize = 10_000;

/// Deepest element nesting accepted in a URDF file (real ones nest about 5 deep); checked before
/// the XML parser sees the text.
pub(crate) const MAX_XML_DEPTH: usize = 64;

/// Longest text of a value quoted in an error message, in characters; longer ones are cut with
/// an ellipsis.
pub(crate) const MAX_QUOTED_CHARS: usize = 60;

/// `text` cut to `MAX_QUOTED_CHARS` characters with an ellipsis, for error messages.
pub fn short(text: &str) -> String {
    cut(text, MAX_QUOTED_CHARS)
}

/// Longest error message, in characters (after [`one_line`]).
pub(crate) const MAX_MESSAGE_CHARS: usize = 600;

/// A (parser's) multi-line message on one line for people: blank and `|` lines dropped, every word
/// longer than `MAX_QUOTED_CHARS` cut ([`short`]), the whole at most `MAX_MESSAGE_CHARS`, so a
/// 5 MB field never becomes a 5 MB message.
pub fn one_line(message: &str) -> String {
    one_line_within(message, MAX_QUOTED_CHARS, MAX_MESSAGE_CHARS)
}

/// [`one_line`] with other limits: words of at most `word` characters, at most `total` in all.
pub fn one_line_within(message: &str, word: usize, total: usize) -> String {
    let words: Vec<String> = message
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && *l != "|")
        .flat_map(str::split_whitespace)
        .map(|w| cut(w, word))
        .collect();
    cut(&words.join(" "), total)
}

/// `text` cut to `n` characters with an ellipsis.
fn cut(text: &str, n: usize) -> String {
    match text.char_indices().nth(n) {
        None => text.to_string(),
        Some((end, _)) => format!("{}...", &text[..end]),
    }
}

/// Checks every value of `values` against `range`; the error names `field` (with the 1-based
/// index when there are several values) and the value found.
///
/// # Errors
/// [`Error::InvalidField`] for the first value that is not finite or outside `range`.
pub fn check(field: &str, values: &[f64], range: &Range) -> Result<()> {
    let Some(i) = values.iter().position(|v| !range.contains(*v)) else {
        return Ok(());
    };
    let field = match values.len() {
        1 => field.to_string(),
        _ => format!("{field}[{}]", i + 1),
    };
    Err(Error::InvalidField {
        field,
        message: format!("{} is outside {range}", number(values[i])),
    })
}

/// [`check`] with the field named inside the file `source_name` (`"robot.toml: joint[2].a_mm"`).
///
/// # Errors
/// As [`check`].
pub(crate) fn check_in(
    source_name: &str,
    field: &str,
    values: &[f64],
    range: &Range,
) -> Result<()> {
    check(&format!("{source_name}: {field}"), values, range)
}

/// Checks that `count` items of `what` are at least `min` and at most `max`.
///
/// # Errors
/// [`Error::InvalidField`] naming `field`, the count and the limits.
pub fn check_count(field: &str, count: usize, min: usize, max: usize) -> Result<()> {
    if (min..=max).contains(&count) {
        return Ok(());
    }
    Err(Error::InvalidField {
        field: field.to_string(),
        message: format!("{count} entries: expected {min} to {max}"),
    })
}

/// Checks that the setting `field` (a count or a budget) lies within `[min, max]`.
///
/// # Errors
/// [`Error::InvalidField`] naming `field`, the value and the range.
pub fn check_integer(field: &str, value: u64, min: u64, max: u64) -> Result<()> {
    if (min..=max).contains(&value) {
        return Ok(());
    }
    Err(Error::InvalidField {
        field: field.to_string(),
        message: format!("{value} is outside [{min}, {max}]"),
    })
}

#[cfg(test)]
mod limits_tests;
