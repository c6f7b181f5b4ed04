//! The joint error maps of a calibration ([`crate::calibration::maps`]): the choice by
//! cross-validation inside the fitted readings, its nested held-out gain, and the fit with the
//! maps chosen.

use crate::calibration::error_model::Observation;
use crate::calibration::fit::{self, Fit, Options};
use crate::calibration::maps::{self, Choice, JointMaps, Linear, Nested, Spec};
use crate::calibration::ErrorModel;
use nalgebra::Vector6;
use stiffid_core::common::error::JobOption;
use stiffid_core::{Error, Result};

/// The most work the maps' choice takes on: readings x (map coefficients)^2, the cost of its
/// cross-validated fits (about 1.2e-7 s of CPU each: a minute of CPU at this bound, half of it
/// on two cores). `--maps auto` (up to 32 harmonics per joint, 384 coefficients) chooses maps on
/// up to 3390 readings; `--maps J1,J3:16` (64 coefficients) on up to 122 070.
pub const MAX_MAP_WORK: f64 = 5e8;

/// What the maps' choice found.
#[derive(Debug, Clone, PartialEq)]
pub struct Maps {
    /// What was asked.
    pub spec: Spec,
    /// The distinct postures of the fitted readings.
    pub postures: usize,
    /// The choice, when maps were considered.
    pub choice: Option<Choice>,
    /// Its held-out gain, when maps were considered.
    pub nested: Option<Nested>,
    /// Why no map was considered, when none was.
    pub skipped: Option<String>,
}

/// The maps of `spec` assessed at a fit: the report with the nested held-out figure (the choice
/// not yet made on every posture), and the linearised fit the choice is made on; or, when no map
/// is considered, the report saying why (and for the ladder the held-out errors without maps).
pub struct Assessed {
    /// What the maps' choice found so far.
    pub maps: Maps,
    /// The calibration linearised at the fit with the candidate maps' columns, when maps are
    /// considered.
    pub linear: Option<Linear>,
    /// The held-out errors of the outer folds, without maps and with them (without alone when
    /// no map is considered): the ladder's; `None` when neither maps nor the ladder need them.
    pub nested: Option<Nested>,
}

/// Assesses the maps of `spec` on `model`'s fit `fitted` to `observations` (module docs); with
/// `ladder` the held-out errors without maps too when no map is considered.
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::Maps`]) for fixed maps beyond [`MAX_MAP_WORK`] or a
/// backlash term without directions; those of [`Linear::at`] and [`maps::nested`].
pub(crate) fn assess(
    spec: Spec,
    model: &ErrorModel,
    fitted: &Fit,
    observations: &[Observation],
    options: &Options,
    ladder: bool,
) -> Result<Assessed> {
    assess_with(spec, (model, fitted), observations, options, ladder, None)
}

/// [`assess`] for the ladder's later gravity models: the nested figure of the maps each outer
/// fold of the first gravity model's assessment chose, with the ridge it chose (`first`,
/// [`Nested::choices`], [`Nested::ridges`]; [`maps::nested_given`]): the maps chosen once on
/// the ladder.
///
/// # Errors
/// Those of [`assess`] and [`maps::nested_given`].
pub(crate) fn assess_given(
    spec: Spec,
    (model, fitted): (&ErrorModel, &Fit),
    observations: &[Observation],
    options: &Options,
    first: &Nested,
) -> Result<Assessed> {
    assess_with(
        spec,
        (model, fitted),
        observations,
        options,
        true,
        Some(first),
    )
}

/// [`assess`], the outer folds' maps chosen anew or `given`.
fn assess_with(
    spec: Spec,
    (model, fitted): (&ErrorModel, &Fit),
    observations: &[Observation],
    options: &Options,
    ladder: bool,
    given: Option<&Nested>,
) -> Result<Assessed> {
    let mut postures: Vec<usize> = observations.iter().map(|o| o.posture).collect();
    postures.sort_unstable();
    postures.dedup();
    let mut report = Maps {
        spec,
        postures: postures.len(),
        choice: None,
        nested: None,
        skipped: None,
    };
    let directions = observations.iter().any(|o| o.direction != Vector6::zeros());
    let candidates = spec.candidates(directions);
    if candidates.any_backlash() && !directions {
        return Err(Error::InvalidOption {
            option: JobOption::Maps,
            message: format!(
                "{} asks for a backlash term: the readings carry no directions of approach (columns dir1..dir6)",
                maps::name(&candidates)
            ),
        });
    }
    report.skipped = skipped(spec, postures.len(), observations.len(), candidates)?;
    let all: Vec<usize> = (0..postures.len()).collect();
    let (candidates, considered) = match (&report.skipped, ladder) {
        (None, _) => (candidates, spec),
        (Some(_), true) => (JointMaps::NONE, Spec::None),
        (Some(_), false) => {
            return Ok(Assessed {
                maps: report,
                linear: None,
                nested: None,
            })
        }
    };
    let linear = Linear::at(model, fitted, observations, options.length, candidates)?;
    let nested = match given {
        Some(first) => maps::nested_given(&linear, &all, first)?,
        None => maps::nested(&linear, &all, considered)?,
    };
    if report.skipped.is_none() {
        report.nested = Some(nested.clone());
    }
    let linear = (report.skipped.is_none()).then_some(linear);
    Ok(Assessed {
        maps: report,
        linear,
        nested: Some(nested),
    })
}

/// Why no map is considered, if none is.
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::Maps`]) for fixed maps beyond [`MAX_MAP_WORK`].
fn skipped(
    spec: Spec,
    postures: usize,
    readings: usize,
    candidates: JointMaps,
) -> Result<Option<String>> {
    let coefficients = candidates.coefficients();
    let work = readings as f64 * (coefficients * coefficients) as f64;
    let over = format!(
        "{readings} readings x {coefficients}^2 map coefficients = {work:.3e}, more than the {MAX_MAP_WORK:.0e} on which maps are chosen in about a minute"
    );
    Ok(match spec {
        Spec::None => Some("--maps none".into()),
        Spec::Auto if postures < maps::MIN_POSTURES => Some(format!(
            "{postures} distinct postures, fewer than the {} with which maps are chosen",
            maps::MIN_POSTURES
        )),
        Spec::Auto if work > MAX_MAP_WORK => Some(format!(
            "{over}: give fewer joints or harmonics (--maps J2,J3:8) or fewer readings"
        )),
        Spec::Fixed(h) if work > MAX_MAP_WORK => {
            return Err(Error::InvalidOption {
                option: JobOption::Maps,
                message: format!(
                    "{}: {over}; give fewer joints or harmonics, or fewer readings",
                    maps::name(&h)
                ),
            })
        }
        _ => None,
    })
}

/// The model, fit and options after the maps `assessed` (`keep`: the maps are fitted, else none
/// is and `why` says why): those given without maps, else the model with the maps chosen on every
/// posture fitted from the calibration's start ([`fit::start`]) with the chosen ridge (what the
/// readings determine analysed where `fitted` analysed it).
///
/// # Errors
/// Those of [`ErrorModel::with_maps`], [`maps::choose`], [`fit::start`] and [`fit::fit`].
pub fn fit_maps(
    assessed: Assessed,
    keep: std::result::Result<(), String>,
    (model, fitted): (ErrorModel, Fit),
    observations: &[Observation],
    options: Options,
) -> Result<(ErrorModel, Fit, Options, Maps)> {
    let Assessed {
        maps: mut report,
        linear,
        ..
    } = assessed;
    if let Err(why) = keep {
        report.skipped = report.skipped.or(Some(why));
    }
    let Some(linear) = linear.filter(|_| report.skipped.is_none()) else {
        return Ok((model, fitted, options, report));
    };
    let all: Vec<usize> = (0..report.postures).collect();
    let choice = maps::choose(&linear, &all, report.spec)?;
    let chosen = choice.maps;
    let ridge = choice.ridge;
    report.choice = Some(choice);
    if chosen.is_none() {
        return Ok((model, fitted, options, report));
    }
    let mapped = model.clone().with_maps(chosen)?;
    // From the calibration's own start, not from the geometric fit: what the readings determine
    // is analysed where the geometric fit analysed it (at the fitted geometry, parallel axes
    // are parallel no more and their merged parameters would be fitted, drifting along a
    // valley), so the final fit fits the parameters the choice was made with.
    let start = fit::start(&mapped, observations)?;
    let with = Options { ridge, ..options };
    let fit_with = fit::fit(&mapped, observations, &start, &with)
        .and_then(|f| mapped.robot_at(&f.estimate.values).map(|_| f));
    // A fit whose maps leave their range (readings that do not determine them) is an error of
    // maps asked for; maps chosen by `auto` are dropped instead, saying why.
    match (report.spec, fit_with) {
        (Spec::Auto, Err(e)) => {
            report.skipped = Some(format!("the fit with the maps chosen failed: {e}"));
            report.choice = None;
            Ok((model, fitted, options, report))
        }
        (_, fit_with) => Ok((mapped, fit_with?, with, report)),
    }
}
