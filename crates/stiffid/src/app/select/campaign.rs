//! A calibration campaign over a track's stations, as the request asks it: the arm's postures
//! and the stations they are read at designed together
//! ([`stiffid_design::selection::campaign`]), on the calibration design with the track's columns
//! ([`purpose::design`]).

use super::choose::{how, name, searching};
use super::station::setup_at;
use super::{size, CalibrationReport, Method, Report, Request, Station};
use crate::app::purpose::{self, Purpose};
use std::time::Instant;
use stiffid_core::common::error::JobOption;
use stiffid_core::{Error, Result};
use stiffid_design::distinct::Near;
use stiffid_design::evaluate;
use stiffid_design::observability::{CalibrationDesign, Placed};
use stiffid_design::selection::campaign::{self, For};
use stiffid_design::selection::search::in_cell;

/// Whether `r` designs a campaign over its stations: a calibration (`--for calibration`) on a
/// robot with a carrier, at two or more stations.
pub(super) fn is_campaign(r: &Request) -> bool {
    let carrier = r
        .setup
        .robot()
        .external()
        .is_some_and(|a| a.carrier_len() > 0);
    r.purpose == Purpose::Calibration && carrier && r.stations.len() > 1
}

/// The campaign of `r` ([`stiffid_design::selection::campaign`]).
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::Station`]) with a pool, a target or the candidates;
/// those of [`campaign::check`], [`purpose::design`] and [`campaign::campaign`].
pub(super) fn campaign(r: &Request) -> Result<Report> {
    if r.method == Method::Pool || r.target_pct.is_some() || r.for_candidates {
        return Err(Error::InvalidOption {
            option: JobOption::Station,
            message: "a calibration over several stations is searched (local or global): not with a pool, a target or the candidates".into(),
        });
    }
    campaign::check(size(r), &r.stations)?;
    let options = r.calibration.of(r.purpose);
    let design = purpose::design(r.setup, &options)?;
    let started = Instant::now();
    let goal = For {
        design: &design,
        criterion: options.criterion(),
        stiffness: r.criterion,
    };
    let named = purpose::goal(r.purpose, r.criterion, Some(&design), &options);
    let name = name(r, &named);
    let searching = searching(r, &name);
    let c = campaign::campaign(r.setup, goal, &r.stations, size(r), how(r, None), searching)?;
    report(r, &design, c.groups, c.placed, c.stations, c.value, started).map(|mut report| {
        report.evaluations = c.evaluations;
        report.start_value = c.start_value;
        report.termination = Some(c.termination);
        report.terminations = c.terminations;
        report
    })
}

/// The report of the campaign `groups` (one per station, `all` placed), its `value` and each
/// station's.
fn report(
    r: &Request,
    design: &CalibrationDesign,
    groups: Vec<Vec<nalgebra::Vector6<f64>>>,
    all: Vec<Placed>,
    stations: Vec<Station>,
    value: f64,
    started: Instant,
) -> Result<Report> {
    let distances = r.distinct.unwrap_or_default();
    // One group per station.
    let n = groups.len().min(r.stations.len());
    let (at, margin) = ((&groups[..n], &r.stations[..n]), r.options.margin);
    let held = in_cell(r.setup, at.0, at.1, margin, &distances)?;
    let options = r.calibration.of(r.purpose);
    let postures: Vec<nalgebra::Vector6<f64>> = all.iter().map(|p| p.0).collect();
    Ok(Report {
        method: r.method,
        criterion: r.criterion,
        purpose: r.purpose,
        calibration: Some(CalibrationReport {
            criterion: options.criterion(),
            options,
            criteria: design.evaluate_placed(&all)?,
            weight: 1.0,
        }),
        seed: r.options.seed,
        gradient: Some(r.options.gradient),
        solver: Some(
            purpose::goal(r.purpose, r.criterion, Some(design), &options).solver(r.options.solver),
        ),
        evaluation: evaluate(&setup_at(r, &r.stations[0])?, &postures),
        start_value: None,
        value,
        evaluations: 0,
        termination: None,
        terminations: Vec::new(),
        elapsed_s: started.elapsed().as_secs_f64(),
        pool: None,
        target: None,
        unconstrained: None,
        warnings: held.near.iter().map(Near::warning).collect(),
        station: None,
        stations,
        near: held.near,
        margin: held.margin,
        min_margins: held.min_margins,
        placed: all.iter().map(|p| p.1).collect(),
        postures,
        candidates: None,
        // Named by `run`.
        setup: String::new(),
        external_axes: None,
        out: None,
        report_dir: None,
    })
}
