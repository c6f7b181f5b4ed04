//! The free variables a compensation reads, in one place ([`FreeVariables`]): each variable's
//! range and step in SI units ([`FreeRange`], [`LeadTilt`]) and the one objective they minimise
//! together. [`super::Freedom::apply`] builds it from the options of the command line and
//! Python, each range and step checked here against its variable's limits ([`Limits`]).

use super::Scope;
use stiffid_core::common::error::JobOption;
use stiffid_core::common::words::number;
use stiffid_core::{Error, Result};

/// A variable a compensation may move from the path's own value at every point.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Variable {
    /// The rotation about the tool z axis (`tool-rotation`, deg).
    ToolRotation,
    /// The lead and the tilt of the tool axis within a cone (`lead-tilt`, deg).
    LeadTilt,
    /// The track station: the carrier's first axis (`station`, mm).
    Station,
    /// The positioner's last axis, the table's turn (`positioner`, deg).
    Positioner,
    /// A two-axis positioner's first axis (`tilt`, deg).
    Tilt,
    /// The configuration of the arm (`configuration`, `configuration=run`: one per run).
    Configuration(Scope),
    /// An external axis named as the setup's cell names it: the carrier's first axis is the
    /// station, the positioner's last the table's turn, a two-axis positioner's first the tilt.
    Axis(String),
}

impl Variable {
    /// The variable's name as `super::Free::parse` reads it.
    pub(crate) fn name(&self) -> &str {
        match self {
            Variable::ToolRotation => "tool-rotation",
            Variable::LeadTilt => "lead-tilt",
            Variable::Station => "station",
            Variable::Positioner => "positioner",
            Variable::Tilt => "tilt",
            Variable::Configuration(_) => "configuration",
            Variable::Axis(name) => name,
        }
    }
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

/// What the free variables minimise (module docs, "The free tool axis"); by default the
/// error bound the document reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Objective {
    /// The TCP translation deflection under the path's wrench at every point.
    Deflection,
    /// The breakthrough surge at every drilling exit of a program
    /// ([`crate::dynamics`]): needs the robot's masses and a process that drills.
    Surge,
    /// The error bound of every point ([`super::Budget`]).
    #[default]
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

/// A free variable's range about the path's own value (`+-range`) and its step (the grid's
/// spacing, and the most it changes between consecutive points), in SI units: rad, or m for
/// the station.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeRange {
    /// The half range, rad or m, > 0.
    pub range: f64,
    /// The step, rad or m, > 0.
    pub step: f64,
}

/// The lead and the tilt of the tool axis free within a cone about the path's own axis (module
/// docs of [`super`], "Lead and tilt").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LeadTilt {
    /// The cone's half angle, rad: `Some` for a path file's points (`--free
    /// lead-tilt=-CONE..CONE`); `None` for a program's, whose process file gives each
    /// operation's cone ([`crate::process::Operation::cone`]).
    pub cone: Option<f64>,
    /// The largest change of the lead, and of the tilt, between consecutive points, rad: the
    /// grid's spacing.
    pub step: f64,
}

/// One free variable with its bounds in SI units: what a compensation may move from the path's
/// own value at every point (`Free::variable` names it as `--free` does).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Free {
    /// The rotation about the tool z axis, rad (module docs of [`super`], "The free tool axis").
    ToolRotation(FreeRange),
    /// The lead and tilt of the tool axis within a cone ("Lead and tilt").
    LeadTilt(LeadTilt),
    /// The track station: the carrier's first axis, m ("The free station").
    Station(FreeRange),
    /// The positioner's last axis, the table's turn, rad ("The free positioner").
    Positioner(FreeRange),
    /// A two-axis positioner's first axis, the tilt, rad.
    Tilt(FreeRange),
    /// The configuration of the arm, one per program or per run ([`Scope`]).
    Configuration(Scope),
}

impl Free {
    /// The variable this one moves.
    pub(crate) fn variable(&self) -> Variable {
        match self {
            Free::ToolRotation(_) => Variable::ToolRotation,
            Free::LeadTilt(_) => Variable::LeadTilt,
            Free::Station(_) => Variable::Station,
            Free::Positioner(_) => Variable::Positioner,
            Free::Tilt(_) => Variable::Tilt,
            Free::Configuration(per) => Variable::Configuration(*per),
        }
    }

    /// Its name as `--free` gives it: `tool-rotation`, `lead-tilt`, `station`, `positioner`,
    /// `tilt` or `configuration`.
    pub fn name(&self) -> &'static str {
        match self {
            Free::ToolRotation(_) => "tool-rotation",
            Free::LeadTilt(_) => "lead-tilt",
            Free::Station(_) => "station",
            Free::Positioner(_) => "positioner",
            Free::Tilt(_) => "tilt",
            Free::Configuration(_) => "configuration",
        }
    }

    /// Whether it is an external axis: the station, the positioner or the tilt.
    pub(crate) fn is_external(&self) -> bool {
        matches!(self, Free::Station(_) | Free::Positioner(_) | Free::Tilt(_))
    }

    /// Whether it moves the tool axis: its rotation or its lead and tilt.
    pub(crate) fn is_tool_axis(&self) -> bool {
        matches!(self, Free::ToolRotation(_) | Free::LeadTilt(_))
    }

    /// Whether `self` and `other` move the same variable (the configuration whatever its
    /// scope).
    pub(crate) fn same_variable(&self, other: &Free) -> bool {
        std::mem::discriminant(self) == std::mem::discriminant(other)
    }

    /// Checks its range and step as [`FreeRange::checked`] and [`LeadTilt::checked`] give them.
    ///
    /// # Errors
    /// Those of [`FreeRange::checked`] and [`LeadTilt::checked`].
    pub(crate) fn validate(&self) -> Result<()> {
        let variable = self.variable();
        let s = variable.scale();
        match self {
            Free::ToolRotation(f) | Free::Station(f) | Free::Positioner(f) | Free::Tilt(f) => {
                FreeRange::checked(&variable, f.range / s, f.step / s).map(|_| ())
            }
            Free::LeadTilt(l) => {
                LeadTilt::checked(l.cone.map(f64::to_degrees), l.step.to_degrees()).map(|_| ())
            }
            Free::Configuration(_) => Ok(()),
        }
    }
}

/// What a compensation may move from the path's own values at every point, and what it
/// minimises: the free variables ([`Free`], at most one of each; none by default: the path's
/// own values) and their one objective.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FreeVariables {
    /// The free variables, at most one of each ([`FreeVariables::validate`]).
    pub free: Vec<Free>,
    /// What a point costs.
    pub minimise: Objective,
    /// How the points' costs add up along the path.
    pub aggregate: Aggregate,
}

/// A free variable's limits in the units of the command line (deg, mm for the station).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// The largest half range.
    pub max_range: f64,
    /// The smallest step (exclusive when 0: any step > 0).
    pub min_step: f64,
    /// The largest step; `None`: the range.
    pub max_step: Option<f64>,
    /// The default step.
    pub step: f64,
    /// The default half range; `None`: the range must be given (for the lead and tilt, a
    /// program's cones are its process file's).
    pub range: Option<f64>,
    /// The unit, `deg` or `mm`.
    pub unit: &'static str,
}

impl Variable {
    /// The variable's limits (an axis name resolves to the station, the positioner or the tilt
    /// first, [`super::Freedom::apply`]; the configuration has no range).
    pub fn limits(&self) -> Limits {
        let deg = |max_range, min_step, max_step, step, range| Limits {
            max_range,
            min_step,
            max_step,
            step,
            range,
            unit: "deg",
        };
        match self {
            Variable::ToolRotation => deg(180.0, 0.0, Some(90.0), 2.0, Some(90.0)),
            Variable::LeadTilt => deg(LEAD_TILT_MAX_CONE_DEG, 0.1, None, 2.0, None),
            Variable::Station => Limits {
                unit: "mm",
                ..deg(20_000.0, 0.1, None, 10.0, None)
            },
            _ => deg(360.0, 0.01, None, 5.0, None),
        }
    }

    /// The options that name this variable's range and step in an error.
    fn options(&self) -> [JobOption; 2] {
        match self {
            Variable::ToolRotation => [JobOption::ToolRotationRange, JobOption::ToolRotationStep],
            Variable::LeadTilt => [JobOption::LeadTiltRange, JobOption::LeadTiltStep],
            Variable::Station => [JobOption::StationRange, JobOption::StationStep],
            Variable::Tilt => [JobOption::TiltRange, JobOption::TiltStep],
            _ => [JobOption::PositionerRange, JobOption::PositionerStep],
        }
    }

    /// SI units per unit of the command line.
    fn scale(&self) -> f64 {
        match self {
            Variable::Station => 1e-3,
            _ => 1f64.to_radians(),
        }
    }
}

/// The largest cone's half angle of the lead and tilt, deg: of `--free lead-tilt=-CONE..CONE` and
/// of a process file's `[tool_axis] cone_deg`.
pub(crate) const LEAD_TILT_MAX_CONE_DEG: f64 = 30.0;

/// The most grid cells (states x path points) a free variable's optimisation may visit: each is
/// one inverse kinematics solution kept in memory (about 70 bytes), so at most about 0.4 GB.
pub(crate) const MAX_GRID_CELLS: f64 = 5e6;

/// The most path points a free configuration evaluates (every configuration holds the whole
/// path).
pub(crate) const MAX_CONFIGURATION_POINTS: usize = 100_000;

/// Random starts of inverse kinematics that look for the configurations of the first point.
pub(crate) const CONFIGURATION_SEEDS: usize = 128;

impl FreeRange {
    /// The range and step of `variable` from the units of the command line (`range`: the half
    /// range; `step`: the step), checked against [`Variable::limits`].
    ///
    /// # Errors
    /// [`Error::InvalidOption`] naming the variable's range or step option with the value given
    /// and the limits.
    pub fn checked(variable: &Variable, range: f64, step: f64) -> Result<Self> {
        let l = variable.limits();
        let [range_option, step_option] = variable.options();
        check_range(l, range, range_option)?;
        check_step(l, step, Some(range), variable.scale(), step_option)?;
        Ok(FreeRange {
            range: range * variable.scale(),
            step: step * variable.scale(),
        })
    }

    /// The offsets from the path's own value (rad or m), ascending, `0` among them:
    /// `k step` for `|k| <= floor(range / step)`.
    pub(super) fn offsets(&self) -> Vec<f64> {
        offsets(self.range, self.step)
    }

    /// The rotation grid's spacing: `step` divided into whole cells of at most 5 deg, and the
    /// number of cells one step may move.
    pub(crate) fn cells(&self) -> (f64, usize) {
        let cells = (self.step / 5f64.to_radians()).ceil().max(1.0);
        (self.step / cells, cells as usize)
    }

    /// The rotation grid's angles, rad, ascending, `0` among them: `2 floor(range / spacing) +
    /// 1` ([`FreeRange::cells`]).
    pub(crate) fn angles(&self) -> Vec<f64> {
        offsets(self.range, self.cells().0)
    }

    /// The number of the rotation grid's angles, as a float (it may be astronomically large for
    /// a tiny step).
    pub(crate) fn angle_count(&self) -> f64 {
        2.0 * (self.range / self.cells().0 + 1e-9).floor() + 1.0
    }

    /// Checks that the rotation grid of a path of `points` points stays within
    /// [`MAX_GRID_CELLS`].
    ///
    /// # Errors
    /// [`Error::InvalidOption`] ([`JobOption::ToolRotationStep`]) with the grid's size and what to
    /// change.
    pub(super) fn check_rotation_grid(&self, points: usize) -> Result<()> {
        let angles = self.angle_count();
        let cells = angles * points as f64;
        if cells <= MAX_GRID_CELLS {
            return Ok(());
        }
        Err(Error::InvalidOption {
            option: JobOption::ToolRotationStep,
            message: format!(
                "{} deg with a range of +-{} deg makes a grid of {angles:.3e} angles x {points} path points = {cells:.3e} cells; at most {MAX_GRID_CELLS:.0e} (a larger step, a smaller range or a shorter path)",
                number(self.step.to_degrees()),
                number(self.range.to_degrees()),
            ),
        })
    }
}

impl LeadTilt {
    /// The lead and tilt from the cone's half angle (`None`: the process file's) and the step in
    /// the units of the command line (deg), checked against [`Variable::limits`].
    ///
    /// # Errors
    /// [`Error::InvalidOption`] ([`JobOption::LeadTiltRange`], [`JobOption::LeadTiltStep`]) with
    /// the value given.
    pub fn checked(cone_deg: Option<f64>, step_deg: f64) -> Result<Self> {
        let variable = Variable::LeadTilt;
        let l = variable.limits();
        if let Some(c) = cone_deg {
            check_range(l, c, JobOption::LeadTiltRange)?;
        }
        check_step(
            l,
            step_deg,
            cone_deg,
            variable.scale(),
            JobOption::LeadTiltStep,
        )?;
        Ok(LeadTilt {
            cone: cone_deg.map(f64::to_radians),
            step: step_deg.to_radians(),
        })
    }
}

/// `k step` for `|k| <= floor(range / step)`, ascending.
pub(super) fn offsets(range: f64, step: f64) -> Vec<f64> {
    let half = (range / step + 1e-9).floor() as isize;
    (-half..=half).map(|k| k as f64 * step).collect()
}

/// A half range within `(0, l.max_range]` and at least the smallest step.
fn check_range(l: Limits, range: f64, option: JobOption) -> Result<()> {
    let refuse = |message| Err(Error::InvalidOption { option, message });
    if !(range > 0.0 && range <= l.max_range) {
        return refuse(format!(
            "{}: expected a number > 0 and <= {} ({})",
            number(range),
            number(l.max_range),
            l.unit
        ));
    }
    if range < l.min_step {
        return refuse(format!(
            "{}: below the smallest step, {} {}: the range would hold no value but the path's own",
            number(range),
            number(l.min_step),
            l.unit
        ));
    }
    Ok(())
}

/// A step at least `l.min_step` (> 0, normal in SI) and at most `l.max_step`, else the range
/// (`range`; without one, the largest range).
fn check_step(
    l: Limits,
    step: f64,
    range: Option<f64>,
    scale: f64,
    option: JobOption,
) -> Result<()> {
    let most = l.max_step.or(range).unwrap_or(l.max_range);
    // A subnormal step in SI (5e-324 deg) is zero in every computation: refused as <= 0.
    if (step * scale).is_normal() && step > 0.0 && step >= l.min_step && step <= most {
        return Ok(());
    }
    let least = match l.min_step {
        0.0 => "> 0".to_string(),
        m => format!(">= {}", number(m)),
    };
    let what = match (l.max_step, range) {
        (Some(_), _) => String::new(),
        (None, Some(_)) => " (the range)".into(),
        (None, None) => " (the largest range)".into(),
    };
    Err(Error::InvalidOption {
        option,
        message: format!(
            "{}: expected a number {least} and <= {}{what} ({})",
            number(step),
            number(most),
            l.unit
        ),
    })
}

/// The bounds of the free variable `$variant` of `self`, if free.
macro_rules! find {
    ($self:ident, $variant:ident) => {
        $self.free.iter().find_map(|f| match f {
            Free::$variant(v) => Some(*v),
            _ => None,
        })
    };
}

impl FreeVariables {
    /// The free variables `free` minimising `minimise`, their costs added up by `aggregate`.
    pub(crate) fn new(free: Vec<Free>, minimise: Objective, aggregate: Aggregate) -> Self {
        FreeVariables {
            free,
            minimise,
            aggregate,
        }
    }

    /// The rotation about the tool z axis (module docs of [`super`], "The free tool axis"), if
    /// free.
    pub fn tool_rotation(&self) -> Option<FreeRange> {
        find!(self, ToolRotation)
    }

    /// The lead and tilt of the tool axis ("Lead and tilt"), if free.
    pub fn lead_tilt(&self) -> Option<LeadTilt> {
        find!(self, LeadTilt)
    }

    /// The track station, m ("The free station"), if free.
    pub(crate) fn station(&self) -> Option<FreeRange> {
        find!(self, Station)
    }

    /// The positioner's last axis, the table's turn ("The free positioner"), if free.
    pub(crate) fn positioner(&self) -> Option<FreeRange> {
        find!(self, Positioner)
    }

    /// A two-axis positioner's first axis, the tilt, if free.
    pub(crate) fn tilt(&self) -> Option<FreeRange> {
        find!(self, Tilt)
    }

    /// The configuration of the arm, one per program or per run ([`Scope`]), if free.
    pub fn configuration(&self) -> Option<Scope> {
        find!(self, Configuration)
    }

    /// Frees `free`: in place of the same variable if free, else after the others.
    pub fn set(&mut self, free: Free) {
        match self.free.iter_mut().find(|f| f.same_variable(&free)) {
            Some(f) => *f = free,
            None => self.free.push(free),
        }
    }

    /// The same with only the free variables `keep` keeps.
    pub fn keeping(&self, keep: impl Fn(&Free) -> bool) -> Self {
        FreeVariables {
            free: self.free.iter().copied().filter(|f| keep(f)).collect(),
            ..self.clone()
        }
    }

    /// Whether an external axis is free: the station, the positioner or the tilt.
    pub fn frees_external(&self) -> bool {
        self.free.iter().any(Free::is_external)
    }

    /// Whether the tool axis is free: its rotation or its lead and tilt.
    pub(crate) fn frees_tool_axis(&self) -> bool {
        self.free.iter().any(Free::is_tool_axis)
    }

    /// Whether anything is free.
    pub fn any(&self) -> bool {
        !self.free.is_empty()
    }

    /// Checks every variable, that none is given twice, and the
    /// objective: the surge only for the tool rotation alone (a drilling exit's, whose axis is
    /// the hole's).
    ///
    /// # Errors
    /// Those of `Free::validate`; [`Error::InvalidOption`] ([`JobOption::Free`]) for a
    /// variable given twice, ([`JobOption::Minimise`]) for the surge with another free
    /// variable.
    pub fn validate(&self) -> Result<()> {
        for (i, f) in self.free.iter().enumerate() {
            f.validate()?;
            if self.free[..i].iter().any(|g| g.same_variable(f)) {
                return Err(Error::InvalidOption {
                    option: JobOption::Free,
                    message: format!("{}: given twice: at most one of each variable", f.name()),
                });
            }
        }
        let others = self
            .free
            .iter()
            .any(|f| !matches!(f, Free::ToolRotation(_)));
        if self.minimise == Objective::Surge && others {
            return Err(Error::InvalidOption {
                option: JobOption::Minimise,
                message: "surge: the surge is a drilling exit's, chosen by the tool rotation alone; the station, the positioner axes, the lead and tilt and the configuration minimise the deflection or the bound".into(),
            });
        }
        Ok(())
    }
}
