//! The checks of [`Options`]: every field within its range, and the free variables minimising
//! one objective with one aggregate.

use super::options::{FreePositioner, FreeStation, FreeToolAxis, Objective, Options};
#[cfg(doc)]
use super::path;
use stiffid_core::common::error::JobOption;
use stiffid_core::common::words::number;
#[cfg(doc)]
use stiffid_core::robot::ik;
use stiffid_core::{common::limits, Error, Result};

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
    /// [`JobOption::FreeToolAxisObjective`]) and the feasibility's ([`super::Feasible::validate`]);
    /// ([`JobOption::Refine`]) for more than [`super::refine::MAX_LEVELS`] levels, or levels
    /// without a free variable whose grid they refine.
    pub fn validate(&self) -> Result<()> {
        limits::check(
            "compensate::Options.q0",
            self.q0.as_slice(),
            &limits::ANGLE_RAD,
        )?;
        self.ik.validate()?;
        stiffid_core::model::prediction::check_level("compensate::Options.level", self.level)?;
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
        super::refine::check(self.refine, 0, 0)?;
        let free = self.free_tool_axis.is_some() || self.free_lead_tilt.is_some();
        if self.refine > 0 && !(free || self.frees_external()) {
            return Err(Error::InvalidOption {
                option: JobOption::Refine,
                message: format!("{}: it refines the grid of a free variable (the tool axis, the station, the positioner, the tilt or the lead and tilt); none is free", self.refine),
            });
        }
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
                message: format!("{}: the free station, positioner axes, lead and tilt minimise the deflection or the bound, the same objective and aggregate as the free tool axis given with them", stiffid_core::common::choice::Choice::name(own.0)),
            });
        }
        Ok(())
    }

    /// A free configuration's objective not the surge ([`FreeConfiguration::check`]), one per
    /// run not with a map, and its objective and aggregate those of the other free variables
    /// given with it.
    fn validate_configuration(&self) -> Result<()> {
        let Some(c) = &self.free_configuration else {
            return Ok(());
        };
        c.check(0)?;
        if c.per == super::Scope::Run && self.map {
            return Err(Error::OptionCombination {
                option: JobOption::ConfigurationPer,
                with: vec![JobOption::Map],
                needs: false,
                reason: "run: a map is drawn over the whole program in one configuration".into(),
            });
        }
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
}
