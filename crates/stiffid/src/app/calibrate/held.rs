//! What a calibration is judged by: the leave-one-posture-out cross-validation, and the held-out
//! readings with their prediction intervals.

use super::checks::cross_validation_size;
use super::chosen::Chosen;
use super::{diverged, fit_bound, held_out, Bounds, Held, Request, MAX_CROSS_VALIDATION_POSTURES};
use crate::app::{in_data, Warning, WarningKind};
use stiffid_core::Result;
use stiffid_metrology::calibration::error_model::{MeasuredIn, Observation};
use stiffid_metrology::calibration::fit;
use stiffid_metrology::calibration::intervals::Intervals;
use stiffid_metrology::calibration::validation::{self, Validation};
use stiffid_metrology::calibration::ErrorModel;

/// The held-out validation (`validate`, with intervals from the fitted postures' folds when
/// they are at most [`MAX_CROSS_VALIDATION_POSTURES`]) and the cross-validation
/// (`cross_validate`) of the model `chosen` fitted to `obs`, beside the `nominal` errors
/// (`reference`), the fitted readings' `labels`, the intervals' `level`.
///
/// # Errors
/// Those of [`validation::cross_validate`], [`validation::leave_one_out_linearised`] (as
/// [`stiffid_core::Error::Input`] naming the readings) and [`held_out`].
pub(super) fn held(
    request: &Request<'_>,
    (chosen, reference, obs): (&Chosen, &ErrorModel, &[Observation]),
    (nominal, labels, level): (&Validation, &[String], f64),
    warnings: &mut Vec<Warning>,
) -> Result<(Option<Held>, Option<Held>)> {
    let name = &request.readings.name;
    let (model, fitted, options) = (&chosen.model, &chosen.fit, &chosen.options);
    let with_intervals = request.validate.is_some() && cross_validation_size(obs).is_ok();
    if request.validate.is_some() && !with_intervals {
        warnings.push(Warning::new(
            WarningKind::LeftOut,
            format!(
                "the held-out readings get no prediction intervals: they take one fold per fitted posture, at most {MAX_CROSS_VALIDATION_POSTURES}"
            ),
        ));
    }
    let cross_validation = match request.cross_validate {
        false => None,
        true => Some(Held {
            name: "cross-validation".into(),
            calibrated: without_lone_reflectors(
                validation::cross_validate(model, obs, fitted, options, request.progress)
                    .map_err(|e| in_data(name, e))?,
                obs,
                warnings,
            ),
            nominal: nominal.clone(),
            labels: labels.to_vec(),
            intervals: None,
            outside: Default::default(),
            coverage: None,
            from_fit: 0,
        }),
    };
    // The intervals' folds: linearised at the fit (with the maps' ridge rows).
    let folds =
        with_intervals.then(|| validation::leave_one_out_linearised(model, obs, fitted, options));
    let intervals = match folds {
        None => None,
        Some(f) => {
            // A fold that diverged says one posture holds up the fit, not how far a new
            // reading's error lies: left out of the intervals, saying so.
            let (f, warning) = diverged::kept(f.map_err(|e| in_data(name, e))?, labels);
            warnings.extend(warning);
            Some((Intervals::new(&f), fit_bound::held_out_variance(&f)))
        }
    };
    let validation = match &request.validate {
        None => None,
        Some((held_name, text)) => Some(held_out(
            request,
            (model, reference, obs),
            &fitted.estimate,
            intervals.as_ref().map(|(i, held)| Bounds {
                intervals: i,
                level,
                fit: fitted,
                held_variance: *held,
            }),
            held_name,
            text,
            warnings,
        )?),
    };
    Ok((validation, cross_validation))
}

/// The errors of the nominal `reference` on the held-out readings `held`, the tracker registered
/// on them; where their measured positions cannot register it (fewer than
/// [`stiffid_metrology::register::MIN_POINTS`] not on one line), registered on the fitted
/// readings `fitted` instead, saying so (a warning `left-out`).
///
/// # Errors
/// Those of [`fit::start`] and [`validation::validate`], naming the readings `name`.
pub(super) fn nominal(
    reference: &ErrorModel,
    (held, fitted): (&[Observation], &[Observation]),
    name: &str,
    warnings: &mut Vec<Warning>,
) -> Result<Validation> {
    let positions: Vec<_> = (held.iter().filter(|o| !o.table))
        .map(|o| o.measured)
        .collect();
    let registers = reference.measured_in() == MeasuredIn::Base
        || stiffid_metrology::register::rotation_std_per_noise(&positions).is_finite();
    if !registers {
        warnings.push(Warning::new(
            WarningKind::LeftOut,
            format!(
                "{name}: {} held-out position{} cannot register the tracker on the nominal robot (it takes {} not on one line): the nominal robot's errors there (nominal_rms_mm) are with the tracker registered on the fitted readings",
                positions.len(),
                if positions.len() == 1 { "" } else { "s" },
                stiffid_metrology::register::MIN_POINTS
            ),
        ));
    }
    let start = fit::start(reference, if registers { held } else { fitted })
        .map_err(|e| in_data(name, e))?;
    validation::validate(reference, &start, held).map_err(|e| in_data(name, e))
}

/// The cross-validation's errors `v` without those of a reflector fixed in the cell (`T<k>`) that
/// no other posture of `obs` reads: the fold holding out its only posture has no reading of it,
/// so its position there is the fit's start, not a prediction (errors of metres). A warning of
/// kind `left-out` names the reflectors left out.
fn without_lone_reflectors(
    v: Validation,
    obs: &[Observation],
    warnings: &mut Vec<Warning>,
) -> Validation {
    let mut postures: Vec<Vec<usize>> = Vec::new();
    for o in obs.iter().filter(|o| o.table) {
        if postures.len() <= o.point {
            postures.resize(o.point + 1, Vec::new());
        }
        if !postures[o.point].contains(&o.posture) {
            postures[o.point].push(o.posture);
        }
    }
    let lone: Vec<usize> = (0..postures.len())
        .filter(|&k| postures[k].len() == 1)
        .collect();
    if lone.is_empty() {
        return v;
    }
    let names: Vec<String> = lone.iter().map(|k| format!("T{}", k + 1)).collect();
    warnings.push(Warning::new(
        WarningKind::LeftOut,
        format!(
            "cross-validation: reflector{} {} read in one posture only: the fold that holds it out has no reading of {}, so nothing predicts {} there; left out of the cross-validation's errors (read each reflector beside two postures or more to cross-validate it)",
            if lone.len() == 1 { "" } else { "s" },
            names.join(", "),
            if lone.len() == 1 { "it" } else { "them" },
            if lone.len() == 1 { "its reading" } else { "their readings" },
        ),
    ));
    let kept = (v.errors.into_iter())
        .filter(|e| !(e.table && lone.contains(&e.point)))
        .collect();
    Validation::new(kept)
}
