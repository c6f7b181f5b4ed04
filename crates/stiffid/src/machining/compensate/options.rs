//! How to compensate a path: the free tool axis and the options of the Newton steps.

use super::{FreeConfiguration, FreeLeadTilt};
use crate::common::error::JobOption;
use crate::common::words::number;
use crate::robot::ik::{self};
use crate::{common::limits, Error, Result, Setup};
use nalgebra::Vector6;

/// The stiffness-optimal rotation about the tool z axis (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeToolAxis {
    /// Largest change of the rotation between consecutive points, rad, > 0.
    pub max_step: f64,
    /// The rotation stays within `+-range` of the path's, rad.
    pub range: f64,
    /// What the rotation minimises.
    pub objective: Objective,
    /// How the points' costs add up along the path: their sum, or the worst point's.
    pub aggregate: Aggregate,
}

/// How the free tool axis adds the points' costs up along the path (`--objective`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Aggregate {
    /// The sum over the path.
    #[default]
    Sum,
    /// The worst point's (ties broken by the sum).
    Max,
}

impl crate::common::choice::Choice for Aggregate {
    const FIELD: &'static str = "objective";
    const ALL: &'static [Self] = &[Aggregate::Sum, Aggregate::Max];
    fn name(self) -> &'static str {
        match self {
            Aggregate::Sum => "sum",
            Aggregate::Max => "max",
        }
    }
    fn help(self) -> &'static str {
        match self {
            Aggregate::Sum => "The sum of the points' costs along the path",
            Aggregate::Max => "The worst point's cost (ties broken by the sum)",
        }
    }
}

crate::common::choice::by_name!(Aggregate);

/// What the free tool axis minimises (module docs, "The free tool axis").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Objective {
    /// The TCP translation deflection under the path's wrench at every point.
    #[default]
    Deflection,
    /// The breakthrough surge at every drilling exit of a program
    /// ([`crate::machining::dynamics`]): needs the robot's masses and a process that drills.
    Surge,
    /// The error bound of every point ([`super::Budget`]).
    Bound,
}

impl crate::common::choice::Choice for Objective {
    const FIELD: &'static str = "free_tool_axis_objective";
    const ALL: &'static [Self] = &[Objective::Deflection, Objective::Surge, Objective::Bound];
    fn name(self) -> &'static str {
        match self {
            Objective::Deflection => "deflection",
            Objective::Surge => "surge",
            Objective::Bound => "bound",
        }
    }
    fn help(self) -> &'static str {
        match self {
            Objective::Deflection => "The TCP deflection under the path's wrench at every point",
            Objective::Surge => {
                "The breakthrough surge at every drilling exit (a program whose robot gives its masses)"
            }
            Objective::Bound => {
                "The error bound at every point: the compensation's uncertainty, the calibration's held-out error, the force model's part"
            }
        }
    }
}

crate::common::choice::by_name!(Objective);

impl FreeToolAxis {
    /// Largest accepted `max_step`, deg.
    pub const MAX_STEP_DEG: f64 = 90.0;
    /// Largest accepted `range`, deg.
    pub const MAX_RANGE_DEG: f64 = 180.0;

    /// The free tool axis from its step and range in degrees (the units of the command line and
    /// the Python package): `max_step_deg` in (0, 90], `tool_axis_range_deg` in (0, 180]; it
    /// minimises the deflection ([`Objective::Deflection`]).
    ///
    /// # Errors
    /// [`Error::InvalidOption`] naming the one argument that is wrong ([`JobOption::MaxStepDeg`] or
    /// [`JobOption::ToolAxisRangeDeg`]) with the value given.
    pub fn try_from_degrees(max_step_deg: f64, tool_axis_range_deg: f64) -> Result<Self> {
        // A subnormal angle in rad (5e-324 deg) is zero in every computation: refused as <= 0.
        let check = |v: f64, max: f64, option| match v.to_radians().is_normal() && v <= max {
            true => Ok(v.to_radians()),
            false => Err(Error::InvalidOption {
                option,
                message: format!("{}: expected a number > 0 and <= {max}", number(v)),
            }),
        };
        Ok(Self {
            max_step: check(max_step_deg, Self::MAX_STEP_DEG, JobOption::MaxStepDeg)?,
            range: check(
                tool_axis_range_deg,
                Self::MAX_RANGE_DEG,
                JobOption::ToolAxisRangeDeg,
            )?,
            objective: Objective::Deflection,
            aggregate: Aggregate::Sum,
        })
    }

    /// The most grid cells (angles x path points) the optimisation may visit: each is one
    /// inverse kinematics solution kept in memory (about 70 bytes), so at most about 0.4 GB.
    pub const MAX_GRID_CELLS: f64 = 5e6;

    /// The grid spacing: `max_step` divided into whole cells of at most 5 deg, and the number of
    /// cells one step may move.
    pub(super) fn grid(&self) -> (f64, usize) {
        let cells = (self.max_step / 5f64.to_radians()).ceil().max(1.0);
        (self.max_step / cells, cells as usize)
    }

    /// The grid's angles, rad, ascending, `0` among them: `2 floor(range / spacing) + 1`.
    pub(super) fn angles(&self) -> Vec<f64> {
        let (spacing, _) = self.grid();
        let half = (self.range / spacing + 1e-9).floor() as isize;
        (-half..=half).map(|g| g as f64 * spacing).collect()
    }

    /// The number of angles of the grid: `2 floor(range / spacing) + 1`, as a float (it may be
    /// astronomically large for a tiny `max_step`).
    pub(super) fn angle_count(&self) -> f64 {
        2.0 * (self.range / self.grid().0 + 1e-9).floor() + 1.0
    }

    /// Checks that the grid of a path of `points` points stays within [`Self::MAX_GRID_CELLS`].
    ///
    /// # Errors
    /// [`Error::InvalidOption`] ([`JobOption::MaxStepDeg`]) with the grid's size and what to
    /// change.
    pub fn check_grid(&self, points: usize) -> Result<()> {
        let angles = self.angle_count();
        let cells = angles * points as f64;
        if cells <= Self::MAX_GRID_CELLS {
            return Ok(());
        }
        Err(Error::InvalidOption {
            option: JobOption::MaxStepDeg,
            message: format!(
                "{} deg with a range of +-{} deg makes a grid of {angles:.3e} angles x {points} path points = {cells:.3e} cells; at most {:.0e} (a larger step, a smaller range or a shorter path)",
                number(self.max_step.to_degrees()),
                number(self.range.to_degrees()),
                Self::MAX_GRID_CELLS
            ),
        })
    }
}

/// The free track station: the first carrier axis of the cell ([`crate::robot::external`]) moved
/// from the path's own station at every point, jointly with the tool rotation when
/// [`Options::free_tool_axis`] is given too (module docs of [`super`], "The free station").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeStation {
    /// The station stays within `+-range` of the path's own and within the axis's travel, m, > 0.
    pub range: f64,
    /// Largest change of the station's offset from the path's own between consecutive points
    /// (m, positive): the grid's spacing. The cell files give no axis speeds: this step is the
    /// speed limit (the step over the distance between two points, times the feed).
    pub max_step: f64,
    /// What the station minimises ([`Objective::Surge`] is refused: a path file has no
    /// drilling exits).
    pub objective: Objective,
    /// How the points' costs add up along the path.
    pub aggregate: Aggregate,
}

impl FreeStation {
    /// Largest accepted `range`, mm.
    pub const MAX_RANGE_MM: f64 = 20_000.0;
    /// Smallest accepted `max_step`, mm.
    pub const MIN_STEP_MM: f64 = 0.1;

    /// The free station from its range and step in mm (the units of the command line):
    /// `free_station_mm` in (0, 20 000], `station_step_mm` in [0.1, `free_station_mm`]; it
    /// minimises the error bound ([`Objective::Bound`]) summed along the path.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] naming the argument that is wrong ([`JobOption::FreeStationMm`]
    /// or [`JobOption::StationStepMm`]) with the value given.
    pub fn try_from_mm(free_station_mm: f64, station_step_mm: f64) -> Result<Self> {
        if !(free_station_mm > 0.0 && free_station_mm <= Self::MAX_RANGE_MM) {
            return Err(Error::InvalidOption {
                option: JobOption::FreeStationMm,
                message: format!(
                    "{}: expected a number > 0 and <= {}",
                    number(free_station_mm),
                    Self::MAX_RANGE_MM
                ),
            });
        }
        if !(station_step_mm >= Self::MIN_STEP_MM && station_step_mm <= free_station_mm) {
            return Err(Error::InvalidOption {
                option: JobOption::StationStepMm,
                message: format!(
                    "{}: expected a number >= {} and <= --free-station-mm ({})",
                    number(station_step_mm),
                    Self::MIN_STEP_MM,
                    number(free_station_mm)
                ),
            });
        }
        Ok(Self {
            range: free_station_mm * 1e-3,
            max_step: station_step_mm * 1e-3,
            objective: Objective::Bound,
            aggregate: Aggregate::Sum,
        })
    }

    /// [`FreeStation::try_from_mm`] minimising what the free tool axis `free` given with it
    /// minimises (the bound without one), its points' costs added up by `aggregate`: the options
    /// of `compensate --free-station-mm` and Python's `free_station_mm=`.
    ///
    /// # Errors
    /// Those of [`FreeStation::try_from_mm`].
    pub fn try_with(
        free_station_mm: f64,
        station_step_mm: f64,
        free: Option<&FreeToolAxis>,
        aggregate: Aggregate,
    ) -> Result<Self> {
        Ok(Self {
            objective: free.map_or(Objective::Bound, |f| f.objective),
            aggregate,
            ..Self::try_from_mm(free_station_mm, station_step_mm)?
        })
    }

    /// The offsets from the path's own station, m, ascending, `0` among them:
    /// `k max_step` for `|k| <= floor(range / max_step)`.
    pub(super) fn offsets(&self) -> Vec<f64> {
        offsets(self.range, self.max_step)
    }
}

/// `k step` for `|k| <= floor(range / step)`, ascending.
pub(super) fn offsets(range: f64, step: f64) -> Vec<f64> {
    let half = (range / step + 1e-9).floor() as isize;
    (-half..=half).map(|k| k as f64 * step).collect()
}

/// A free axis of the positioner: its last axis (the table's turn; a turntable's only axis,
/// [`Options::free_positioner`]) or a two-axis positioner's first (the tilt,
/// [`Options::free_tilt`]), [`crate::robot::external`], turned from the path's own angle at
/// every point, jointly with the other free variables given (module docs of [`super`], "The
/// free positioner"). Its options mirror the station's: a range and a step, in deg.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreePositioner {
    /// The angle stays within `+-range` of the path's own and within the axis's travel, rad, > 0.
    pub range: f64,
    /// Largest change of the angle's offset from the path's own between consecutive points
    /// (rad, positive): the grid's spacing, and the speed limit (as the station's step).
    pub max_step: f64,
    /// What the positioner minimises ([`Objective::Surge`] is refused).
    pub objective: Objective,
    /// How the points' costs add up along the path.
    pub aggregate: Aggregate,
}

impl FreePositioner {
    /// Largest accepted `range`, deg.
    pub const MAX_RANGE_DEG: f64 = 360.0;
    /// Smallest accepted `max_step`, deg.
    pub const MIN_STEP_DEG: f64 = 0.01;

    /// The free positioner (its last axis) from its range and step in degrees (the units of
    /// the command line and the Python package): `free_positioner_deg` in (0, 360],
    /// `positioner_step_deg` in [0.01, `free_positioner_deg`]; it minimises what the free tool
    /// axis `free` minimises (the bound without one), its points' costs added up by
    /// `aggregate`.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] naming the argument that is wrong
    /// ([`JobOption::FreePositionerDeg`] or [`JobOption::PositionerStepDeg`]) with the value
    /// given.
    pub fn try_with(
        free_positioner_deg: f64,
        positioner_step_deg: f64,
        free: Option<&FreeToolAxis>,
        aggregate: Aggregate,
    ) -> Result<Self> {
        let names = [JobOption::FreePositionerDeg, JobOption::PositionerStepDeg];
        Self::try_axis(
            (free_positioner_deg, positioner_step_deg),
            free,
            aggregate,
            names,
        )
    }

    /// The free tilt (a two-axis positioner's first axis) from its range and step in degrees,
    /// as [`FreePositioner::try_with`]: `free_tilt_deg` in (0, 360], `tilt_step_deg` in
    /// [0.01, `free_tilt_deg`].
    ///
    /// # Errors
    /// [`Error::InvalidOption`] naming the argument that is wrong ([`JobOption::FreeTiltDeg`]
    /// or [`JobOption::TiltStepDeg`]) with the value given.
    pub fn try_tilt(
        free_tilt_deg: f64,
        tilt_step_deg: f64,
        free: Option<&FreeToolAxis>,
        aggregate: Aggregate,
    ) -> Result<Self> {
        let names = [JobOption::FreeTiltDeg, JobOption::TiltStepDeg];
        Self::try_axis((free_tilt_deg, tilt_step_deg), free, aggregate, names)
    }

    /// The range and step (deg) checked, each refused naming its option of `names`.
    fn try_axis(
        (range, step): (f64, f64),
        free: Option<&FreeToolAxis>,
        aggregate: Aggregate,
        [range_option, step_option]: [JobOption; 2],
    ) -> Result<Self> {
        if !(range > 0.0 && range <= Self::MAX_RANGE_DEG) {
            return Err(Error::InvalidOption {
                option: range_option,
                message: format!(
                    "{}: expected a number > 0 and <= {}",
                    number(range),
                    Self::MAX_RANGE_DEG
                ),
            });
        }
        if !(step >= Self::MIN_STEP_DEG && step <= range) {
            return Err(Error::InvalidOption {
                option: step_option,
                message: format!(
                    "{}: expected a number >= {} and <= --{} ({})",
                    number(step),
                    Self::MIN_STEP_DEG,
                    range_option.name().replace('_', "-"),
                    number(range)
                ),
            });
        }
        Ok(Self {
            range: range.to_radians(),
            max_step: step.to_radians(),
            objective: free.map_or(Objective::Bound, |f| f.objective),
            aggregate,
        })
    }

    /// The offsets from the path's own angle, rad, ascending, `0` among them.
    pub(super) fn offsets(&self) -> Vec<f64> {
        offsets(self.range, self.max_step)
    }
}

/// The free variable a map is drawn over (`compensate --map rotation|track`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MapVariable {
    /// The rotation about tool z (the free tool axis).
    #[default]
    Rotation,
    /// The track station (the carrier's first axis, the free station).
    Track,
}

impl crate::common::choice::Choice for MapVariable {
    const FIELD: &'static str = "map";
    const ALL: &'static [Self] = &[MapVariable::Rotation, MapVariable::Track];
    fn name(self) -> &'static str {
        match self {
            MapVariable::Rotation => "rotation",
            MapVariable::Track => "track",
        }
    }
    fn help(self) -> &'static str {
        match self {
            MapVariable::Rotation => "The rotation about the spindle (tool z)",
            MapVariable::Track => "The track station (a robot on a track)",
        }
    }
}

crate::common::choice::by_name!(MapVariable);

/// How to compensate a path.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Where inverse kinematics starts for the first pose, axis angles, rad.
    pub q0: Vector6<f64>,
    /// Inverse kinematics tolerances and effort.
    pub ik: ik::Options,
    /// Optimise the rotation about the tool z axis.
    pub free_tool_axis: Option<FreeToolAxis>,
    /// Optimise the track station (a cell with a carrier: a path file's points,
    /// [`super::path_on_track`], or a program's, [`crate::machining::compensate()`]), jointly
    /// with the rotation when `free_tool_axis` is given too.
    pub free_station: Option<FreeStation>,
    /// Optimise the positioner's angle (a cell with a positioner: its last axis), jointly with
    /// the station, the tilt and the rotation when they are given too.
    pub free_positioner: Option<FreePositioner>,
    /// Lean the tool axis within a cone about the path's own ([`FreeLeadTilt`]), jointly
    /// with the rotation, the station and the positioner when they are free too.
    pub free_lead_tilt: Option<FreeLeadTilt>,
    /// Optimise the tilt (a cell with a two-axis positioner: its first axis), jointly with the
    /// other free variables given.
    pub free_tilt: Option<FreePositioner>,
    /// Evaluate the path in every configuration of the arm and keep the best
    /// ([`FreeConfiguration`]), jointly with the other free variables (their dynamic
    /// programming run in each configuration); `None`: the path's own configuration.
    /// [`super::path_configurations`], [`crate::machining::compensate()`] and the compensate
    /// job evaluate it; [`super::path`] and [`super::stream`] ignore it.
    pub free_configuration: Option<FreeConfiguration>,
    /// The level of the prediction intervals of the deflection (with a compliance that carries
    /// a prediction calibration, [`crate::model::prediction`]), within
    /// [`crate::model::prediction::LEVEL`].
    pub level: f64,
    /// Newton steps at most per point, 1 to [`super::MAX_ITERATIONS`] (the default).
    pub max_iterations: usize,
    /// The process force model's relative error, in [0, 1] (default
    /// [`super::budget::DEFAULT_FORCE_TOLERANCE`]): the error budget's force part
    /// ([`super::Budget`]).
    pub force_tolerance: f64,
    /// The largest error bound the compensate job accepts anywhere on the path, m (> 0, finite):
    /// a path with a point above it is refused ([`crate::app::compensate::run`]); `None` accepts
    /// any.
    pub max_error: Option<f64>,
    /// What every posture the free variables move a point to must keep: the joint-limit margin,
    /// the condition number and the cell's collision checks ([`super::Feasible`]).
    pub feasible: super::Feasible,
    /// The compensate job also maps the free variable ([`super::Map`]: every point at every
    /// value of the grid of [`Options::map_over`]); [`super::path`] ignores it.
    pub map: bool,
    /// The variable of the map: the rotation about tool z (the default) or the track station.
    pub map_over: MapVariable,
}

impl Options {
    /// Checks every field: `q0` within [`limits::ANGLE_RAD`] (finite), `ik`
    /// ([`ik::Options::validate`]), `max_iterations` 1 to [`super::MAX_ITERATIONS`], a free tool axis' `max_step` in (0, 90] deg and `range` in
    /// (0, 180] deg as [`FreeToolAxis::try_from_degrees`] gives them, a free station's as
    /// [`FreeStation::try_from_mm`] and a free positioner's and tilt's as
    /// [`FreePositioner::try_with`] and [`FreePositioner::try_tilt`] give them, minimising the deflection or the bound with the free tool axis' objective and
    /// aggregate. [`path`] calls it.
    ///
    /// # Errors
    /// [`Error::InvalidField`] naming the field, the value and the range;
    /// [`Error::InvalidOption`] for a free station's or positioner's
    /// ([`JobOption::FreeStationMm`], [`JobOption::StationStepMm`],
    /// [`JobOption::FreePositionerDeg`], [`JobOption::PositionerStepDeg`],
    /// [`JobOption::FreeTiltDeg`], [`JobOption::TiltStepDeg`],
    /// [`JobOption::FreeToolAxisObjective`]) and the feasibility's ([`super::Feasible::validate`]).
    pub fn validate(&self) -> Result<()> {
        limits::check(
            "compensate::Options.q0",
            self.q0.as_slice(),
            &limits::ANGLE_RAD,
        )?;
        self.ik.validate()?;
        crate::model::prediction::check_level("compensate::Options.level", self.level)?;
        limits::check_integer(
            "compensate::Options.max_iterations",
            self.max_iterations as u64,
            1,
            super::MAX_ITERATIONS as u64,
        )?;
        if let Some(m) = self.max_error.filter(|m| !(m.is_finite() && *m > 0.0)) {
            return Err(Error::InvalidOption {
                option: JobOption::MaxErrorMm,
                message: format!("{}: expected a number > 0", number(m * 1e3)),
            });
        }
        if !(0.0..=1.0).contains(&self.force_tolerance) {
            return Err(Error::InvalidOption {
                option: JobOption::ForceTolerancePercent,
                message: format!(
                    "{}: expected 0 to 100 percent",
                    number(self.force_tolerance * 100.0)
                ),
            });
        }
        self.validate_station()?;
        if let Some(l) = &self.free_lead_tilt {
            l.validate()?;
        }
        self.validate_configuration()?;
        self.feasible.validate()?;
        let Some(free) = &self.free_tool_axis else {
            return Ok(());
        };
        let fields = [
            ("max_step", free.max_step, FreeToolAxis::MAX_STEP_DEG),
            ("range", free.range, FreeToolAxis::MAX_RANGE_DEG),
        ];
        for (field, value, most) in fields {
            if !(value > 0.0 && value <= most.to_radians()) {
                return Err(Error::InvalidField {
                    field: format!("FreeToolAxis.{field}"),
                    message: format!(
                        "{} rad: expected a number > 0 and <= {most} deg",
                        number(value)
                    ),
                });
            }
        }
        Ok(())
    }

    /// A free station's range and step as [`FreeStation::try_from_mm`] gives them, a free
    /// positioner's and tilt's as [`FreePositioner::try_with`] and [`FreePositioner::try_tilt`],
    /// and their objective and aggregate those of a free tool axis given with them and of each
    /// other.
    fn validate_station(&self) -> Result<()> {
        if let Some(s) = &self.free_station {
            FreeStation::try_from_mm(s.range * 1e3, s.max_step * 1e3)?;
        }
        if let Some(p) = &self.free_positioner {
            FreePositioner::try_with(
                p.range.to_degrees(),
                p.max_step.to_degrees(),
                None,
                p.aggregate,
            )?;
        }
        if let Some(p) = &self.free_tilt {
            let (range, step) = (p.range.to_degrees(), p.max_step.to_degrees());
            FreePositioner::try_tilt(range, step, None, p.aggregate)?;
        }
        let station = self.free_station.map(|s| (s.objective, s.aggregate));
        let positioner = self.free_positioner.map(|p| (p.objective, p.aggregate));
        let tilt = self.free_tilt.map(|p| (p.objective, p.aggregate));
        let tool = self.free_tool_axis.map(|f| (f.objective, f.aggregate));
        let lean = self.free_lead_tilt.map(|l| (l.objective, l.aggregate));
        let Some(own) = station.or(positioner).or(tilt).or(lean) else {
            return Ok(());
        };
        let agree = [station, positioner, tilt, tool, lean]
            .iter()
            .flatten()
            .all(|c| *c == own);
        if own.0 == Objective::Surge || !agree {
            return Err(Error::InvalidOption {
                option: JobOption::FreeToolAxisObjective,
                message: format!("{}: the free station, positioner axes, lead and tilt minimise the deflection or the bound, the same objective and aggregate as the free tool axis given with them", crate::common::choice::Choice::name(own.0)),
            });
        }
        Ok(())
    }

    /// A free configuration's objective not the surge ([`FreeConfiguration::check`]) and
    /// its objective and aggregate those of the other free variables given with it.
    fn validate_configuration(&self) -> Result<()> {
        let Some(c) = &self.free_configuration else {
            return Ok(());
        };
        c.check(0)?;
        let tool = self.free_tool_axis.map(|f| (f.objective, f.aggregate));
        let lean = self.free_lead_tilt.map(|l| (l.objective, l.aggregate));
        match self.external_objective().or(tool).or(lean) {
            Some(other) if other != (c.objective, c.aggregate) => Err(Error::InvalidOption {
                option: JobOption::FreeConfiguration,
                message: "the free configuration minimises the same objective and aggregate as the other free variables given with it".into(),
            }),
            _ => Ok(()),
        }
    }

    /// What the free station, positioner or tilt minimise and how the costs add up: theirs
    /// (equal, [`Options::validate`]); `None` without any.
    pub(super) fn external_objective(&self) -> Option<(Objective, Aggregate)> {
        let station = self.free_station.map(|s| (s.objective, s.aggregate));
        let positioner = self.free_positioner.or(self.free_tilt);
        station.or(positioner.map(|p| (p.objective, p.aggregate)))
    }

    /// Whether an external axis is free: the station, the positioner or the tilt.
    pub fn frees_external(&self) -> bool {
        self.external_objective().is_some()
    }

    /// The defaults for `setup`: inverse kinematics starts at the setup's first test posture (else
    /// the middle of its bounds), with [`ik::Options::default`]; no free tool axis; at most
    /// [`super::MAX_ITERATIONS`] Newton steps per point; the feasibility of
    /// [`super::Feasible::for_setup`].
    pub fn for_setup(setup: &Setup) -> Self {
        let bounds = setup.bounds();
        Self {
            q0: setup
                .test_postures()
                .first()
                .copied()
                .unwrap_or((bounds.lower + bounds.upper) / 2.0),
            ik: ik::Options::default(),
            free_tool_axis: None,
            free_station: None,
            free_positioner: None,
            free_lead_tilt: None,
            free_tilt: None,
            free_configuration: None,
            level: crate::model::prediction::DEFAULT_LEVEL,
            max_iterations: super::MAX_ITERATIONS,
            force_tolerance: super::budget::DEFAULT_FORCE_TOLERANCE,
            max_error: None,
            feasible: super::Feasible::for_setup(setup),
            map: false,
            map_over: MapVariable::Rotation,
        }
    }
}
