//! The setup file's `[noise]` table: the tracker's reading noise, and the old `variance_mm2`
//! read with a note of what it meant.

use crate::common::limits;
use crate::common::warning::{Warning, WarningKind};
use crate::{Error, Result};
use serde::Deserialize;

/// `[noise]`: the standard deviation of one coordinate of one tracker reading (or the old
/// variance), and the levels of a noise study.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct NoiseFile {
    reading_sd_mm: Option<f64>,
    variance_mm2: Option<f64>,
    /// Optional: `[1.0]`, the reading noise as given ([`super::Noise::one_level`]).
    #[serde(default = "super::Noise::one_level")]
    pub(super) level_multiples: Vec<f64>,
}

impl NoiseFile {
    /// The variance of one coordinate of one reading, m^2, and the note of the old
    /// `variance_mm2` (what it meant: one displacement coordinate, or with load steps one
    /// reading's), `steps` whether the setup has `[loading] steps_n`.
    pub(super) fn reading_variance(&self, steps: bool) -> Result<(f64, Option<Warning>)> {
        match (self.reading_sd_mm, self.variance_mm2) {
            (Some(sd), None) => {
                limits::check("noise.reading_sd_mm", &[sd], &limits::READING_SD_MM)?;
                let sd = sd * 1e-3;
                Ok((sd * sd, None))
            }
            (None, Some(v)) => {
                limits::check("noise.variance_mm2", &[v], &limits::VARIANCE_MM2)?;
                let (reading, meant, formula) = match steps {
                    false => (v / 2.0, "one coordinate of one displacement (a loaded minus an unloaded reading)", "sqrt(variance_mm2 / 2)"),
                    true => (v, "one coordinate of one reading (with loading.steps_n)", "sqrt(variance_mm2)"),
                };
                let note = Warning::new(
                    WarningKind::OldField,
                    format!(
                        "noise.variance_mm2 = {v} is the old noise field, the variance of {meant}: read as reading_sd_mm = {formula} = {:.6} mm, the standard deviation of one coordinate of one tracker reading; write reading_sd_mm instead",
                        reading.sqrt()
                    ),
                );
                Ok((reading * 1e-6, Some(note)))
            }
            (Some(_), Some(_)) => Err(Error::InvalidField {
                field: "noise.variance_mm2".into(),
                message: "expected reading_sd_mm or the old variance_mm2, not both".into(),
            }),
            (None, None) => Err(Error::InvalidField {
                field: "noise.reading_sd_mm".into(),
                message: "missing: expected the standard deviation of one coordinate of one tracker reading, mm".into(),
            }),
        }
    }
}
