//! A calibration campaign over a track's stations: the arm's postures and the stations they are
//! read at designed together, for the calibration of the arm and the track from one campaign.
//!
//! One station cannot separate a track's direction and error motions from the tracker's
//! registration: the campaign reads postures at every station given (a grid over the travel,
//! [`stiffid_core::robot::ExternalAxes::stations`]), `n / S` at each (the first `n mod S`
//! stations one more). The criterion is the whole campaign's, on the error model with the
//! track's columns: the postures of station `k` are searched (the method asked for) on the arm
//! standing there in the fixed cell ([`Setup::at_station`]: the tracker's lines of sight, the
//! rope and the obstacles as they are from there), with the rows of the postures already chosen
//! at the other stations in the criterion ([`CalibrationDesign::on_station`]); a second pass
//! searches each station's postures again (a local search from where they are) with every other
//! station's fixed, so the first stations see the last.

use super::search::{choose, How, Searching};
use super::station::{setup_at, Station};
use crate::observability::{CalibrationCriterion, CalibrationDesign, Placed};
use crate::{CalibrationGoal, Criterion, Goal, Termination};
use nalgebra::Vector6;
use stiffid_core::common::error::JobOption;
use stiffid_core::robot::external::ExternalValues;
use stiffid_core::{Error, Result, Setup};

/// A campaign found over the stations.
#[derive(Debug, Clone)]
pub struct Campaign {
    /// The postures of each station (axis angles, rad), in the stations' order.
    pub groups: Vec<Vec<Vector6<f64>>>,
    /// Every posture with where it is read, station after station.
    pub placed: Vec<Placed>,
    /// The calibration criterion's loss of the whole campaign.
    pub value: f64,
    /// Each station with the campaign's value with the postures up to it.
    pub stations: Vec<Station>,
    /// Criterion evaluations of every search.
    pub evaluations: usize,
    /// The value minimised for the first search's start group.
    pub start_value: Option<f64>,
    /// Why the last search stopped.
    pub termination: Termination,
    /// Why every local search stopped, search after search.
    pub terminations: Vec<Termination>,
}

fn refuse(message: String) -> Error {
    Error::InvalidOption {
        option: JobOption::Station,
        message,
    }
}

/// Refuses a campaign of `n` postures over `stations` with fewer than two postures per station or
/// a station given twice.
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::Station`]).
pub fn check(n: usize, stations: &[ExternalValues]) -> Result<()> {
    let count = stations.len();
    if n < 2 * count {
        return Err(refuse(format!(
            "a calibration over {count} stations reads at least 2 postures at each: give at least {} postures, or fewer stations",
            2 * count
        )));
    }
    let repeated =
        (1..count).find_map(|k| (0..k).find(|&j| stations[j] == stations[k]).map(|j| (j, k)));
    match repeated {
        Some((j, k)) => Err(refuse(format!(
            "station {} repeats station {}: a campaign deals its postures over distinct stations",
            k + 1,
            j + 1
        ))),
        None => Ok(()),
    }
}

/// What a campaign is for: the calibration `design` on the whole setup (with the track's
/// columns), the calibration `criterion` minimised and the stiffness criterion of its goal.
#[derive(Clone, Copy)]
pub struct For<'a> {
    /// The calibration design of the setup.
    pub design: &'a CalibrationDesign,
    /// The calibration criterion minimised.
    pub criterion: CalibrationCriterion,
    /// The stiffness criterion of the searches' goal (unused by a calibration's loss).
    pub stiffness: Criterion,
}

/// The campaign of `n` postures of `setup` over `stations` (module docs; [`check`]ed before),
/// each station's first search `how` (a local search from its share of the start group, or
/// global).
///
/// # Errors
/// Those of the stations ([`setup_at`]), of [`CalibrationDesign::on_station`] and of the
/// searches (a group-size error said as one station's share); [`Error::Input`] (`calibration`)
/// for a campaign that does not separate the calibration's parameters.
pub fn campaign(
    setup: &Setup,
    goal: For,
    stations: &[ExternalValues],
    n: usize,
    how: How,
    s: Searching,
) -> Result<Campaign> {
    let count = stations.len();
    let blocks: Vec<usize> = (0..count)
        .map(|k| n / count + usize::from(k < n % count))
        .collect();
    let mut groups: Vec<Vec<Vector6<f64>>> = vec![Vec::new(); count];
    let (mut evaluations, mut terminations, mut start_value) = (0, Vec::new(), None);
    let mut termination = Termination::Converged;
    for pass in 0..2 {
        for k in 0..count {
            let offset: usize = blocks[..k].iter().sum();
            let start = match (pass, how) {
                (0, How::Local(start)) => start.map(|s| s[offset..offset + blocks[k]].to_vec()),
                (0, _) => None,
                _ => Some(groups[k].clone()),
            };
            let first = match (pass, how) {
                (0, How::Global) => How::Global,
                _ => How::Local(start.as_deref()),
            };
            let others = placed(&groups, stations, Some(k));
            let station = Here {
                k,
                at: &stations[k],
                size: blocks[k],
                n,
            };
            let found = search(setup, goal, station, &others, first, s)?;
            evaluations += found.evaluations;
            start_value = start_value.or(found.start_value);
            termination = found.termination;
            terminations.extend(found.terminations);
            groups[k] = found.postures;
        }
    }
    let all = placed(&groups, stations, None);
    let value = goal.design.value_placed(goal.criterion, &all);
    if !value.is_finite() {
        return Err(Error::Input {
            source_name: "postures: the campaign the search found".into(),
            error: Box::new(Error::InvalidField {
                field: "calibration".into(),
                message: format!(
                    "the {n} postures at {count} stations do not separate the calibration's {} parameters: choose more postures or stations",
                    goal.design.kept().len()
                ),
            }),
        });
    }
    let values = (0..count)
        .map(|k| Station {
            e: stations[k],
            value: (goal.design)
                .value_placed(goal.criterion, &placed(&groups[..=k], stations, None)),
        })
        .collect();
    Ok(Campaign {
        groups,
        placed: all,
        value,
        stations: values,
        evaluations,
        start_value,
        termination,
        terminations,
    })
}

/// The postures of `groups` read at `stations`, station `skip` left out.
fn placed(
    groups: &[Vec<Vector6<f64>>],
    stations: &[ExternalValues],
    skip: Option<usize>,
) -> Vec<Placed> {
    (groups.iter().zip(stations).enumerate())
        .filter(|(k, _)| Some(*k) != skip)
        .flat_map(|(_, (g, e))| g.iter().map(move |q| (*q, *e)))
        .collect()
}

/// Station `k` of a campaign of `n` postures: where it is and its share.
#[derive(Clone, Copy)]
struct Here<'a> {
    k: usize,
    at: &'a ExternalValues,
    size: usize,
    n: usize,
}

/// The postures of station `here` with the campaign's `others` fixed, searched `how`.
fn search(
    setup: &Setup,
    goal: For,
    here: Here,
    others: &[Placed],
    how: How,
    s: Searching,
) -> Result<crate::selection::search::Found> {
    let at = setup_at(setup, here.at)?;
    let design = goal.design.on_station(*here.at, others)?;
    let goal = Goal {
        stiffness: goal.stiffness,
        calibration: Some(CalibrationGoal {
            design: &design,
            criterion: goal.criterion,
            weight: 1.0,
        }),
    };
    choose(&at, &goal, how, here.size, s).map_err(|e| at_station(e, here))
}

/// A group-size error of station `here`'s search said as one station's share, not as the group
/// asked for.
fn at_station(e: Error, here: Here) -> Error {
    match e {
        Error::InvalidField { field, message } if field == "postures" => {
            let (size, n) = (here.size, here.n);
            let given = format!("{size} given: ");
            let why = message.strip_prefix(&given).unwrap_or(&message);
            Error::InvalidField {
                field,
                message: format!("station {}: {size} postures per station (the campaign deals its {n} postures over its stations): {why}; give more postures or fewer stations", here.k + 1),
            }
        }
        e => e,
    }
}
