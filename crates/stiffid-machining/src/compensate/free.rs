//! What a compensation may move, in one place: each free variable as given ([`FreeOption`]: the
//! variable, its range and its step) and the run's one objective ([`Freedom`]), parsed and checked
//! here for the command line (`--free tool-rotation=-90..90/5`) and Python
//! (`free=["tool-rotation=-90..90/5"]`) into [`FreeVariables`]. The grammar's one parser,
//! [`FreeOption::parse`], also reads `place --free` (`stiffid::app::place`).

use super::grammar::{self, invalid};
use super::options::Options;
use super::variables::{Aggregate, Free, FreeRange, FreeVariables, LeadTilt, Objective, Variable};
use super::Scope;
use stiffid_core::common::error::JobOption;
use stiffid_core::common::words::number;
use stiffid_core::robot::external::{ExternalAxes, Role};
use stiffid_core::{Error, Result, Setup};

/// One free variable as given: what moves, how far from the path's own value (`range`, `-range..range`)
/// and on which grid step (also the most it changes between consecutive points), in the units
/// of the command line: mm for the station, deg otherwise; `None` for the default.
#[derive(Debug, Clone, PartialEq)]
pub struct FreeOption {
    /// What moves.
    pub variable: Variable,
    /// The half range about the path's own value, mm or deg.
    pub range: Option<f64>,
    /// The grid step, mm or deg.
    pub step: Option<f64>,
}

/// The free variables of one run and what they minimise together: the options of
/// `compensate --free`, `--minimise`, `--objective`, `--margin-deg`, `--max-condition`,
/// `--refine` and of Python's keywords of the same names; `None` for the default.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Freedom {
    /// The free variables, at most one of each.
    pub free: Vec<FreeOption>,
    /// What a point costs; default the error bound the document reports.
    pub minimise: Option<Objective>,
    /// How the points' costs add up; default their sum.
    pub objective: Option<Aggregate>,
    /// The joint-limit margin of a moved posture, deg.
    pub margin_deg: Option<f64>,
    /// The largest condition number of a moved posture.
    pub max_condition: Option<f64>,
    /// Levels of refinement of the grid.
    pub refine: Option<usize>,
}

/// The most `--free` options of one run.
pub(crate) const MAX_FREE: usize = 8;

/// The options that `free` replaced (command-line spelling, without `--`), each with the option
/// that replaces it (`free` or `minimise`) and how to write its value there.
pub(crate) const RETIRED: &[(&str, &str, &str)] = &[
    ("free-tool-axis", "free", "tool-rotation=-90..90/2"),
    ("max-step-deg", "free", "tool-rotation=-R..R/STEP"),
    ("tool-axis-range-deg", "free", "tool-rotation=-R..R/STEP"),
    (
        "free-tool-axis-objective",
        "minimise",
        "deflection|surge|bound",
    ),
    ("free-station-mm", "free", "station=-R..R/STEP (mm)"),
    ("station-step-mm", "free", "station=-R..R/STEP (mm)"),
    ("free-positioner-deg", "free", "positioner=-R..R/STEP"),
    ("positioner-step-deg", "free", "positioner=-R..R/STEP"),
    ("free-tilt-deg", "free", "tilt=-R..R/STEP"),
    ("tilt-step-deg", "free", "tilt=-R..R/STEP"),
    (
        "free-lead-tilt",
        "free",
        "lead-tilt (a program's cone) or lead-tilt=-CONE..CONE/STEP",
    ),
    ("cone-deg", "free", "lead-tilt=-CONE..CONE/STEP"),
    ("lead-tilt-step-deg", "free", "lead-tilt=-CONE..CONE/STEP"),
    ("free-configuration", "free", "configuration"),
    ("configuration-per", "free", "configuration=run"),
];

/// The option replacing the retired option `name` (command-line spelling, without `--`) and how
/// to write its value (`RETIRED`).
pub fn retired(name: &str) -> Option<(&'static str, &'static str)> {
    RETIRED
        .iter()
        .find(|(n, _, _)| *n == name)
        .map(|(_, option, value)| (*option, *value))
}

impl FreeOption {
    /// Parses `NAME`, `NAME=LO..HI`, `NAME=LO..HI/STEP` or `NAME=/STEP` (`LO = -HI`: the range
    /// is symmetric about the path's own value), or `configuration=program|run`.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] ([`JobOption::Free`]) naming the text and what was expected.
    pub fn parse(text: &str) -> Result<Self> {
        let (name, value) = text.split_once('=').unwrap_or((text, ""));
        if name.trim() == "configuration" {
            let per = match value.trim() {
                "" | "program" => Scope::Program,
                "run" => Scope::Run,
                v => return Err(invalid(text, &format!("`{v}`: expected program or run"))),
            };
            return Ok(FreeOption::new(Variable::Configuration(per), None, None));
        }
        let parts = grammar::parts(text)?;
        let variable = match parts.name {
            "tool-rotation" => Variable::ToolRotation,
            "lead-tilt" => Variable::LeadTilt,
            "station" => Variable::Station,
            "positioner" => Variable::Positioner,
            "tilt" => Variable::Tilt,
            n => Variable::Axis(n.to_string()),
        };
        let half = match parts.range {
            None => None,
            Some([lo, hi]) if hi > 0.0 && lo == -hi => Some(hi),
            Some(_) => {
                let range = value.split('/').next().unwrap_or("").trim();
                return Err(invalid(
                    text,
                    &format!("`{range}`: expected a range -R..R about the path's own value, R > 0"),
                ));
            }
        };
        Ok(FreeOption::new(variable, half, parts.step))
    }

    /// The free variable `variable` (a name of [`FreeOption::parse`]) with its range and step: the
    /// parts of a Python dict (`{"variable": "station", "range": 500, "step": 10}`).
    ///
    /// # Errors
    /// Those of [`FreeOption::parse`].
    pub fn from_parts(variable: &str, range: Option<f64>, step: Option<f64>) -> Result<Self> {
        let free = FreeOption::parse(variable)?;
        if variable.contains('=') {
            return Err(invalid(variable, "expected a variable's name alone"));
        }
        let positive = |v: f64| v.is_finite() && v > 0.0;
        if let Some(r) = range.filter(|r| !positive(*r)) {
            return Err(invalid(
                variable,
                &format!("range {}: expected a number > 0", number(r)),
            ));
        }
        Ok(FreeOption {
            range,
            step,
            ..free
        })
    }

    fn new(variable: Variable, range: Option<f64>, step: Option<f64>) -> Self {
        FreeOption {
            variable,
            range,
            step,
        }
    }

    /// The variable with an axis name resolved against the cell's external axes.
    fn resolve(&self, axes: Option<&ExternalAxes>) -> Result<Variable> {
        let Variable::Axis(name) = &self.variable else {
            return Ok(self.variable.clone());
        };
        let all = axes.map_or(&[][..], |a| a.axes());
        let known = || -> String {
            let names: Vec<&str> = all.iter().map(|a| a.name.as_str()).collect();
            format!(
                "tool-rotation, lead-tilt, station, positioner, tilt, configuration{}{}",
                if names.is_empty() {
                    ""
                } else {
                    " or an axis of the cell: "
                },
                names.join(", ")
            )
        };
        let Some(i) = all.iter().position(|a| a.name == *name) else {
            return Err(invalid(
                name,
                &format!("unknown variable: expected {}", known()),
            ));
        };
        let positioner: Vec<usize> = (0..all.len())
            .filter(|&k| all[k].role == Role::Positioner)
            .collect();
        match all[i].role {
            Role::Carrier if i == 0 => Ok(Variable::Station),
            Role::Positioner if positioner.last() == Some(&i) => Ok(Variable::Positioner),
            Role::Positioner => Ok(Variable::Tilt),
            Role::Carrier => Err(invalid(
                name,
                "only the carrier's first axis (the station) is free",
            )),
        }
    }
}

impl Freedom {
    /// Sets the free variables of `options` ([`Options::free`]: all of them minimising
    /// [`Freedom::minimise`], their costs added up by [`Freedom::objective`]) and the
    /// feasibility and refinement they use, the axis names resolved against `setup`'s cell.
    /// Without a free variable, the options that only mean something with one are refused.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] ([`JobOption::Free`]) for more than 8 variables, one given twice or
    /// an unknown name; those of each variable's range and step ([`FreeRange::checked`],
    /// [`LeadTilt::checked`], [`FreeVariables::validate`]); [`Error::OptionCombination`] for
    /// `minimise`, `objective`, `margin_deg`, `max_condition` or `refine` without a free variable.
    pub fn apply(&self, setup: &Setup, options: &mut Options) -> Result<()> {
        self.check_alone()?;
        if self.free.len() > MAX_FREE {
            return Err(invalid(
                &format!("{} variables", self.free.len()),
                &format!("at most {MAX_FREE}"),
            ));
        }
        let mut free = FreeVariables::new(
            Vec::new(),
            self.minimise.unwrap_or_default(),
            self.objective.unwrap_or_default(),
        );
        let axes = setup.robot().external();
        let mut seen: Vec<Variable> = Vec::new();
        for given in &self.free {
            let variable = given.resolve(axes)?;
            let key = match &variable {
                Variable::Configuration(_) => Variable::Configuration(Scope::Program),
                v => v.clone(),
            };
            if seen.contains(&key) {
                return Err(invalid(
                    key.name(),
                    "given twice: at most one of each variable",
                ));
            }
            seen.push(key);
            free.free.push(bounds(&variable, given)?);
        }
        free.validate()?;
        options.free = free;
        if let Some(m) = self.margin_deg {
            options.feasible.margin = m.to_radians();
        }
        if let Some(c) = self.max_condition {
            options.feasible.max_condition = c;
        }
        options.refine = self.refine.unwrap_or(0);
        Ok(())
    }

    /// Refuses the options that only mean something with a free variable when none is given.
    fn check_alone(&self) -> Result<()> {
        if !self.free.is_empty() {
            return Ok(());
        }
        let given = [
            (self.minimise.is_some(), JobOption::Minimise),
            (self.objective.is_some(), JobOption::Objective),
            (self.margin_deg.is_some(), JobOption::MarginDeg),
            (self.max_condition.is_some(), JobOption::MaxCondition),
            (self.refine.is_some(), JobOption::Refine),
        ];
        match given.iter().find(|(g, _)| *g) {
            Some((_, option)) => Err(Error::OptionCombination {
                option: *option,
                with: vec![JobOption::Free],
                needs: true,
                reason: "it applies to the free variables; none is free".into(),
            }),
            None => Ok(()),
        }
    }
}

/// The free variable `variable` with the range and step of `given` (the variable's defaults
/// where it gives none, [`Variable::limits`]), checked.
fn bounds(variable: &Variable, given: &FreeOption) -> Result<Free> {
    let l = variable.limits();
    let step = given.step.unwrap_or(l.step);
    let range = || {
        given.range.or(l.range).ok_or_else(|| {
            let name = variable.name();
            invalid(
                name,
                &format!("expected its range, {name}=-R..R/STEP ({})", l.unit),
            )
        })
    };
    let checked = || FreeRange::checked(variable, range()?, step);
    Ok(match variable {
        Variable::ToolRotation => Free::ToolRotation(checked()?),
        Variable::Station => Free::Station(checked()?),
        Variable::Positioner => Free::Positioner(checked()?),
        Variable::Tilt => Free::Tilt(checked()?),
        Variable::LeadTilt => Free::LeadTilt(LeadTilt::checked(given.range, step)?),
        Variable::Configuration(per) => Free::Configuration(*per),
        Variable::Axis(name) => return Err(invalid(name, "unknown variable")),
    })
}
