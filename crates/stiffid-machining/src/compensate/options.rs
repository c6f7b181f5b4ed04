//! How to compensate a path: the free tool axis and the options of the Newton steps.

use nalgebra::Vector6;
use stiffid_core::common::error::JobOption;
use stiffid_core::common::words::number;
use stiffid_core::robot::ik;
use stiffid_core::{Error, Result, Setup};

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

impl stiffid_core::common::choice::Choice for Aggregate {
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

stiffid_core::common::choice::by_name!(Aggregate);

/// What the free tool axis minimises (module docs, "The free tool axis").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Objective {
    /// The TCP translation deflection under the path's wrench at every point.
    #[default]
    Deflection,
    /// The breakthrough surge at every drilling exit of a program
    /// ([`crate::dynamics`]): needs the robot's masses and a process that drills.
    Surge,
    /// The error bound of every point ([`super::Budget`]).
    Bound,
}

impl stiffid_core::common::choice::Choice for Objective {
    const FIELD: &'static str = "minimise";
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

stiffid_core::common::choice::by_name!(Objective);

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

/// The free track station: the first carrier axis of the cell ([`stiffid_core::robot::external`]) moved
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
                    "{}: expected a number >= {} and <= the range ({})",
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
    /// of `compensate --free station` and Python's `free=["station=..."]`.
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
/// [`Options::free_tilt`]), [`stiffid_core::robot::external`], turned from the path's own angle at
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
        if range < Self::MIN_STEP_DEG {
            return Err(Error::InvalidOption {
                option: range_option,
                message: format!(
                    "{}: below the smallest step, {} deg: the range would hold no angle but the path's own",
                    number(range),
                    Self::MIN_STEP_DEG
                ),
            });
        }
        if !(step >= Self::MIN_STEP_DEG && step <= range) {
            return Err(Error::InvalidOption {
                option: step_option,
                message: format!(
                    "{}: expected a number >= {} and <= the range ({})",
                    number(step),
                    Self::MIN_STEP_DEG,
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

/// The lead and the tilt of the tool axis, free within a cone about the path's own axis
/// (module docs of [`super`], "Lead and tilt"), on a grid of `max_step` spacing, jointly with
/// the rotation about tool z, the station and the positioner when they are free too.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeLeadTilt {
    /// The cone's half angle, rad, in (0, [`FreeLeadTilt::MAX_CONE_DEG`]]: `Some` for a path
    /// file's points (`--free lead-tilt=-CONE..CONE`); `None` for a program's, whose process file gives each
    /// operation's cone ([`crate::process::Operation::cone`]).
    pub cone: Option<f64>,
    /// The largest change of the lead, and of the tilt, between consecutive points (rad, at
    /// least [`FreeLeadTilt::MIN_STEP_DEG`], at most the cone): the grid's spacing.
    pub max_step: f64,
    /// What the lean minimises: the deflection or the bound ([`Objective::Surge`] is refused:
    /// a drill's axis is the hole's).
    pub objective: Objective,
    /// How the points' costs add up along the path.
    pub aggregate: Aggregate,
}

/// The free configuration (`compensate --free configuration`): what the path's objective is
/// and how its points' costs add up, those of the other free variables given with it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeConfiguration {
    /// What a point costs: the TCP deflection or the error bound ([`Objective::Surge`] is
    /// refused).
    pub objective: Objective,
    /// How the points' costs add up along the path.
    pub aggregate: Aggregate,
    /// What one configuration holds: the whole program, or each run between rapid moves
    /// ([`super::Scope`]).
    pub per: super::Scope,
}

impl FreeLeadTilt {
    /// The largest cone's half angle, deg: of `--free lead-tilt=-CONE..CONE` and of a process file's
    /// `[tool_axis] cone_deg`.
    pub const MAX_CONE_DEG: f64 = 30.0;
    /// The smallest accepted `max_step`, deg.
    pub const MIN_STEP_DEG: f64 = 0.1;

    /// The free lead and tilt from the cone's half angle (`None`: the process file's) and the
    /// step in degrees (the units of the command line and the Python package): `cone_deg` in
    /// (0, 30], `step_deg` in [0.1, `cone_deg`] (at most 30 without a cone); it minimises what
    /// the free tool axis `free` minimises (the bound without one), its points' costs added up
    /// by `aggregate`.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] naming the argument that is wrong ([`JobOption::ConeDeg`] or
    /// [`JobOption::LeadTiltStepDeg`]) with the value given; ([`JobOption::FreeToolAxisObjective`])
    /// for the surge.
    pub fn try_with(
        cone_deg: Option<f64>,
        step_deg: f64,
        free: Option<&FreeToolAxis>,
        aggregate: Aggregate,
    ) -> Result<Self> {
        let objective = free.map_or(Objective::Bound, |f| f.objective);
        Self::checked(cone_deg, step_deg, objective, aggregate)
    }

    /// Checks the fields as [`FreeLeadTilt::try_with`] gives them.
    ///
    /// # Errors
    /// Those of [`FreeLeadTilt::try_with`].
    pub fn validate(&self) -> Result<()> {
        let cone = self.cone.map(f64::to_degrees);
        Self::checked(
            cone,
            self.max_step.to_degrees(),
            self.objective,
            self.aggregate,
        )
        .map(|_| ())
    }

    /// [`FreeLeadTilt::try_with`] with its objective.
    fn checked(
        cone_deg: Option<f64>,
        step_deg: f64,
        objective: Objective,
        aggregate: Aggregate,
    ) -> Result<Self> {
        if let Some(c) = cone_deg.filter(|c| !(*c > 0.0 && *c <= Self::MAX_CONE_DEG)) {
            return Err(Error::InvalidOption {
                option: JobOption::ConeDeg,
                message: format!(
                    "{}: expected a number > 0 and <= {} (the cone's half angle)",
                    number(c),
                    Self::MAX_CONE_DEG
                ),
            });
        }
        if let Some(c) = cone_deg.filter(|c| *c < Self::MIN_STEP_DEG) {
            return Err(Error::InvalidOption {
                option: JobOption::ConeDeg,
                message: format!(
                    "{}: below the smallest step of the lead and tilt, {} deg: the cone would hold no lean",
                    number(c),
                    Self::MIN_STEP_DEG
                ),
            });
        }
        let most = cone_deg.unwrap_or(Self::MAX_CONE_DEG);
        if !(step_deg >= Self::MIN_STEP_DEG && step_deg <= most) {
            return Err(Error::InvalidOption {
                option: JobOption::LeadTiltStepDeg,
                message: format!(
                    "{}: expected a number >= {} and <= {} ({})",
                    number(step_deg),
                    Self::MIN_STEP_DEG,
                    number(most),
                    match cone_deg {
                        Some(_) => "the cone",
                        None => "the largest cone",
                    }
                ),
            });
        }
        if objective == Objective::Surge {
            return Err(Error::InvalidOption {
                option: JobOption::FreeToolAxisObjective,
                message: "surge: the surge is a drilling exit's, and a drill's axis is the hole's: the lead and tilt minimise the deflection or the bound".into(),
            });
        }
        Ok(Self {
            cone: cone_deg.map(f64::to_radians),
            max_step: step_deg.to_radians(),
            objective,
            aggregate,
        })
    }
}

impl FreeConfiguration {
    /// The most path points a free configuration evaluates (every configuration holds the whole
    /// path).
    pub const MAX_POINTS: usize = 100_000;
    /// Random starts of inverse kinematics that look for the configurations of the first point.
    pub const SEEDS: usize = 128;

    /// The free configuration minimising what the free tool axis `free` minimises (the bound
    /// without one), its points' costs added up by `aggregate`: the option
    /// `compensate --free configuration` and Python's `free=["configuration"]`; one
    /// configuration per program ([`FreeConfiguration::per`] to change it).
    pub fn with(free: Option<&FreeToolAxis>, aggregate: Aggregate) -> Self {
        Self {
            objective: free.map_or(Objective::Bound, |f| f.objective),
            aggregate,
            per: super::Scope::Program,
        }
    }

    /// Refuses the surge objective and a path of more than [`Self::MAX_POINTS`] points.
    ///
    /// # Errors
    /// [`Error::OptionCombination`] (`free configuration` not with `minimise`)
    /// for the surge; [`Error::InvalidOption`] ([`JobOption::FreeConfiguration`]) for too many
    /// points.
    pub fn check(&self, points: usize) -> Result<()> {
        if self.objective == Objective::Surge {
            return Err(Error::OptionCombination {
                option: JobOption::FreeConfiguration,
                with: vec![JobOption::FreeToolAxisObjective],
                needs: false,
                reason: "surge: the configuration is chosen by the deflection or the error bound"
                    .into(),
            });
        }
        if points > Self::MAX_POINTS {
            return Err(Error::InvalidOption {
                option: JobOption::FreeConfiguration,
                message: format!(
                    "{points} path points: at most {} (every configuration holds the whole path)",
                    Self::MAX_POINTS
                ),
            });
        }
        Ok(())
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

impl stiffid_core::common::choice::Choice for MapVariable {
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

stiffid_core::common::choice::by_name!(MapVariable);

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
    /// [`super::path_on_track`], or a program's, [`crate::compensate()`]), jointly
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
    /// [`super::path_configurations`], [`crate::compensate()`] and the compensate
    /// job evaluate it; [`super::path`] and [`super::stream`] ignore it.
    pub free_configuration: Option<FreeConfiguration>,
    /// The level of the prediction intervals of the deflection (with a compliance that carries
    /// a prediction calibration, [`stiffid_core::model::prediction`]), within
    /// [`stiffid_core::model::prediction::LEVEL`].
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
    /// Levels of refinement of the free variables' grid around the line chosen on it, 0 to
    /// [`super::refine::MAX_LEVELS`] (module docs of [`super`], "Refining the grid"); 0: the
    /// grid alone.
    pub refine: usize,
}

impl Options {
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
            level: stiffid_core::model::prediction::DEFAULT_LEVEL,
            max_iterations: super::MAX_ITERATIONS,
            force_tolerance: super::budget::DEFAULT_FORCE_TOLERANCE,
            max_error: None,
            feasible: super::Feasible::for_setup(setup),
            map: false,
            map_over: MapVariable::Rotation,
            refine: 0,
        }
    }
}
