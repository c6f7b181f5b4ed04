//! The joint error maps of a calibration ([`crate::calibration::maps`]): the choice by
//! cross-validation inside the fitted readings, its nested held-out gain, and the fit with the
//! maps chosen.
//!
//! The choice is made once, on every posture at the first fit assessed (a ladder's first gravity
//! model), with its nested figure around it; a ladder's later gravity models keep both (the maps
//! chosen on every posture, and each outer fold's maps and ridge), so the figure of a rung scores
//! the maps that rung fits; their ridge alone is chosen again at the fit of the model fitted.
//! Where `--maps auto` keeps no map on every posture, no nested figure is made: the model with
//! maps is the one without.

use crate::calibration::error_model::Observation;
use crate::calibration::fit::{self, Fit, Options};
use crate::calibration::maps::{self, Choice, JointMaps, Linear, Nested, Spec};
use crate::calibration::ErrorModel;
use nalgebra::Vector6;
use stiffid_core::common::error::JobOption;
use stiffid_core::{Error, Result};

/// The most work the maps' choice takes on: readings x (map coefficients)^2, the cost of its
/// cross-validated fits (about 4e-8 s of CPU each for the whole default calibration: the real
/// UR10's 2773 readings of series C, every joint's maps chosen, take 17 s of CPU; about 20 s at
/// this bound, half of it on two cores). `--maps auto` (up to 32 harmonics per joint, 384 coefficients) chooses maps on
/// up to 3390 readings; `--maps J1,J3:16` (64 coefficients) on up to 122 070.
pub(crate) const MAX_MAP_WORK: f64 = 5e8;

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

/// The maps of `spec` assessed at a fit: the report with the choice on every posture and its
/// nested held-out figure; or, when no map is considered, the report saying why (and for the
/// ladder the held-out errors without maps).
pub struct Assessed {
    /// What the maps' choice found.
    pub maps: Maps,
    /// Whether the choice was made at this fit; else at the first gravity model's, and the
    /// ridge of its maps is chosen again at this fit before they are fitted ([`fit_maps`]).
    pub own_fit: bool,
    /// The held-out errors of the outer folds, without maps and with them (without alone when
    /// no map is considered or `auto` keeps none): the ladder's; `None` when neither maps nor
    /// the ladder need them.
    pub nested: Option<Nested>,
}

/// Assesses the maps of `spec` on `model`'s fit `fitted` to `observations` (module docs): the
/// choice on every posture and its nested figure; with `ladder` the held-out errors without maps
/// too when no map is considered.
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::Maps`]) for fixed maps beyond [`MAX_MAP_WORK`] or a
/// backlash term without directions; those of [`Linear::at`], [`maps::choose`] and
/// [`maps::nested`].
pub(crate) fn assess(
    spec: Spec,
    (model, fitted): (&ErrorModel, &Fit),
    observations: &[Observation],
    options: &Options,
    ladder: bool,
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
    let candidates = match (&report.skipped, ladder) {
        (None, _) => candidates,
        (Some(_), true) => JointMaps::NONE,
        (Some(_), false) => {
            return Ok(Assessed {
                maps: report,
                own_fit: true,
                nested: None,
            })
        }
    };
    let linear = Linear::at(model, fitted, observations, options.length, candidates)?;
    if report.skipped.is_none() {
        report.choice = Some(maps::choose(&linear, &all, spec)?);
    }
    // Where `auto` keeps no map on every posture, the model with maps is the one without.
    let outer = match (&report.choice, spec) {
        (Some(c), Spec::Auto) if !c.maps.is_none() => spec,
        (Some(_), Spec::Fixed(_)) => spec,
        _ => Spec::None,
    };
    let nested = maps::nested(&linear, &all, outer)?;
    if outer != Spec::None {
        report.nested = Some(nested.clone());
    }
    Ok(Assessed {
        maps: report,
        own_fit: true,
        nested: Some(nested),
    })
}

/// [`assess`] for the ladder's later gravity models: the first gravity model's assessment
/// `first` kept, its choice on every posture and the nested figure of the maps and ridge each of
/// its outer folds chose ([`Nested::choices`], [`Nested::ridges`]; [`maps::nested_given`]): the
/// maps chosen once on the ladder.
///
/// # Errors
/// Those of [`Linear::at`] and [`maps::nested_given`].
pub(crate) fn assess_given(
    (model, fitted): (&ErrorModel, &Fit),
    observations: &[Observation],
    options: &Options,
    first: &Assessed,
) -> Result<Assessed> {
    let all: Vec<usize> = (0..first.maps.postures).collect();
    let Some(first_nested) = &first.nested else {
        return Ok(Assessed {
            maps: first.maps.clone(),
            own_fit: false,
            nested: None,
        });
    };
    let candidates = (first_nested.choices.iter()).fold(JointMaps::NONE, |a, c| a.union(c));
    let linear = Linear::at(model, fitted, observations, options.length, candidates)?;
    let nested = maps::nested_given(&linear, &all, first_nested)?;
    let maps = Maps {
        nested: first.maps.nested.as_ref().map(|_| nested.clone()),
        ..first.maps.clone()
    };
    Ok(Assessed {
        maps,
        own_fit: false,
        nested: Some(nested),
    })
}

/// Whether `auto` chose no map on every posture ([`assess`]): the model with maps is the one
/// without.
pub(crate) fn keeps_none(maps: &Maps) -> bool {
    maps.spec == Spec::Auto && maps.choice.as_ref().is_some_and(|c| c.maps.is_none())
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
        "{readings} readings x {coefficients}^2 map coefficients = {work:.3e}, more than the {MAX_MAP_WORK:.0e} on which maps are chosen in about 20 s of CPU"
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
/// posture (the assessment's) fitted from the calibration's start ([`fit::start`]) with the chosen
/// ridge, chosen again at `fitted` where the maps were chosen at another fit (what the readings
/// determine analysed where `fitted` analysed it).
///
/// # Errors
/// Those of [`ErrorModel::with_maps`], [`Linear::at`], [`maps::choose`], [`fit::start`] and
/// [`fit::fit`].
pub fn fit_maps(
    assessed: Assessed,
    keep: std::result::Result<(), String>,
    (model, fitted): (ErrorModel, Fit),
    observations: &[Observation],
    options: Options,
) -> Result<(ErrorModel, Fit, Options, Maps)> {
    let Assessed {
        maps: mut report,
        own_fit,
        ..
    } = assessed;
    if let Err(why) = keep {
        report.skipped = report.skipped.or(Some(why));
        report.choice = None;
    }
    let Some(choice) = report.choice.as_ref() else {
        return Ok((model, fitted, options, report));
    };
    let chosen = choice.maps;
    if chosen.is_none() {
        return Ok((model, fitted, options, report));
    }
    let ridge = match own_fit {
        true => choice.ridge,
        false => {
            let linear = Linear::at(&model, &fitted, observations, options.length, chosen)?;
            let all: Vec<usize> = (0..report.postures).collect();
            let again = maps::choose(&linear, &all, Spec::Fixed(chosen))?;
            if let Some(c) = report.choice.as_mut() {
                c.ridge = again.ridge;
            }
            again.ridge
        }
    };
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
