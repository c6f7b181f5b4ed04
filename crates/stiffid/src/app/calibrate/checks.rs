//! The checks of a calibrate request: before any fit, the level of the held-out readings'
//! intervals and the size of a cross-validation; after it, readings that determine nothing.

use super::{Request, MAX_CROSS_VALIDATION_POSTURES};
use stiffid_core::common::error::JobOption;
use stiffid_core::common::limits;
use stiffid_core::{Error, Result, Setup};
use stiffid_metrology::calibration::error_model::Observation;
use stiffid_metrology::calibration::fit::Fit;
use stiffid_metrology::calibration::ErrorModel;

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
            message: "only with --validate or --update (Python validate= or update=True): the level is that of the held-out readings' prediction intervals or of the check's bound".into(),
        }),
        (Some(l), _) => check_level("level", l)
            .map(|_| l)
            .map_err(|e| e.for_option(JobOption::Level)),
    }
}

/// The bound on the gravity terms `request` gives (rad), checked; `None` for the fit's default
/// ([`stiffid_metrology::calibration::fit::Options::for_campaign`]).
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::GravityBoundMrad`]) outside
/// [`limits::GRAVITY_BOUND_MRAD`].
pub(super) fn gravity_bound(request: &Request<'_>) -> Result<Option<f64>> {
    let Some(bound) = request.gravity_bound else {
        return Ok(None);
    };
    match limits::GRAVITY_BOUND_MRAD.contains(bound * 1e3) {
        true => Ok(Some(bound)),
        false => Err(Error::InvalidOption {
            option: JobOption::GravityBoundMrad,
            message: format!(
                "expected {}, got {}",
                limits::GRAVITY_BOUND_MRAD,
                stiffid_core::common::words::number(bound * 1e3)
            ),
        }),
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
                "at most {MAX_CROSS_VALIDATION_POSTURES} postures (one fold each), got {}: validate on a held-out file instead",
                postures.len()
            ),
        }),
        false => Ok(()),
    }
}

/// Refuses readings (`obs`, every reading as an observation) whose distinct postures
/// ([`stiffid_design::distinct`]) give no more coordinates than the fit has parameters (but the
/// maps' ridge-held ones): they would determine nothing. Checked after the first model's fit,
/// before the ladder's and the maps' choices, and again for the model chosen.
///
/// # Errors
/// [`Error::InvalidField`] (`readings`) naming the count of distinct postures, of readings, of
/// their coordinates and of the fitted parameters.
pub(super) fn refuse_repeated(
    setup: &Setup,
    obs: &[Observation],
    model: &ErrorModel,
    fit: &Fit,
) -> Result<()> {
    // The postures of the arm's points, grouped by their external axes' values: postures at two
    // stations of a track are distinct whatever their axis angles.
    let labels = obs.iter().map(|o| o.posture + 1).max().unwrap_or(0);
    let mut postures = vec![None; labels];
    for o in obs.iter().filter(|o| !o.table) {
        postures[o.posture].get_or_insert((o.q, &o.e));
    }
    let mut groups = std::collections::BTreeMap::<Vec<u64>, Vec<_>>::new();
    for (q, e) in postures.into_iter().flatten() {
        let key = e.as_slice().iter().map(|v| v.to_bits()).collect();
        groups.entry(key).or_default().push(q);
    }
    let distance = stiffid_design::distinct::Distinctness::default();
    let distinct: usize = (groups.values())
        .map(|postures| {
            let mut usable = vec![true; postures.len()];
            stiffid_design::distinct::distinct_pool(
                setup.robot(),
                postures,
                &mut usable,
                &distance,
            );
            usable.iter().filter(|&&u| u).count()
        })
        .sum();
    let tables = obs.iter().filter(|o| o.table).count();
    let coordinates = 3 * model.points() * distinct + 3 * tables;
    let fitted = (fit.fitted.iter()).filter(|&&i| model.map_start().is_none_or(|s| i < s));
    let fitted = fitted.count();
    if coordinates > fitted {
        return Ok(());
    }
    Err(Error::InvalidField {
        field: "readings".into(),
        message: format!(
            "{} readings of {distinct} distinct posture{} (postures closer than 2 deg in every axis, or 10 mm and 2 deg at the flange, count once) give {coordinates} coordinates for {} fitted parameters: the readings determine nothing the fit would not choose; read more distinct postures",
            obs.len(),
            if distinct == 1 { "" } else { "s" },
            fitted
        ),
    })
}

/// Refuses held-out readings of a reflector fixed in the cell (`T<k>`) that the fitted readings
/// `fitted` do not read: the calibration located no such reflector, so nothing predicts its
/// reading (the model fits the reflectors `T1` to `T<model.tables()>`).
///
/// # Errors
/// [`Error::Column`] (`point`) on the first such reading's line, naming the reflector and those
/// the fitted readings located.
pub(super) fn refuse_unfitted_reflectors(
    model: &ErrorModel,
    held: &stiffid_core::io::readings::Readings,
    fitted: &str,
) -> Result<()> {
    let fitted_count = model.tables();
    let Some((reading, line)) =
        (held.readings.iter().zip(&held.lines)).find(|(r, _)| r.table && r.point >= fitted_count)
    else {
        return Ok(());
    };
    let located = match fitted_count {
        0 => "none".to_string(),
        1 => "T1".to_string(),
        n => format!("T1 to T{n}"),
    };
    Err(Error::Column {
        line: *line,
        column: None,
        name: "point".into(),
        problem: stiffid_core::ColumnProblem::Measurement {
            message: format!(
                "reflector T{} is not read in the fitted readings {fitted}, which locate {located}: the calibration predicts a held-out reflector's reading from where the fitted readings put it; read it in the fitted readings too, or leave the row out",
                reading.point + 1
            ),
        },
    })
}
