//! Where a robot on a track (or with other external axes) stands for the group: the design runs
//! with the arm at each requested station in the fixed cell ([`Setup::at_station`]), and the
//! station whose group has the smallest minimised value is kept.
//!
//! The design criteria of the stiffness identification do not change when the arm moves along a
//! straight track (the observation matrix is the same in any translated frame), but what the cell
//! allows does: the rope's anchor and the tracker stay where they are, so the load's direction,
//! the lines of sight and the obstacles differ from station to station, and so does the best
//! feasible group.

use super::{Report, Request};
use stiffid_core::common::error::JobOption;
use stiffid_core::robot::external::ExternalValues;
use stiffid_core::{Error, Result};

/// Most stations one selection tries.
pub const MAX_STATIONS: usize = 100;

/// One station tried, and the value its group reached.
#[derive(Debug, Clone, PartialEq)]
pub struct Station {
    /// The external axis values (SI, the cell's order).
    pub e: ExternalValues,
    /// The value minimised for its group ([`Report::value`]).
    pub value: f64,
}

/// The selection at each of the request's stations, the best kept with every station's value
/// ([`Report::station`], [`Report::stations`]); `run` selects on one setup.
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::Station`]) for stations on a robot without external
/// axes, none on a robot with them, more than [`MAX_STATIONS`], or a station of another count
/// of values or outside the travel; those of `run`.
pub(super) fn at_stations(
    request: &Request,
    run: impl Fn(&Request) -> Result<Report>,
) -> Result<Report> {
    let tried = stations_of(request)?;
    let mut best: Option<Report> = None;
    let mut stations = Vec::with_capacity(tried.len());
    for e in &tried {
        let setup = setup_at(request, e)?;
        let report = run(&Request {
            setup: &setup,
            ..request.clone()
        })?;
        stations.push(Station {
            e: *e,
            value: report.value,
        });
        if best.as_ref().is_none_or(|b| report.value < b.value) {
            best = Some(Report {
                station: Some(*e),
                ..report
            });
        }
    }
    let mut best = best.expect("at least one station");
    best.stations = stations;
    Ok(best)
}

fn refuse(message: String) -> Error {
    Error::InvalidOption {
        option: JobOption::Station,
        message,
    }
}

/// The stations to try: the request's; on a cell whose only external axes are a positioner's
/// (the arm on a fixed base: the positioner moves the part, never the arm), none given means the
/// positioner at its zero, `e = 0` (its carried obstacles where the setup draws them).
///
/// # Errors
/// Those of [`checked`] for a cell with a carrier.
fn stations_of(request: &Request) -> Result<Vec<ExternalValues>> {
    let axes = request.setup.robot().external();
    match axes.filter(|a| request.stations.is_empty() && a.carrier_len() == 0) {
        Some(a) => Ok(vec![ExternalValues::new(&vec![0.0; a.len()])?]),
        None => checked(request).map(|_| request.stations.clone()),
    }
}

/// Refuses stations on a robot without external axes, none on a robot with them, or more
/// than [`MAX_STATIONS`].
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::Station`]).
pub(super) fn checked(request: &Request) -> Result<()> {
    let Some(axes) = request.setup.robot().external() else {
        return Err(refuse(
            "the robot has no external axes: give no station".into(),
        ));
    };
    if request.stations.is_empty() || request.stations.len() > MAX_STATIONS {
        return Err(refuse(format!(
            "the robot has external axes ({}): give 1 to {MAX_STATIONS} stations, each one value per axis in the cell's order",
            axes.column_names().join(", ")
        )));
    }
    Ok(())
}

/// The request's setup with the arm at station `e` ([`stiffid_core::Setup::at_station`]).
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::Station`]) for a station of another count of values
/// or outside the travel.
pub(super) fn setup_at(request: &Request, e: &ExternalValues) -> Result<stiffid_core::Setup> {
    request
        .setup
        .at_station(e.as_slice())
        .map_err(|error| match error {
            Error::InvalidField { field, message } => refuse(format!("{field}: {message}")),
            other => other,
        })
}
