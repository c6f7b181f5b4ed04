//! A calibration campaign over a track's stations: the arm's postures and the stations they are
//! read at designed together, for the calibration of the arm and the track from one campaign.
//!
//! One station cannot separate a track's direction and error motions from the tracker's
//! registration: the campaign reads postures at every requested station (a grid over the
//! travel, [`stiffid_core::robot::ExternalAxes::stations`]), `n / S` at each (the first `n mod S`
//! stations one more). The criterion is the whole campaign's, on the error model with the
//! track's columns ([`purpose::design`]): the postures of station `k` are searched (the
//! request's method) on the arm standing there in the fixed cell ([`stiffid_core::Setup::at_station`]:
//! the tracker's lines of sight, the rope and the obstacles as they are from there), with the
//! rows of the postures already chosen at the other stations in the criterion
//! ([`stiffid_design::observability::CalibrationDesign::on_station`]); a second pass searches
//! each station's postures again (a local search from where they are) with every other
//! station's fixed, so the first stations see the last.

use super::choose::{choose, Found};
use super::station::setup_at;
use super::{min_margins, size, CalibrationReport, Method, Report, Request, Station};
use crate::app::purpose::{self, Purpose};
use std::time::Instant;
use stiffid_core::common::error::JobOption;
use stiffid_core::{Error, Result};
use stiffid_design::distinct::{near_pairs_by, Near};
use stiffid_design::observability::{CalibrationDesign, Placed};
use stiffid_design::search::design_margin;
use stiffid_design::{evaluate, Termination};

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

/// The campaign of `r` (module docs).
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::Station`]) with a pool, a target or the candidates,
/// fewer than two postures per station, or a station given twice; the station's errors (as `select` at a station);
/// those of [`purpose::design`] and the searches; a campaign that does not separate the
/// calibration's parameters.
pub(super) fn campaign(r: &Request) -> Result<Report> {
    let (n, count) = (size(r), r.stations.len());
    let refuse = |message: String| Error::InvalidOption {
        option: JobOption::Station,
        message,
    };
    if r.method == Method::Pool || r.target_pct.is_some() || r.for_candidates {
        return Err(refuse("a calibration over several stations is searched (local or global): not with a pool, a target or the candidates".into()));
    }
    if n < 2 * count {
        return Err(refuse(format!(
            "a calibration over {count} stations reads at least 2 postures at each: give at least {} postures, or fewer stations",
            2 * count
        )));
    }
    let repeated = (1..count).find_map(|k| {
        (0..k)
            .find(|&j| r.stations[j] == r.stations[k])
            .map(|j| (j, k))
    });
    if let Some((j, k)) = repeated {
        return Err(refuse(format!(
            "station {} repeats station {}: a campaign deals its postures over distinct stations",
            k + 1,
            j + 1
        )));
    }
    let options = r.calibration.of(r.purpose);
    let design = purpose::design(r.setup, &options)?;
    let started = Instant::now();
    let blocks: Vec<usize> = (0..count)
        .map(|k| n / count + usize::from(k < n % count))
        .collect();
    let mut groups: Vec<Vec<nalgebra::Vector6<f64>>> = vec![Vec::new(); count];
    let (mut evaluations, mut terminations, mut start_value) = (0, Vec::new(), None);
    let mut termination = Termination::Converged;
    for pass in 0..2 {
        for k in 0..count {
            let offset: usize = blocks[..k].iter().sum();
            let start = match pass {
                0 => r
                    .start
                    .as_ref()
                    .map(|s| s[offset..offset + blocks[k]].to_vec()),
                _ => Some(groups[k].clone()),
            };
            let others = placed(r, &groups, Some(k));
            let found = search(r, &design, k, &others, start, blocks[k], pass)?;
            evaluations += found.evaluations;
            start_value = start_value.or(found.start_value);
            termination = found.termination;
            terminations.extend(found.terminations);
            groups[k] = found.postures;
        }
    }
    let all = placed(r, &groups, None);
    let criterion = options.criterion();
    let value = design.value_placed(criterion, &all);
    if !value.is_finite() {
        return Err(Error::Input {
            source_name: "postures: the campaign the search found".into(),
            error: Box::new(Error::InvalidField {
                field: "calibration".into(),
                message: format!(
                    "the {n} postures at {count} stations do not separate the calibration's {} parameters: choose more postures or stations",
                    design.kept().len()
                ),
            }),
        });
    }
    let mut stations = Vec::with_capacity(count);
    for k in 0..count {
        let upto: Vec<Placed> = placed(r, &groups[..=k], None);
        stations.push(Station {
            e: r.stations[k],
            value: design.value_placed(criterion, &upto),
        });
    }
    report(r, &design, groups, all, stations, value, started).map(|mut report| {
        report.evaluations = evaluations;
        report.start_value = start_value;
        report.termination = Some(termination);
        report.terminations = terminations;
        report
    })
}

/// The postures of `groups` read at the request's stations, station `skip` left out.
fn placed(r: &Request, groups: &[Vec<nalgebra::Vector6<f64>>], skip: Option<usize>) -> Vec<Placed> {
    (groups.iter().zip(&r.stations).enumerate())
        .filter(|(k, _)| Some(*k) != skip)
        .flat_map(|(_, (g, e))| g.iter().map(move |q| (*q, *e)))
        .collect()
}

/// The `size` postures of station `k` with the campaign's `others` fixed: the request's method
/// on the first pass (from `start`, the request's start group's share, if any), a local search
/// from `start` on the second.
fn search(
    r: &Request,
    design: &CalibrationDesign,
    k: usize,
    others: &[Placed],
    start: Option<Vec<nalgebra::Vector6<f64>>>,
    size: usize,
    pass: usize,
) -> Result<Found> {
    let setup = setup_at(r, &r.stations[k])?;
    let here = design.on_station(r.stations[k], others)?;
    let options = r.calibration.of(r.purpose);
    let goal = purpose::goal(r.purpose, r.criterion, Some(&here), &options);
    let sub = Request {
        setup: &setup,
        method: if pass == 0 { r.method } else { Method::Local },
        start,
        postures: size,
        stations: Vec::new(),
        ..r.clone()
    };
    choose(&sub, &goal, &setup, None, size).map_err(|e| at_station(e, k, size, self::size(r)))
}

/// A group-size error of station `k`'s search (`size` of the campaign's `n` postures) said as
/// one station's share, not as the group asked for.
fn at_station(e: Error, k: usize, size: usize, n: usize) -> Error {
    match e {
        Error::InvalidField { field, message } if field == "postures" => {
            let given = format!("{size} given: ");
            let why = message.strip_prefix(&given).unwrap_or(&message);
            Error::InvalidField {
                field,
                message: format!("station {}: {size} postures per station (the campaign deals its {n} postures over its stations): {why}; give more postures or fewer stations", k + 1),
            }
        }
        e => e,
    }
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
    let (mut near, mut margins, mut offset) = (Vec::new(), Vec::new(), 0);
    for (group, e) in groups.iter().zip(&r.stations) {
        let setup = setup_at(r, e)?;
        near.extend(
            near_pairs_by(setup.robot(), group, &distances)
                .into_iter()
                .map(|p| Near {
                    a: p.a + offset,
                    b: p.b + offset,
                    ..p
                }),
        );
        margins.extend(min_margins(&setup, r.options.margin, group));
        offset += group.len();
    }
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
        warnings: near.iter().map(Near::warning).collect(),
        station: None,
        stations,
        near,
        margin: design_margin(r.setup, r.options.margin),
        min_margins: margins,
        placed: all.iter().map(|p| p.1).collect(),
        postures,
        candidates: None,
    })
}
