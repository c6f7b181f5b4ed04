//! The checks of a calibrate request that come before any fit: the level of the held-out
//! readings' intervals and the size of a cross-validation.

use super::{Request, MAX_CROSS_VALIDATION_POSTURES};
use stiffid_core::common::error::JobOption;
use stiffid_core::{Error, Result};
use stiffid_metrology::calibration::error_model::Observation;

/// The level of the held-out readings' prediction intervals: `request.level`, else
/// [`stiffid_core::model::prediction::DEFAULT_LEVEL`].
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::Level`]) for a level outside
/// [`stiffid_core::model::prediction::LEVEL`], or one given without held-out readings or `update`.
pub(super) fn interval_level(request: &Request<'_>) -> Result<f64> {
    use stiffid_core::model::prediction::{check_level, DEFAULT_LEVEL};
    match (request.level, &request.validate) {
        (None, _) => Ok(DEFAULT_LEVEL),
        (Some(_), None) if !request.update => Err(Error::InvalidOption {
            option: JobOption::Level,
            message: "only with --validate or --update: the level is that of the held-out readings' prediction intervals or of the check's bound".into(),
        }),
        (Some(l), _) => check_level("level", l)
            .map(|_| l)
            .map_err(|e| e.for_option(JobOption::Level)),
    }
}

/// Refuses cross-validation beyond [`MAX_CROSS_VALIDATION_POSTURES`] postures, before any fit.
pub(super) fn cross_validation_size(obs: &[Observation]) -> Result<()> {
    let mut postures: Vec<usize> = obs.iter().map(|o| o.posture).collect();
    postures.dedup();
    match postures.len() > MAX_CROSS_VALIDATION_POSTURES {
        true => Err(Error::InvalidField {
            field: "cross_validate".into(),
            message: format!(
                "at most {MAX_CROSS_VALIDATION_POSTURES} postures (one fit each), got {}: validate on a held-out file instead",
                postures.len()
            ),
        }),
        false => Ok(()),
    }
}
