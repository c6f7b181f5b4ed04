//! The positioner's angles of a calibration group's table readings
//! ([`stiffid_design::selection::table`]): with reflectors on the positioner's table
//! (`[workpiece] reflectors_mm`), every posture of `select --for calibration` also reads the
//! table's reflectors, at angles chosen for the group on the calibration design
//! ([`purpose::design`]).

use super::{CalibrationReport, Report, Request};
use crate::app::purpose::{self, Purpose};
use stiffid_core::Result;
pub use stiffid_design::selection::table::CANDIDATE_ANGLES;
use stiffid_design::selection::table::{check_sights, table_angles, Group};

/// `report` with the positioner's angles of its table readings chosen
/// ([`stiffid_design::selection::table::table_angles`]), where each posture is read
/// ([`Report::placed`]) then holding them, and its value and calibration criteria those of the
/// group with them; `report` as it is unless `r` designs for [`Purpose::Calibration`] on a
/// setup with a positioner and table reflectors.
///
/// # Errors
/// Those of [`table_angles`] and [`purpose::design`].
pub(super) fn with_table(r: &Request, mut report: Report) -> Result<Report> {
    if r.purpose != Purpose::Calibration {
        return Ok(report);
    }
    let options = r.calibration.of(r.purpose);
    let group = Group {
        postures: &report.postures,
        station: report.station,
        placed: &report.placed,
    };
    let design = |setup: &stiffid_core::Setup| purpose::design(setup, &options);
    let criterion = options.criterion();
    let Some(table) = table_angles(r.setup, r.options.margin, criterion, design, group)? else {
        return Ok(report);
    };
    report.calibration = Some(CalibrationReport {
        criterion,
        options,
        criteria: table.criteria,
        weight: 1.0,
    });
    report.value = table.value;
    report.placed = table.placed;
    Ok(report)
}

/// Refuses, before any search, a calibration design on `r` with reflectors on the positioner's
/// table that no angle of the positioner can read at the first station asked for
/// ([`check_sights`]).
///
/// # Errors
/// Those of [`check_sights`].
pub(super) fn check(r: &Request) -> Result<()> {
    match r.purpose {
        Purpose::Calibration => check_sights(r.setup, r.stations.first().copied()),
        _ => Ok(()),
    }
}
