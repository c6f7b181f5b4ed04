//! The model a calibration fits and its fit: the ladder of gravity models and maps climbed
//! ([`super::ladder`]), the maps chosen on every posture ([`super::maps`]), their range.

use super::{ladder, maps, update, Maps, Request};
use crate::app::in_data;
use stiffid_core::{Error, Result};
use stiffid_metrology::calibration::error_model::{MeasuredIn, Observation};
use stiffid_metrology::calibration::fit::{self, Fit, Options};
use stiffid_metrology::calibration::gravity::Gravity;
use stiffid_metrology::calibration::{model, motions, ErrorModel, Estimate, Geometry};

/// The model fitted and what chose it.
pub(super) struct Chosen {
    /// The joint errors fitted.
    pub geometry: Geometry,
    /// The error model (with its maps, their range, error motions and loads).
    pub model: ErrorModel,
    /// The fit's start.
    pub start: Estimate,
    /// The fit.
    pub fit: Fit,
    /// The fit's options (the maps' ridge among them).
    pub options: Options,
    /// The maps' choice.
    pub maps: Maps,
    /// The ladder, when the model was chosen.
    pub ladder: Option<ladder::Ladder>,
    /// With external axes: the error motions' choice.
    pub error_motions: Option<motions::Choice>,
}

/// The fit's options ([`Options::for_campaign`]): the setup's characteristic length, the
/// request's priors, the gravity terms bounded by the request's bound
/// ([`super::checks::gravity_bound`]), the same for every gravity model, chosen or given.
///
/// # Errors
/// Those of [`super::checks::gravity_bound`].
fn options(request: &Request<'_>) -> Result<Options> {
    let setup = request.readings.setup;
    Ok(Options::for_campaign(
        setup.characteristic_length().unwrap_or(1.0),
        request.priors.map(|t| (t.length, t.angle)),
        setup.noise().reading_sd(),
        super::checks::gravity_bound(request)?,
    ))
}

/// The model of `request` fitted to `obs` (in `measured_in`, with the cell's `tables`): the
/// ladder climbed, the maps chosen and fitted, their range set.
///
/// # Errors
/// Those of [`update::settings`], [`ladder::climb`] (the option's errors as they are, the
/// others as [`Error::Input`] naming the readings), [`maps::fit_maps`] and [`fit::start`].
pub(super) fn choose(
    request: &Request<'_>,
    (obs, measured_in, tables): (&[Observation], MeasuredIn, usize),
) -> Result<Chosen> {
    let setup = request.readings.setup;
    let name = &request.readings.name;
    let (geometry, gravity, maps_spec) = update::settings(request, setup, obs)?;
    let options = options(request)?;
    // The fits and the maps' choice report no count: each a stage of total 0 (a spinner).
    let progress = request.progress;
    progress.begin("fit", 0);
    let held = held_postures(request);
    let region = super::region::of(setup, obs, held.as_deref());
    let climbed = ladder::climb(
        (gravity, maps_spec),
        (setup.robot().masses().is_some(), !request.update),
        (obs, &region),
        &options,
        (
            |g| fitted(request, (obs, measured_in, tables), geometry, g, &options),
            // Readings that determine nothing are refused before any choice is fitted.
            |f: &ladder::Fitted| super::checks::refuse_repeated(setup, obs, &f.model, &f.fit),
        ),
    );
    progress.end();
    let climbed = climbed.map_err(|e| match e {
        // Too many maps for the readings is the option's error, not the data's.
        e @ (Error::InvalidOption { .. } | Error::Input { .. }) => e,
        e => in_data(name, e),
    })?;
    let ladder::Fitted {
        model,
        start,
        fit: fitted,
        error_motions,
    } = climbed.fitted;
    progress.begin("joint error maps", 0);
    let mapped = maps::fit_maps(
        climbed.assessed,
        climbed.keep,
        (model, fitted),
        obs,
        options,
    );
    progress.end();
    let (model, fit, options, maps) = mapped.map_err(|e| in_data(name, e))?;
    // The maps hold over the fitted postures' angles and taper to zero beyond them.
    let model =
        (model.with_map_ranges(super::extrapolation::ranges(obs))).map_err(|e| in_data(name, e))?;
    let start = match model.map_start() {
        Some(_) => fit::start(&model, obs).map_err(|e| in_data(name, e))?,
        None => start,
    };
    Ok(Chosen {
        geometry,
        model,
        start,
        fit,
        options,
        maps,
        ladder: climbed.ladder,
        error_motions,
    })
}

/// The axis angles (rad) of the held-out readings of `--validate` (table readings left out);
/// `None` without them or when they cannot be read (the validation says why).
fn held_postures(request: &Request<'_>) -> Option<Vec<nalgebra::Vector6<f64>>> {
    let (name, text) = request.validate.as_ref()?;
    let readings = crate::app::readings::Request {
        setup: request.readings.setup,
        setup_name: request.readings.setup_name.clone(),
        name: name.clone(),
        text,
        force: true,
    };
    let (data, _) = crate::app::readings::read(&readings).ok()?;
    Some(
        (data.readings.iter())
            .filter(|r| !r.table)
            .map(|r| r.q)
            .collect(),
    )
}

/// The calibration of `gravity` fitted to the readings `obs` (in `measured_in`, with the
/// cell's `tables`): the error model with its error motions and loads, its start and its fit,
/// the gravity terms bounded as `options` state, the same whether the ladder chose the gravity
/// model or the request gave it.
///
/// # Errors
/// Those of [`model`], [`update::kept`], [`ErrorModel::with_tables`], [`update::external`],
/// [`stiffid_metrology::calibration::motions::choose`], [`update::identifiable`],
/// [`ErrorModel::with_loads`], [`fit::start`] and [`fit::fit`];
/// [`Error::InvalidField`] (`readings`) for base-frame readings with external axes.
pub(super) fn fitted(
    request: &Request<'_>,
    (obs, measured_in, tables): (&[Observation], MeasuredIn, usize),
    geometry: Geometry,
    gravity: Gravity,
    options: &Options,
) -> Result<ladder::Fitted> {
    let setup = request.readings.setup;
    let name = &request.readings.name;
    let model = update::kept(request, model(setup, measured_in, geometry, gravity)?)?;
    let (model, error_motions) = match setup.robot().external() {
        None => (model.with_tables(tables)?, None),
        Some(_) if measured_in == MeasuredIn::Base => {
            return Err(Error::InvalidField {
                field: "readings".into(),
                message: "the readings are in the base frame (x_mm, y_mm, z_mm): with external axes the calibration registers the tracker to the cell, give the tracker's readings (x_tracker_mm, y_tracker_mm, z_tracker_mm)".into(),
            });
        }
        Some(_) if request.update => update::external(request, model, tables, name)?,
        Some(_) => {
            let chosen = stiffid_metrology::calibration::motions::choose(
                &model,
                tables,
                obs,
                options,
                request.error_motions,
            );
            let (model, _, choice) = chosen?;
            (model, Some(choice))
        }
    };
    update::identifiable(request, setup, &model, obs)?;
    let model = match obs.iter().any(Observation::loaded) {
        true => model.with_loads(setup)?,
        false => model,
    };
    let start = fit::start(&model, obs)?;
    let fit = fit::fit(&model, obs, &start, options)?;
    Ok(ladder::Fitted {
        model,
        start,
        fit,
        error_motions,
    })
}
