//! The positioner's angles of a calibration group: with reflectors on the positioner's table
//! (`[workpiece] reflectors_mm`), every posture of `select --for calibration` also reads the
//! table's reflectors, with the positioner at angles chosen for the group
//! ([`stiffid_design::observability::CalibrationDesign::choose_table_angles`]) on the calibration
//! design with the positioner's lines, offsets and the reflectors ([`purpose::design`]).
//!
//! The candidates are a grid of about [`CANDIDATE_ANGLES`] angles over the positioner's travel
//! ([`purpose::table_grid`]: the travel is a feasibility check by construction) and the
//! positioner's values the postures were designed at (so that each posture clears the boxes the
//! positioner carries at one candidate at least, its own), those with the
//! tracker's line of sight to a reflector through an obstacle of the cell left out (the sight
//! from the tracker's head to [`SIGHT_END`] before the reflector, where its nest and the table
//! are). The arm's own bodies are not checked against these sights. With boxes the positioner
//! carries (`[[cell.obstacle]] carried_by`), a posture is read only at a candidate where its
//! arm, its rope and its lines of sight clear those boxes turned there, by the cell's checks
//! with the design's margin ([`design_checker`]): the arm's postures are designed with the
//! boxes at rest, the table's angles then keep them clear of the arm.

use super::{CalibrationReport, Report, Request};
use crate::app::purpose::{self, Purpose};
use rayon::prelude::*;
use stiffid_core::cell::{capsule_box, Capsule, Part, Thing};
use stiffid_core::robot::external::{ExternalAxes, ExternalValues};
use stiffid_core::{Error, Result, Setup};
use stiffid_design::observability::Placed;
use stiffid_design::search::design_checker;

/// About how many candidate angles of the positioner a group's table readings are chosen among.
pub const CANDIDATE_ANGLES: usize = 64;

/// How far before a table reflector its line of sight is checked, m.
pub const SIGHT_END: f64 = 0.05;

/// `report` with the positioner's angles of its table readings chosen (module docs), where
/// each posture is read ([`Report::placed`]) then holding them, and its value and calibration
/// criteria those of the group with them; `report` as it is unless `r` designs for
/// [`Purpose::Calibration`] on a setup with a positioner and table reflectors (reflectors on a
/// fixed part are read as the campaign's steps say, at no angle to choose).
///
/// # Errors
/// [`Error::Input`] (`table`) when no candidate angle has clear lines of sight, a posture meets
/// a box the positioner carries at every candidate, or the chosen angles do not separate the
/// calibration's parameters; those of [`purpose::design`].
pub(super) fn with_table(r: &Request, mut report: Report) -> Result<Report> {
    let reflectors = r.setup.table_reflectors();
    let Some(axes) = (r.setup.robot().external()).filter(|a| a.len() > a.carrier_len()) else {
        return Ok(report);
    };
    if r.purpose != Purpose::Calibration || reflectors.is_empty() {
        return Ok(report);
    }
    let here = report.station.unwrap_or_else(|| axes.stations(1)[0]);
    let where_read: Vec<ExternalValues> = match report.placed.is_empty() {
        true => vec![here; report.postures.len()],
        false => report.placed.clone(),
    };
    // One station of a track: the design of the arm there with the positioner (the track's
    // own parameters need a campaign over its stations).
    let cut = match report.placed.is_empty() {
        true => axes.carrier_len(),
        false => 0,
    };
    let setup = match cut {
        0 => r.setup.clone(),
        _ => r.setup.at_carrier(here.as_slice())?,
    };
    let options = r.calibration.of(r.purpose);
    let design = purpose::design(&setup, &options)?;
    let placed: Vec<Placed> = (report.postures.iter().zip(&where_read))
        .map(|(q, e)| (*q, tail(e, cut)))
        .collect();
    let design_axes = setup.robot().external().expect("a positioner");
    let designed_at: Vec<ExternalValues> = (where_read.iter())
        .map(|w| joined(design_axes, &tail(&here, cut), &tail(w, cut)))
        .collect();
    let candidates = candidates(
        &setup,
        design_axes,
        &reflectors,
        &tail(&here, cut),
        &designed_at,
    );
    if candidates.is_empty() {
        return Err(no_sight());
    }
    let read_at = |at: &ExternalValues, table: &ExternalValues| {
        let e = joined(design_axes, &tail(at, cut), table);
        joined(axes, at, &lifted(at, &e, cut))
    };
    let allowed = clear_of_carried(r, &report.postures, &where_read, &candidates, read_at);
    if let Some(i) = (allowed.iter().flatten()).position(|a| !a.contains(&true)) {
        return Err(refused(format!("posture {} of the group meets a box the positioner carries (its arm, rope or a line of sight within the clearance) at every candidate angle with clear lines of sight to the reflectors: move the box, the reflectors or the tracker, or choose other postures", i + 1)));
    }
    let criterion = options.criterion();
    let count = placed.len();
    let choice =
        design.choose_table_angles(criterion, &placed, &candidates, count, allowed.as_deref())?;
    if !choice.value.is_finite() {
        return Err(refused(format!(
            "the {} postures with the table read at as many angles do not separate the calibration's {} parameters: choose more postures or reflectors",
            placed.len(),
            design.kept().len()
        )));
    }
    let placed: Vec<Placed> = (placed.iter().zip(&choice.chosen))
        .map(|((q, e), &c)| (*q, joined(design_axes, e, &candidates[c])))
        .collect();
    let angles: Vec<ExternalValues> = placed.iter().map(|p| p.1).collect();
    let with = design.with_table_angles(&angles)?;
    report.calibration = Some(CalibrationReport {
        criterion,
        options,
        criteria: with.evaluate_placed(&placed)?,
        weight: 1.0,
    });
    report.value = choice.value;
    report.placed = (where_read.iter().zip(&choice.chosen))
        .map(|(at, &c)| read_at(at, &candidates[c]))
        .collect();
    Ok(report)
}

/// Whether each posture (`postures[i]` read where `where_read[i]` puts the external axes) clears
/// the boxes the positioner carries with the table at each of `candidates` (`read_at`: the
/// cell's values of a reading there), by every check's pairs with such a box (module docs);
/// `None` when the cell carries none.
fn clear_of_carried(
    r: &Request,
    postures: &[nalgebra::Vector6<f64>],
    where_read: &[ExternalValues],
    candidates: &[ExternalValues],
    read_at: impl Fn(&ExternalValues, &ExternalValues) -> ExternalValues + Sync,
) -> Option<Vec<Vec<bool>>> {
    let obstacles = &r.setup.cell()?.obstacles;
    let carried = |t: Thing| matches!(t, Thing::Obstacle(i) if obstacles[i].carried_by.is_some());
    if !obstacles.iter().any(|o| o.carried_by.is_some()) {
        return None;
    }
    let checker = design_checker(r.setup, r.options.margin);
    let clear = |q: &nalgebra::Vector6<f64>, e: &ExternalValues| {
        (checker.margins_at(q, e.as_slice()).iter())
            .filter(|m| carried(m.between.0) || carried(m.between.1))
            .all(|m| m.margin >= 0.0)
    };
    let rows = (postures.par_iter().zip(where_read))
        .map(|(q, at)| {
            (candidates.iter())
                .map(|c| clear(q, &read_at(at, c)))
                .collect()
        })
        .collect();
    Some(rows)
}

/// `e` without its first `cut` values.
fn tail(e: &ExternalValues, cut: usize) -> ExternalValues {
    ExternalValues::new(&e.as_slice()[cut..]).expect("fewer axes")
}

/// `e` (the axes after the first `cut`) with the first `cut` values of `at` before it.
fn lifted(at: &ExternalValues, e: &ExternalValues, cut: usize) -> ExternalValues {
    let values: Vec<f64> = (at.as_slice()[..cut].iter())
        .chain(e.as_slice())
        .copied()
        .collect();
    ExternalValues::new(&values).expect("the cell's axes")
}

/// The carrier's values of `at` with the positioner's of `table`.
fn joined(axes: &ExternalAxes, at: &ExternalValues, table: &ExternalValues) -> ExternalValues {
    let mut e = at.as_slice().to_vec();
    let c = axes.carrier_len();
    e[c..].copy_from_slice(&table.as_slice()[c..]);
    ExternalValues::new(&e).expect("the cell's axes")
}

/// The candidate angles (module docs), the carrier at `here`, and the positioner's values
/// `designed_at` the postures were designed at (the boxes it carries there: every posture clears
/// them at its own), each with clear lines of sight to the reflectors.
fn candidates(
    setup: &Setup,
    axes: &ExternalAxes,
    reflectors: &[nalgebra::Vector3<f64>],
    here: &ExternalValues,
    designed_at: &[ExternalValues],
) -> Vec<ExternalValues> {
    let mut grid = purpose::table_grid(axes, CANDIDATE_ANGLES, here);
    for e in designed_at {
        if !grid.contains(e) {
            grid.push(*e);
        }
    }
    grid.into_iter()
        .filter(|e| sights_clear(setup, axes, reflectors, e))
        .collect()
}

/// Whether the tracker sees every reflector on the table with the external axes at `e` (module
/// docs): always without a tracker or a cell.
fn sights_clear(
    setup: &Setup,
    axes: &ExternalAxes,
    reflectors: &[nalgebra::Vector3<f64>],
    e: &ExternalValues,
) -> bool {
    let (Some(tracker), Some(cell)) = (setup.tracker(), setup.cell()) else {
        return true;
    };
    let pose = axes.positioner_pose(e.as_slice());
    let obstacles = cell.obstacles_at(setup.robot(), e.as_slice());
    reflectors.iter().all(|x| {
        let point = (pose * nalgebra::Point3::from(*x)).coords;
        let towards = tracker.position - point;
        let length = towards.norm();
        if length <= SIGHT_END {
            return true;
        }
        let sight = Capsule {
            part: Part::Tool,
            a: tracker.position,
            b: point + towards * (SIGHT_END / length),
            radius: 0.0,
        };
        obstacles.iter().all(|o| capsule_box(&sight, o) > 0.0)
    })
}

/// The refusal of a group's table readings with `message`.
fn refused(message: String) -> Error {
    Error::Input {
        source_name: "postures: the table's readings".into(),
        error: Box::new(Error::InvalidField {
            field: "table".into(),
            message,
        }),
    }
}

/// The refusal when no angle of the positioner has clear lines of sight to the reflectors.
fn no_sight() -> Error {
    refused("no angle of the positioner has clear lines of sight from the tracker to every reflector on the table: move the tracker or the reflectors".into())
}

/// Refuses, before any search, a calibration design on `r` with reflectors on the positioner's
/// table that no angle of the positioner can read: no candidate angle (module docs) at the
/// first station asked for (the cell's first without one) has clear lines of sight from the
/// tracker to every reflector. A cheap check (a line per reflector and candidate), where the
/// search would otherwise run its course first.
///
/// # Errors
/// [`Error::Input`] (`table`) as [`with_table`] for no clear line of sight.
pub(super) fn check(r: &Request) -> Result<()> {
    let reflectors = r.setup.table_reflectors();
    let Some(axes) = r.setup.robot().external() else {
        return Ok(());
    };
    if r.purpose != Purpose::Calibration
        || reflectors.is_empty()
        || axes.len() == axes.carrier_len()
    {
        return Ok(());
    }
    let here = (r.stations.first().copied()).unwrap_or_else(|| axes.stations(1)[0]);
    match candidates(r.setup, axes, &reflectors, &here, &[here]).is_empty() {
        true => Err(no_sight()),
        false => Ok(()),
    }
}
