//! The model-comparison job (`stiffid identify --compare-models`): from the setup's model, forward
//! selection of candidate virtual springs on the leave-one-posture-out error, nested in an outer
//! cross-validation ([`crate::identify::compare`]), on a measurement file or measurements given
//! as arrays.

use super::identify::{angle_warnings, on_measurements, Data};
use super::Warning;
use crate::identify::compare::{
    candidates_by_name, compare, default_candidates, Comparison, Document,
};
use crate::model::fragment;
use crate::{Result, Setup};
use std::io::Read;

/// What to compare.
pub struct Request<'a, R> {
    /// The setup: its model is where the selection starts, its tracker noise judges the fit.
    pub setup: &'a Setup,
    /// The measurements.
    pub data: Data<R>,
    /// The candidates by name ([`candidates_by_name`]: family springs such as `tilt3_x`, or
    /// whole families `tilt`, `tool`, `base`); `None` for the default, the `tilt` springs of
    /// joints 1-6 and the `tool` translations ([`default_candidates`]).
    pub candidates: Option<&'a [String]>,
}

/// What the comparison found.
#[derive(Debug, Clone)]
pub struct Report {
    /// The data's name (a file's, or `arrays`).
    pub data_name: String,
    /// The selection path, every step, the recommendation and the nested estimate.
    pub comparison: Comparison,
    /// The setup's tracker noise variance, m^2 (what the noise ratios are against).
    pub noise_variance: f64,
    /// Results to look at before trusting them (angles that look like radians).
    pub warnings: Vec<Warning>,
}

impl Report {
    /// The document (`stiffid identify --compare-models --json`), `setup` named as given.
    pub fn document(&self, setup: &str) -> Document {
        self.comparison
            .document(setup, &self.data_name, self.noise_variance)
    }

    /// The recommended model as a `[model]` fragment to paste into the setup, with a comment
    /// naming the data it was chosen on.
    pub fn fragment(&self) -> String {
        format!(
            "# The model `stiffid identify --compare-models` recommends for {}: paste into the setup.\n{}",
            self.data_name,
            fragment(&self.comparison.recommended_springs)
        )
    }
}

/// Runs the comparison, with the nested estimate.
///
/// # Errors
/// [`crate::Error::InvalidField`] (`candidates`) for an unknown candidate or none left; errors
/// about the data as [`crate::Error::Input`] naming the data (a file's line and column): those
/// of the measurement file's parser and of [`compare`].
pub fn run<R: Read>(request: Request<'_, R>) -> Result<Report> {
    let Request {
        setup,
        data,
        candidates,
    } = request;
    let candidates = match candidates {
        Some(names) => candidates_by_name(setup, names)?,
        None => default_candidates(setup),
    };
    let (data_name, origin, comparison) =
        on_measurements(setup, data, |m| compare(setup, m, &candidates, true))?;
    let warnings = angle_warnings(&data_name, &origin);
    Ok(Report {
        data_name,
        comparison,
        noise_variance: setup.noise().variance,
        warnings,
    })
}
