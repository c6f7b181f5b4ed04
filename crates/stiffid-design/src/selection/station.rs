//! Where a robot on a track (or with other external axes) stands for the group: the design runs
//! with the arm at each requested station in the fixed cell ([`Setup::at_station`]), and the
//! station whose group has the smallest minimised value is kept ([`best`]).
//!
//! The design criteria of the stiffness identification do not change when the arm moves along a
//! straight track (the observation matrix is the same in any translated frame), but what the cell
//! allows does: the rope's anchor and the tracker stay where they are, so the load's direction,
//! the lines of sight and the obstacles differ from station to station, and so does the best
//! feasible group.

use stiffid_core::common::error::JobOption;
use stiffid_core::robot::external::ExternalValues;
use stiffid_core::{Error, Result, Setup};

/// Most stations one selection tries.
pub(crate) const MAX_STATIONS: usize = 100;

/// One station tried, and the value its group reached.
#[derive(Debug, Clone, PartialEq)]
pub struct Station {
    /// The external axis values (SI, the cell's order).
    pub e: ExternalValues,
    /// The value minimised for its group.
    pub value: f64,
}

/// The selection `run` at each station to try, the one of the smallest `value` kept (the first
/// of equal ones): its station, its result and every station's value in order. The stations
/// tried are those `given`; on a cell whose only external axes are a positioner's (the arm on a
/// fixed base: the positioner moves the part, never the arm), none given means the positioner
/// at its zero, `e = 0` (its carried obstacles where the setup draws them).
///
/// # Errors
/// Those of [`check`] for a cell with a carrier and of [`setup_at`]; those of `run`.
pub fn best<T>(
    setup: &Setup,
    given: &[ExternalValues],
    mut run: impl FnMut(&Setup) -> Result<T>,
    value: impl Fn(&T) -> f64,
) -> Result<(ExternalValues, T, Vec<Station>)> {
    let tried = stations(setup, given)?;
    let mut best: Option<(ExternalValues, T)> = None;
    let mut values = Vec::with_capacity(tried.len());
    for e in &tried {
        let found = run(&setup_at(setup, e)?)?;
        values.push(Station {
            e: *e,
            value: value(&found),
        });
        if best.as_ref().is_none_or(|b| value(&found) < value(&b.1)) {
            best = Some((*e, found));
        }
    }
    let (e, found) = best.expect("at least one station");
    Ok((e, found, values))
}

fn refuse(message: String) -> Error {
    Error::InvalidOption {
        option: JobOption::Station,
        message,
    }
}

/// The stations to try: those `given`; on a cell whose only external axes are a positioner's
/// (the arm on a fixed base: the positioner moves the part, never the arm), none given means the
/// positioner at its zero, `e = 0` (its carried obstacles where the setup draws them).
///
/// # Errors
/// Those of [`check`] for a cell with a carrier.
fn stations(setup: &Setup, given: &[ExternalValues]) -> Result<Vec<ExternalValues>> {
    let axes = setup.robot().external();
    match axes.filter(|a| given.is_empty() && a.carrier_len() == 0) {
        Some(a) => Ok(vec![ExternalValues::new(&vec![0.0; a.len()])?]),
        None => check(setup, given).map(|_| given.to_vec()),
    }
}

/// Refuses stations on a robot without external axes, none on a robot with them, or more
/// than `MAX_STATIONS`.
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::Station`]).
pub fn check(setup: &Setup, given: &[ExternalValues]) -> Result<()> {
    let Some(axes) = setup.robot().external() else {
        return Err(refuse(
            "the robot has no external axes: give no station".into(),
        ));
    };
    if given.is_empty() || given.len() > MAX_STATIONS {
        return Err(refuse(format!(
            "the robot has external axes ({}): give 1 to {MAX_STATIONS} stations, each one value per axis in the cell's order",
            axes.column_names().join(", ")
        )));
    }
    Ok(())
}

/// `setup` with the arm at station `e` ([`Setup::at_station`]).
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::Station`]) for a station of another count of values
/// or outside the travel.
pub fn setup_at(setup: &Setup, e: &ExternalValues) -> Result<Setup> {
    setup.at_station(e.as_slice()).map_err(|error| match error {
        Error::InvalidField { field, message } => refuse(format!("{field}: {message}")),
        other => other,
    })
}
