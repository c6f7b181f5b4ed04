//! The compensate job's options as the front ends take them, in the units of the command's
//! options and Python's keywords (mm, percent, the free variables as parsed from their texts),
//! converted to the job's [`Options`] once, here: the command and Python fill a [`Given`] and
//! call [`Given::options`].

use nalgebra::Vector6;
use stiffid_core::{Result, Setup};
use stiffid_machining::compensate::{Freedom, MapVariable, Options};

/// The options of `stiffid compensate` and of Python's `stiffid.compensate` that shape the
/// compensation, as given.
#[derive(Debug, Clone, PartialEq)]
pub struct Given {
    /// Where inverse kinematics starts, axis angles, rad (`--q0-deg`, `q0_deg=`, read and
    /// checked by the front end); `None` for the setup's first test posture, else the middle of
    /// its bounds ([`Options::for_setup`]).
    pub q0: Option<Vector6<f64>>,
    /// The level of the error bound and of the deflection's prediction intervals (`--level`).
    pub level: f64,
    /// Refuse a path whose error bound exceeds this anywhere, mm (`--max-error-mm`).
    pub max_error_mm: Option<f64>,
    /// The process force model's relative error, percent (`--force-tolerance-pct`).
    pub force_tolerance_pct: f64,
    /// The map of a free variable (`--map`); `None` for no map.
    pub map: Option<MapVariable>,
    /// The free variables and what they minimise (`--free`, `--minimise`, `--objective`,
    /// `--margin-deg`, `--max-condition`, `--refine`).
    pub freedom: Freedom,
}

impl Given {
    /// The job's options: the setup's ([`Options::for_setup`]) with these, in SI.
    ///
    /// # Errors
    /// Those of [`Freedom::apply`] (a free variable the setup cannot move, an option without
    /// `--free`, a value outside its range).
    pub fn options(self, setup: &Setup) -> Result<Options> {
        let mut options = Options::for_setup(setup);
        options.level = self.level;
        options.force_tolerance = self.force_tolerance_pct / 100.0;
        options.max_error = self.max_error_mm.map(|m| m * 1e-3);
        options.map = self.map.is_some();
        options.map_over = self.map.unwrap_or_default();
        if let Some(q0) = self.q0 {
            options.q0 = q0;
        }
        self.freedom.apply(setup, &mut options)?;
        Ok(options)
    }
}
