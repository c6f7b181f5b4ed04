//! The checks of [`Options`]: every field within its range, and the free variables minimising
//! one objective with one aggregate.

use super::options::Options;
#[cfg(doc)]
use super::path;
use stiffid_core::common::error::JobOption;
use stiffid_core::common::words::number;
#[cfg(doc)]
use stiffid_core::robot::ik;
use stiffid_core::{common::limits, Error, Result};

impl Options {
    /// Checks every field: `q0` within [`limits::ANGLE_RAD`] (finite), `ik`
    /// ([`ik::Options::validate`]), `max_iterations` 1 to [`super::MAX_ITERATIONS`], the free
    /// variables ([`super::FreeVariables::validate`]). [`path`] calls it.
    ///
    /// # Errors
    /// [`Error::InvalidField`] naming the field, the value and the range;
    /// [`Error::InvalidOption`] for the free variables' ranges, steps and objective
    /// ([`super::FreeVariables::validate`]) and the feasibility's;
    /// ([`JobOption::Refine`]) for more than 4 levels, or levels
    /// without a free variable whose grid they refine.
    pub fn validate(&self) -> Result<()> {
        limits::check(
            "compensate::Options.q0",
            self.q0.as_slice(),
            &limits::ANGLE_RAD,
        )?;
        self.ik.validate()?;
        stiffid_core::model::prediction::check_level("level", self.level)
            .map_err(|e| e.for_option(JobOption::Level))?;
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
                option: JobOption::ForceTolerancePct,
                message: format!(
                    "{}: expected 0 to 100 percent",
                    number(self.force_tolerance * 100.0)
                ),
            });
        }
        self.free.validate()?;
        self.validate_configuration()?;
        self.feasible.validate()?;
        super::refine::check(self.refine, 0, 0)?;
        let free = self.free.frees_tool_axis() || self.free.frees_external();
        if self.refine > 0 && !free {
            return Err(Error::InvalidOption {
                option: JobOption::Refine,
                message: format!("{}: it refines the grid of a free variable (the tool axis, the station, the positioner, the tilt or the lead and tilt); none is free", self.refine),
            });
        }
        Ok(())
    }

    /// One configuration per run not with a map.
    fn validate_configuration(&self) -> Result<()> {
        if self.free.configuration() == Some(super::Scope::Run) && self.map {
            return Err(Error::OptionCombination {
                option: JobOption::ConfigurationScope,
                with: vec![JobOption::Map],
                needs: false,
                reason: "run: a map is drawn over the whole program in one configuration".into(),
            });
        }
        Ok(())
    }
}
