//! The model-comparison job (`stiffid identify --compare-models`): from the setup's model, forward
//! selection of candidate virtual springs on the leave-one-posture-out error, nested in an outer
//! cross-validation ([`stiffid_identify::compare`]), and on request its posture bootstrap
//! ([`stiffid_identify::compare::bootstrap()`]), on a measurement file or measurements given as
//! arrays.

use crate::app::measurements::{angle_warnings, on_measurements, Data};
use crate::app::Warning;
use std::io::Read;
use stiffid_core::common::error::JobOption;
use stiffid_core::common::progress::Progress;
use stiffid_core::model::fragment;
use stiffid_core::{Error, Result, Setup};
use stiffid_identify::compare::{
    bootstrap, compare, default_pool, pool_by_name, Bootstrap, Comparison, Document, Dropped,
    Resampling,
};

/// What to compare.
pub(super) struct Request<'a, R> {
    /// The setup: its model is where the selection starts, its tracker noise judges the fit.
    pub setup: &'a Setup,
    /// The setup as the user named it ([`super::Request::setup_name`]).
    pub setup_name: String,
    /// The measurements.
    pub data: Data<R>,
    /// The candidates by name ([`pool_by_name`]: single candidates such as `tilt3_z`, `bend2_y`
    /// or a declared spring's name, or whole families `tilt`, `bend`, `base`, `tool`,
    /// `declared`); `None` for the default, every family and the setup's declared candidates
    /// ([`default_pool`]).
    pub candidates: Option<&'a [String]>,
    /// The posture bootstrap of the selection (`--bootstrap N --seed S`); `None` for none.
    pub bootstrap: Option<Resampling>,
    /// Where the bootstrap reports its resamples.
    pub progress: &'a dyn Progress,
}

/// What the comparison found.
#[derive(Debug, Clone)]
pub struct Report {
    /// The setup as the user named it ([`super::Request::setup_name`]).
    pub setup: String,
    /// The setup's tracker noise (SI).
    pub noise: stiffid_core::setup::Noise,
    /// The data's name (a file's, or `arrays`).
    pub data_name: String,
    /// Where each measurement came from.
    pub origin: crate::app::measurements::Origin,
    /// The virtual springs of the setup's model, then the candidates: parameter `j >= 6` of
    /// [`Comparison::parameters`] is `springs[j - 6]`.
    pub springs: Vec<stiffid_core::model::Spring>,
    /// The selection path, every step, the recommendation and the nested estimate.
    pub comparison: Comparison,
    /// The candidates left out because the data could never identify them, with the reason.
    pub dropped: Vec<Dropped>,
    /// The posture bootstrap, when asked for.
    pub bootstrap: Option<Bootstrap>,
    /// The setup's tracker noise variance, m^2 (what the noise ratios are against).
    pub noise_variance: f64,
    /// Results to look at before trusting them (angles that look like radians).
    pub warnings: Vec<Warning>,
}

impl Report {
    /// The document (`stiffid identify --compare-models --json`): a value of its own
    /// ([`stiffid_identify::compare::Comparison::document`]), built from the report.
    pub fn document(&self) -> Document {
        self.comparison.document(
            &self.setup,
            &self.data_name,
            self.noise_variance,
            &self.dropped,
            self.bootstrap.as_ref(),
        )
    }

    /// The stiffness file of `stiffid identify --compare-models --bootstrap N --stiffness-out`:
    /// the setup's model fitted to every posture, as `identify` writes it (the report of that
    /// fit, which is its document), with the models the data support and their resampled
    /// parameter sets (`model_form`, [`stiffid_core::io::stiffness::ModelFormSection`]); `None`
    /// without a bootstrap.
    pub fn stiffness_file(&self) -> Option<super::springs::Report> {
        let b = self.bootstrap.as_ref()?;
        Some(super::springs::Report {
            setup: self.setup.clone(),
            noise: self.noise.clone(),
            data_name: self.data_name.clone(),
            method: super::Fit::LeastSquares,
            fit: self.comparison.setup_fit.clone(),
            origin: self.origin.clone(),
            cross_validation: None,
            prediction: None,
            warnings: self.warnings.clone(),
            model_form: Some(super::model_form::section(
                b,
                &self.comparison,
                &self.springs,
            )),
        })
    }

    /// The text of the stiffness file of `stiffid identify --compare-models --bootstrap N
    /// --stiffness-out` and of Python's `identify(..., stiffness_out=...)`:
    /// [`Report::stiffness_file`] as pretty JSON ending in a line end, read back as `validate`,
    /// `predict` and `compensate` read it ([`super::check_stiffness_file`] against `setup`, its
    /// options as the front end `spell`s them) before anything is written; `None` without a
    /// bootstrap.
    ///
    /// # Errors
    /// Those of [`super::check_stiffness_file`].
    pub fn stiffness_file_text(
        &self,
        setup: &Setup,
        spell: &dyn Fn(JobOption) -> String,
    ) -> Result<Option<String>> {
        let Some(file) = self.stiffness_file() else {
            return Ok(None);
        };
        let text =
            serde_json::to_string_pretty(&file.document()).map_err(|e| Error::InvalidOption {
                option: JobOption::Out,
                message: format!("not written: {e}"),
            })? + "\n";
        super::check_stiffness_file(&text, setup, spell)?;
        Ok(Some(text))
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

/// Runs the comparison, with the nested estimate, and the bootstrap if asked.
///
/// # Errors
/// [`stiffid_core::Error::InvalidOption`] ([`stiffid_core::JobOption::Bootstrap`]) for a number of resamples
/// out of range ([`Resampling::check`]), ([`stiffid_core::JobOption::Candidates`]) for an unknown
/// candidate or none left; errors
/// about the data as [`stiffid_core::Error::Input`] naming the data (a file's line and column): those
/// of the measurement file's parser and of [`compare`].
pub(super) fn run<R: Read>(request: Request<'_, R>) -> Result<Report> {
    let Request {
        setup,
        setup_name,
        data,
        candidates,
        bootstrap: resampling,
        progress,
    } = request;
    if let Some(r) = &resampling {
        r.check()?;
    }
    let pool = match candidates {
        Some(names) => pool_by_name(setup, names)?,
        None => default_pool(setup),
    };
    let (data_name, origin, (comparison, bootstrap)) = on_measurements(setup, data, |m| {
        let c = compare(setup, m, &pool.candidates, true)?;
        let b = resampling
            .map(|r| bootstrap(setup, m, &pool.candidates, &c, r, progress))
            .transpose()?;
        Ok((c, b))
    })?;
    let warnings = angle_warnings(&data_name, &origin);
    Ok(Report {
        setup: setup_name,
        noise: setup.noise().clone(),
        springs: setup.model().with(&pool.candidates)?.springs().to_vec(),
        origin,
        data_name,
        comparison,
        dropped: pool.dropped,
        bootstrap,
        noise_variance: setup.noise().displacement_variance(),
        warnings,
    })
}
